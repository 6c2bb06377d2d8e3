// A team: Size adjacent GPU lanes of one warp that share one particle's work. The lanes walk the
// same neighbour rows together and split each row's candidates between them (lane r takes every
// Size-th from the r-th on), so they stay converged; sum() adds their partial sums. A small run
// thus puts several lanes on each particle instead of leaving most of the GPU idle
// (bench/NOTES.md #12). A team of one, the default and the CPU's, is a plain thread.
#pragma once

#include "core/config.h"

namespace weir {

template <int Size = 1>
struct Team {
    static_assert(Size == 1 || Size == 2 || Size == 4 || Size == 8, "a power of two in a warp");
    static constexpr int size = Size;
    int rank = 0;  // this lane's place in the team, 0 .. Size - 1

    // The lane's first candidate in a run: a constant for a team of one.
    WEIR_HD int first() const { return Size == 1 ? 0 : rank; }
    WEIR_HD bool leader() const { return Size == 1 || rank == 0; }

    // The sum of v over the team's lanes, on every lane. Every lane of the team must call it.
    WEIR_HD Real sum(Real v) const {
#if defined(__CUDA_ARCH__)
        if constexpr (Size > 1) {
            const unsigned lane = threadIdx.x & 31u;
            const unsigned mask = ((1u << Size) - 1u) << (lane & ~unsigned(Size - 1));
            for (int offset = Size / 2; offset > 0; offset /= 2) {
                v += __shfl_xor_sync(mask, v, offset);
            }
        }
#endif
        return v;
    }

    // The largest v over the team's lanes, on every lane. Every lane of the team must call it.
    WEIR_HD Real max(Real v) const {
#if defined(__CUDA_ARCH__)
        if constexpr (Size > 1) {
            const unsigned lane = threadIdx.x & 31u;
            const unsigned mask = ((1u << Size) - 1u) << (lane & ~unsigned(Size - 1));
            for (int offset = Size / 2; offset > 0; offset /= 2) {
                const Real other = __shfl_xor_sync(mask, v, offset);
                v = other > v ? other : v;
            }
        }
#endif
        return v;
    }
};

}  // namespace weir
