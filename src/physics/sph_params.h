// Every number the step needs, derived once from the scene (scene/derive.cpp) and passed by
// value to the stages.
#pragma once

#include "core/config.h"
#include "core/vec3.h"
#include "physics/kernels.h"

namespace weir {

enum class IntegratorKind : int { SemiImplicitEuler = 0, ExplicitEuler = 1 };

struct SphParams {
    KernelCoefficients kernel;
    Real mass = 0;                      // per particle, kg
    Real restDensity = 0;               // rho0, kg/m^3
    Real stiffness = 0;                 // k of eq. 3, m^2/s^2
    bool clampNegativePressure = true;  // P = max(0, k (rho - rho0)) when set
    Real viscosity = 0;                 // mu of eq. 5, Pa s
    Vec3 gravity;                       // m/s^2
    Real timeStep = 0;                  // s
    IntegratorKind integrator = IntegratorKind::SemiImplicitEuler;

    Vec3 boxMin, boxMax;   // container walls
    Real restitution = 0;  // normal speed kept after a wall contact
    Real friction = 0;     // share of tangential speed removed on contact
    Real maxSpeed = 0;     // blow-up bound, m/s
};

}  // namespace weir
