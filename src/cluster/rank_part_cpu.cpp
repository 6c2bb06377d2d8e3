// A rank's part on the CPU backend, and the choice of backend.
#include "cluster/rank_part_on.h"
#include "core/exec_cpu.h"

namespace weir {

template class RankPartOn<CpuExec>;

#if defined(WEIR_HAS_CUDA)
std::unique_ptr<RankPart> makeCudaRankPart(NeighbourMode mode, SimulationSetup setup);
#endif

std::unique_ptr<RankPart> makeRankPart(Backend backend, NeighbourMode mode, SimulationSetup setup) {
    mode = resolveNeighbourMode(mode, setup.grid, setup.particleCount());
    setup.method = checkPressureSolver(setup.method);
    const std::size_t idBytes = cellIdBytesFor(setup.grid);
    if (backend == Backend::Cpu) {
        checkMemoryFits(Index(setup.countHere()), mode, CpuExec().freeMemoryBytes(), "host memory",
                        idBytes);
        return std::make_unique<RankPartOn<CpuExec>>(mode, std::move(setup));
    }
#if defined(WEIR_HAS_CUDA)
    if (!cudaDeviceAvailable()) {
        throw SimulationError("the cuda backend was asked for, but no CUDA device is visible");
    }
    return makeCudaRankPart(mode, std::move(setup));
#else
    throw SimulationError("the cuda backend was asked for, but this weir was built without CUDA");
#endif
}

}  // namespace weir
