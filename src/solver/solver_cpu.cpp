// The simulation instantiated on the CPU backend (OpenMP).
#include "core/exec_cpu.h"
#include "solver/sph_simulation.h"

namespace weir {

template class SphSimulation<CpuExec>;

std::unique_ptr<Simulation> makeCpuSimulation(NeighbourMode mode, SimulationSetup setup) {
    return std::make_unique<SphSimulation<CpuExec>>(mode, std::move(setup));
}

}  // namespace weir
