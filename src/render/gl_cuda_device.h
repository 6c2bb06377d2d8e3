// Whether CUDA can write into the current OpenGL context's buffers and textures directly
// (CUDA-OpenGL interop): only where that context runs on the current CUDA device. CUDA builds only
// (defined in particle_interop_cuda.cu).
#pragma once

#include <string>

namespace weir {

// True where the current OpenGL context runs on the current CUDA device; else false, and `why`
// says why (Mesa's software renderer, or another GPU).
bool openGlRunsOnCurrentCudaDevice(std::string& why);

}  // namespace weir
