// Why a run had to stop: the first particle to fail records itself on the device, and the host
// reads the record back between frames (solver/simulation.h turns it into a diagnosis).
#pragma once

#include "core/config.h"

namespace weir {

// Compressed: a density past the bound (physics/sph_params.h maxDensityRatio); Collapsed: two
// particles on the same point (the kernel then pushes them apart no more).
enum class FaultCode : int {
    None = 0,
    NotFinite = 1,
    TooFast = 2,
    Escaped = 3,
    Compressed = 4,
    Collapsed = 5
};

struct FaultRecord {
    int code;       // FaultCode
    int step;       // step number at which it happened
    int particle;   // index in cell order at that step
    float value;    // speed for TooFast, rho / rho0 for Compressed
    float time;     // simulated time at the end of that step, s
    float x, y, z;  // where the particle was, m
};

// True for the one thread that records the run's first fault.
WEIR_HD inline bool claimFault(FaultRecord* record, FaultCode code) {
#if defined(__CUDA_ARCH__)
    return atomicCAS(&record->code, 0, int(code)) == 0;
#else
    int expected = 0;
    return __atomic_compare_exchange_n(&record->code, &expected, int(code), false, __ATOMIC_RELAXED,
                                       __ATOMIC_RELAXED);
#endif
}

}  // namespace weir
