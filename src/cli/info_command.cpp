// `weir info`: the build, the backends and the GPU found.
#include <iostream>

#include "cli/commands.h"
#include "core/backend.h"
#include "core/config.h"
#include "grid/cell_id.h"
#include "scene/scene.h"

namespace weir {

int infoCommand() {
    std::cout << "weir " << WEIR_VERSION << "\n";
    std::cout << "precision: " << (sizeof(Real) == 8 ? "double" : "float") << "\n";
#if defined(WEIR_HAS_CUDA)
    std::cout << "cuda backend: built in\n";
#else
    std::cout << "cuda backend: not built (no nvcc at configure time)\n";
#endif
    std::cout << "cpu: " << describeBackend(Backend::Cpu) << "\n";
    std::cout << "gpu: " << describeBackend(Backend::Cuda) << "\n";
    std::cout << "auto backend picks: " << backendName(parseBackend("auto")) << "\n";
    std::cout << "grid cell ids: 32-bit (" << kCellBitsPerAxis << " bits per axis) up to "
              << kMaxCellsPerAxis << " cells per axis, 64-bit ("
              << CellIdLayout<WideCellKey>::bitsPerAxis << " bits per axis) past that\n";
    std::cout << "built-in scenes:";
    for (const std::string& name : builtinSceneNames()) {
        std::cout << " " << name;
    }
    std::cout << "\n";
    return kExitOk;
}

}  // namespace weir
