// A team: a few adjacent GPU lanes of one warp that share one particle's work. Each lane walks
// its share of the neighbour rows and sum() adds the lanes' partial sums, so a small run puts
// several lanes on each particle instead of leaving most of the GPU idle (bench/NOTES.md #12).
// A team of one, the default and the CPU's, is a plain thread.
#pragma once

#include "core/config.h"

namespace weir {

struct Team {
    int rank = 0;  // this lane's place in the team, 0 .. size - 1
    int size = 1;  // 1, 2, 4 or 8 (a power of two within a warp)

    WEIR_HD bool leader() const { return rank == 0; }
    // Whether this lane takes the k-th piece of work (pieces dealt in turn).
    WEIR_HD bool takes(int k) const { return (k & (size - 1)) == rank; }

    // The sum of v over the team's lanes, on every lane. Every lane of the team must call it.
    WEIR_HD Real sum(Real v) const {
#if defined(__CUDA_ARCH__)
        if (size > 1) {
            const unsigned lane = threadIdx.x & 31u;
            const unsigned mask = ((1u << size) - 1u) << (lane & ~unsigned(size - 1));
            for (int offset = size / 2; offset > 0; offset /= 2) {
                v += __shfl_xor_sync(mask, v, offset);
            }
        }
#endif
        return v;
    }
};

// log2 of a team size, for splitting a thread index into particle and rank.
WEIR_HD constexpr int teamShift(int size) { return size >= 8 ? 3 : (size >= 4 ? 2 : (size >= 2 ? 1 : 0)); }

}  // namespace weir
