// A rank's part on the CUDA backend.
#include "cluster/rank_part_on.h"
#include "core/exec_cuda.cuh"

namespace weir {

template class RankPartOn<CudaExec>;

std::unique_ptr<RankPart> makeCudaRankPart(NeighbourMode mode, SimulationSetup setup) {
    CudaExec probe;
    checkMemoryFits(Index(setup.countHere()), mode, probe.freeMemoryBytes(), "the GPU",
                    cellIdBytesFor(setup.grid));
    return std::make_unique<RankPartOn<CudaExec>>(mode, std::move(setup));
}

}  // namespace weir
