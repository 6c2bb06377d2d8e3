// `weir info`: the build (version, precision, the features built in), the backends, the CPU and
// the GPU found, the OpenMP wait policy and the built-in scenes.
#include <cstdlib>
#include <iostream>
#include <string>

#include "cli/commands.h"
#include "core/backend.h"
#include "core/config.h"
#include "grid/cell_id.h"
#include "io/optional_formats.h"
#include "scene/scene.h"

namespace weir {

namespace {

void feature(const char* name, bool built, const std::string& what) {
    std::cout << "  " << name << ": " << (built ? "yes" : "no") << " (" << what << ")\n";
}

constexpr bool kCuda =
#if defined(WEIR_HAS_CUDA)
    true;
#else
    false;
#endif
constexpr bool kMpi =
#if defined(WEIR_HAS_MPI)
    true;
#else
    false;
#endif
constexpr bool kNccl =
#if defined(WEIR_HAS_NCCL)
    true;
#else
    false;
#endif

}  // namespace

int infoCommand(bool renderingBuilt) {
    std::cout << "weir " << WEIR_VERSION << " (commit " << WEIR_COMMIT << ")\n";
    std::cout << "precision: " << (sizeof(Real) == 8 ? "double" : "float") << "\n";
#if defined(WEIR_HAS_CUDA)
    std::cout << "cuda backend: built in\n";
#else
    std::cout << "cuda backend: not built (no nvcc at configure time)\n";
#endif
    std::cout << "built in:\n";
    feature("CUDA backend", kCuda,
            kCuda ? "--backend cuda" : "no nvcc when it was configured; see README, Quick start");
    feature("rendering", renderingBuilt,
            renderingBuilt ? "weir render, weir view, run --render: OpenGL 3.3, EGL, GLFW, libpng"
                           : "OpenGL, EGL, GLFW or libpng not found when it was configured");
    feature("MPI", kMpi, kMpi ? "mpirun -n R weir run: docs/cluster.md" : "MPI not found");
    feature("NCCL", kNccl,
            kNccl ? "GPU-to-GPU halo exchange" : "needs CUDA, MPI and NCCL; halos go via the host");
    feature("OpenVDB", openVdbBuilt(),
            openVdbBuilt() ? "--format vdb: level set, velocity and point grids (docs/pipeline.md)"
                           : "libopenvdb-dev not found when it was configured");
    feature("double precision", sizeof(Real) == 8,
            sizeof(Real) == 8 ? "double particle data" : "float particle data; -DWEIR_DOUBLE=ON");
    std::cout << "cpu: " << describeBackend(Backend::Cpu) << "\n";
    std::cout << "gpu: " << describeBackend(Backend::Cuda) << "\n";
    std::cout << "auto backend picks: " << backendName(parseBackend("auto")) << "\n";
    const char* policy = std::getenv("OMP_WAIT_POLICY");
    std::cout << "OpenMP wait policy: " << (policy != nullptr ? policy : "the runtime's default")
              << (std::getenv("WEIR_SET_OMP_WAIT_POLICY") != nullptr
                      ? " (weir's default: waiting threads sleep; OMP_WAIT_POLICY=active spins)"
                      : " (from OMP_WAIT_POLICY)")
              << "\n";
    std::cout << "grid cell ids: 32-bit (" << kCellBitsPerAxis << " bits per axis) up to "
              << kMaxCellsPerAxis << " cells per axis, 64-bit ("
              << CellIdLayout<WideCellKey>::bitsPerAxis << " bits per axis) past that\n";
    std::cout << "fluid model: delta-sph by default (Wendland C2, continuity density with "
                 "density diffusion, the fluid's own viscosity, particle shifting, boundary "
                 "particles); \"fluid\": {\"model\": \"paper\"} for Müller et al. 2003 as the "
                 "paper has it (weir bench times it)\n";
    std::cout << "built-in scenes:";
    for (const std::string& name : builtinSceneNames()) {
        std::cout << " " << name;
    }
    std::cout << "\n";
    return kExitOk;
}

}  // namespace weir
