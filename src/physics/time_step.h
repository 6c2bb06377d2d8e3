// The adaptive time step, chosen on the device every step with no host round trip, so that a
// step stays capturable in a CUDA graph. The integration stage records the largest speed and
// acceleration it produced into a device-side StepClock (one warp-aggregated atomic max per warp
// on the GPU, a rarely-taken compare-and-swap on the CPU); a one-thread stage at the start of
// the next step turns them into dt by the CFL, force and viscous conditions, cut so that the
// last step before an output time lands on it exactly. The acceleration is the previous step's
// (its force pass fuses integration on the dense path): SPH accelerations change over many
// steps except at impacts, and the CFL condition with c = 10 v_max is the binding one.
#pragma once

#include <cmath>
#include <cstring>

#include "core/config.h"
#include "physics/sph_params.h"

namespace weir {

// Lives in device memory; the host reads it only between frames.
struct StepClock {
    double time;         // simulated time, s
    double target;       // the next output time: steps stop on it (dt = 0 once there)
    Real dt;             // the current step's dt; 0 makes the step a no-op
    unsigned maxSpeed2;  // bits of the largest |v|^2 (a non-negative float) of the last step
    unsigned maxAccel2;  // bits of the largest |a|^2
    int step;            // steps taken (no-op steps not counted)
    int landing;         // this step ends on the target
};

WEIR_HD inline unsigned floatBits(float f) {
#if defined(__CUDA_ARCH__)
    return __float_as_uint(f);
#else
    unsigned u;
    std::memcpy(&u, &f, sizeof u);
    return u;
#endif
}
WEIR_HD inline float bitsFloat(unsigned u) {
#if defined(__CUDA_ARCH__)
    return __uint_as_float(u);
#else
    float f;
    std::memcpy(&f, &u, sizeof f);
    return f;
#endif
}

// slot = max(slot, value) for value >= 0 (non-negative floats order like their bits).
WEIR_HD inline void recordMax(unsigned* slot, Real value) {
    const unsigned bits = floatBits(float(value));
#if defined(__CUDA_ARCH__)
#if __CUDA_ARCH__ >= 800
    // One atomic per warp, and none once the warp's maximum is below the recorded one.
    const unsigned active = __activemask();
    const unsigned warpMax = __reduce_max_sync(active, bits);
    if ((threadIdx.x & 31u) == unsigned(__ffs(active) - 1) &&
        warpMax > *static_cast<volatile unsigned*>(slot)) {
        atomicMax(slot, warpMax);
    }
#else
    if (bits > *static_cast<volatile unsigned*>(slot)) {
        atomicMax(slot, bits);
    }
#endif
#else
    unsigned seen = __atomic_load_n(slot, __ATOMIC_RELAXED);
    while (bits > seen && !__atomic_compare_exchange_n(slot, &seen, bits, true, __ATOMIC_RELAXED,
                                                       __ATOMIC_RELAXED)) {
    }
#endif
}

// The stable step for the recorded speed and acceleration (or the fixed one).
WEIR_HD inline Real stableTimeStep(const SphParams& p, const StepClock& clock) {
    if (!p.adaptiveTimeStep) {
        return p.timeStep;
    }
    const Real h = p.kernel.h;
    Real vMax = std::sqrt(Real(bitsFloat(clock.maxSpeed2)));
    vMax = vMax > p.minCflSpeed ? vMax : p.minCflSpeed;
    const Real aMax = std::sqrt(Real(bitsFloat(clock.maxAccel2)));
    Real dt = p.cflNumber * h / (p.speedOfSound + vMax);
    if (aMax > Real(0)) {
        dt = fmin(dt, p.forceNumber * std::sqrt(h / aMax));
    }
    return fmin(fmin(dt, p.viscousLimit), p.maxTimeStep);
}

// Start of a step (one thread): this step's dt, cut to land on the target; 0 once there.
WEIR_HD inline void beginStep(StepClock& clock, const SphParams& p) {
    const double remaining = clock.target - clock.time;
    if (!(remaining > 0)) {
        clock.dt = 0;
        return;
    }
    double dt = double(stableTimeStep(p, clock));
    if (!(dt > 0)) {
        dt = double(p.timeStep);  // NaN from a blown-up state: the fault check reports it
    }
    clock.landing = dt >= remaining * (1 - 1e-6);
    if (clock.landing) {
        dt = remaining;  // the last step lands on the output time
    } else if (dt > 0.5 * remaining) {
        dt = 0.5 * remaining;  // two even steps rather than one and a sliver
    }
    clock.dt = Real(dt);
    clock.maxSpeed2 = 0;
    clock.maxAccel2 = 0;
}

// End of a step (one thread): the clock moves on, exactly onto the target when cut to it.
WEIR_HD inline void endStep(StepClock& clock) {
    if (clock.dt > Real(0)) {
        clock.time = clock.landing ? clock.target : clock.time + double(clock.dt);
        ++clock.step;
    }
}

}  // namespace weir
