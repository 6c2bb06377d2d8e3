// Atomic read-modify-write usable in code written once for the CPU (OpenMP) and CUDA.
#pragma once

#include "core/config.h"

namespace weir {

// Adds v to *target and returns the previous value (relaxed order: a counter, not a lock).
WEIR_HD inline Index atomicFetchAdd(Index* target, Index v) {
#if defined(__CUDA_ARCH__)
    return atomicAdd(target, v);
#else
    return __atomic_fetch_add(target, v, __ATOMIC_RELAXED);
#endif
}

}  // namespace weir
