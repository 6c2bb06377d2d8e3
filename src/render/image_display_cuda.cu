// CUDA-OpenGL interop for the image display: the texture registered with CUDA once, mapped each
// frame, the device image copied into its array (a device-to-device copy), unmapped for drawing.
// cuda_gl_interop.h brings its own GL header; this file uses no GL call, only the texture's name.
#include <cuda_gl_interop.h>

#include "core/exec_cuda.cuh"
#include "render/gl_cuda_device.h"
#include "render/image_display.h"

namespace weir {

namespace {

constexpr unsigned kTexture2d = 0x0DE1;  // GL_TEXTURE_2D

class CudaImageInterop : public ImageInterop {
   public:
    explicit CudaImageInterop(unsigned texture) {
        WEIR_CUDA_CHECK(cudaGraphicsGLRegisterImage(&resource_, texture, kTexture2d,
                                                    cudaGraphicsRegisterFlagsWriteDiscard));
    }
    ~CudaImageInterop() override {
        if (resource_ != nullptr) {
            cudaGraphicsUnregisterResource(resource_);
        }
    }

    void copy(const std::uint8_t* deviceRgba, int width, int height) override {
        WEIR_CUDA_CHECK(cudaGraphicsMapResources(1, &resource_, 0));
        cudaArray_t array = nullptr;
        WEIR_CUDA_CHECK(cudaGraphicsSubResourceGetMappedArray(&array, resource_, 0, 0));
        // Rows from the top go to texture rows from the bottom as they are: the display's
        // shader reads the texture upside down.
        const std::size_t row = 4 * std::size_t(width);
        WEIR_CUDA_CHECK(cudaMemcpy2DToArray(array, 0, 0, deviceRgba, row, row, std::size_t(height),
                                            cudaMemcpyDeviceToDevice));
        WEIR_CUDA_CHECK(cudaGraphicsUnmapResources(1, &resource_, 0));
    }

   private:
    cudaGraphicsResource* resource_ = nullptr;
};

}  // namespace

std::unique_ptr<ImageInterop> makeImageInterop(unsigned texture, std::string* why) {
    auto say = [&](const std::string& reason) {
        if (why != nullptr) {
            *why = reason;
        }
        return nullptr;
    };
    std::string reason;
    if (!openGlRunsOnCurrentCudaDevice(reason)) {
        return say(reason);
    }
    return std::make_unique<CudaImageInterop>(texture);
}

}  // namespace weir
