// The SPH solver instantiated on the CPU backend (OpenMP).
#include "core/exec_cpu.h"
#include "solver/sph_solver.h"

namespace weir {

template class SphSolver<CpuExec>;

std::unique_ptr<RankPart> makeCpuSimulation(NeighbourMode mode, SimulationSetup setup) {
    return std::make_unique<SphSolver<CpuExec>>(mode, std::move(setup));
}

}  // namespace weir
