// The SPH solver instantiated on the CUDA backend: the same stages, one thread per particle.
#include "core/exec_cuda.cuh"
#include "solver/sph_solver.h"

namespace weir {

template class SphSolver<CudaExec>;

std::unique_ptr<RankPart> makeCudaSimulation(NeighbourMode mode, SimulationSetup setup) {
    CudaExec probe;
    checkMemoryFits(Index(setup.countHere()), mode, probe.freeMemoryBytes(), "the GPU",
                    cellIdBytesFor(setup.grid));
    return std::make_unique<SphSolver<CudaExec>>(mode, std::move(setup));
}

}  // namespace weir
