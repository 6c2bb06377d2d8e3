// Moving one particle over a step: the integrator, the collision response, the blow-up checks
// and the largest speed and acceleration for the next step's dt, shared by every method.
#pragma once

#include <cmath>

#include "core/config.h"
#include "core/vec3.h"
#include "physics/collision.h"
#include "physics/faults.h"
#include "physics/sph_params.h"
#include "physics/time_step.h"

namespace weir {

// Time integration of one particle over the clock's dt (semi-implicit Euler by default; the
// paper's explicit Euler selectable), collision response, the blow-up checks, and the largest
// speed and acceleration for the next step's dt; updates x and v in place. A method whose
// pressure is implicit (DFSPH) passes recordAcceleration false and records its explicit forces
// itself: its dt must not shrink with the pressure it solves for.
WEIR_HD inline void advanceParticle(Vec3& x, Vec3& v, const Vec3& a, Index i,
                                    const SphParams& params, const ObstacleView& obstacles,
                                    FaultRecord* fault, StepClock* clock,
                                    bool recordAcceleration = true) {
    const Real dt = clock->dt;
    if (params.integrator == IntegratorKind::SemiImplicitEuler) {
        v += a * dt;
        x += v * dt;
    } else {
        x += v * dt;
        v += a * dt;
    }
    collide(x, v, params, obstacles);
    if (params.periodicAxes != 0) {
        wrapPeriodic(x, params);
    }

    const Real speed2 = lengthSquared(v);
    recordMax(&clock->maxSpeed2, speed2);
    if (recordAcceleration) {
        recordMax(&clock->maxAccel2, lengthSquared(a));
    }
    const bool finite =
        std::isfinite(x.x) && std::isfinite(x.y) && std::isfinite(x.z) && std::isfinite(speed2);
    FaultCode code = FaultCode::None;
    if (!finite) {
        code = FaultCode::NotFinite;
    } else if (speed2 > params.maxSpeed * params.maxSpeed) {
        code = FaultCode::TooFast;
    } else if (x.x < params.boxMin.x || x.y < params.boxMin.y || x.z < params.boxMin.z ||
               x.x > params.boxMax.x || x.y > params.boxMax.y || x.z > params.boxMax.z) {
        code = FaultCode::Escaped;
    }
    if (code != FaultCode::None && claimFault(fault, code)) {
        fault->step = clock->step;
        fault->particle = i;
        fault->value = float(std::sqrt(speed2));
        fault->time = float(clock->time + double(dt));
        fault->x = float(x.x);
        fault->y = float(x.y);
        fault->z = float(x.z);
    }
}

// Records a fault for a density past the bound or particles on one point (the first fault of the
// run wins; dt of the current step for its time); x is where the particle is.
WEIR_HD inline void checkDensity(Real rho, bool collapsed, Index i, const Vec3& x,
                                 const SphParams& params, FaultRecord* fault,
                                 const StepClock* clock) {
    FaultCode code = FaultCode::None;
    if (collapsed) {
        code = FaultCode::Collapsed;
    } else if (params.maxDensityRatio > Real(0) &&
               !(rho <= params.maxDensityRatio * params.restDensity)) {
        code = FaultCode::Compressed;
    }
    if (code != FaultCode::None && claimFault(fault, code)) {
        fault->step = clock->step;
        fault->particle = i;
        fault->value = float(rho * params.invRestDensity);
        fault->time = float(clock->time + double(clock->dt));
        fault->x = float(x.x);
        fault->y = float(x.y);
        fault->z = float(x.z);
    }
}

}  // namespace weir
