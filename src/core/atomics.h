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

// Stores v at *target where other threads may store the same value at the same time (a flag).
WEIR_HD inline void atomicStoreFlag(std::int32_t* target, std::int32_t v) {
#if defined(__CUDA_ARCH__)
    *reinterpret_cast<volatile std::int32_t*>(target) = v;
#else
    __atomic_store_n(target, v, __ATOMIC_RELAXED);
#endif
}

}  // namespace weir
