// Surface reconstruction instantiated on the CUDA backend: the same stages, one thread per
// sample or cell.
#include "core/exec_cuda.cuh"
#include "surface/surface_pipeline.h"

namespace weir {

template TriangleMesh extractSurface<CudaExec>(CudaExec&, const HostParticles&, const SurfacePlan&,
                                               const char*, StageTimes*);
// The live water look's path (raytrace/interactive_water.cu): particles on the GPU to a mesh
// kept there.
template std::int64_t extractSurfaceInto<CudaExec>(CudaExec&, const Real4*, Index,
                                                   const SurfacePlan&, const char*,
                                                   BackendMesh<CudaExec>&, StageTimes*);

TriangleMesh reconstructSurfaceCuda(const HostParticles& particles, const SurfacePlan& plan,
                                    StageTimes* stages) {
    if (!cudaDeviceAvailable()) {
        throw SurfaceError("no CUDA device is visible; use the cpu backend");
    }
    CudaExec exec;
    return extractSurface(exec, particles, plan, "the GPU", stages);
}

}  // namespace weir
