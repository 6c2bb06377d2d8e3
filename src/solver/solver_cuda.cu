// The simulation instantiated on the CUDA backend: the same stages, one thread per particle.
#include "core/exec_cuda.cuh"
#include "solver/sph_simulation.h"

namespace weir {

template class SphSimulation<CudaExec>;

std::unique_ptr<Simulation> makeCudaSimulation(NeighbourMode mode, SimulationSetup setup) {
    CudaExec probe;
    checkMemoryFits(Index(setup.countHere()), mode, probe.freeMemoryBytes(), "the GPU",
                    cellIdBytesFor(setup.grid));
    return std::make_unique<SphSimulation<CudaExec>>(mode, std::move(setup));
}

}  // namespace weir
