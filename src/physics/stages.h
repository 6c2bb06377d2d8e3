// The per-particle stages of the SPH step (paper §6.3), written once for CPU and CUDA.
// Each stage reads whatever it needs and writes only particle i's own outputs.
#pragma once

#include <cmath>

#include "core/config.h"
#include "core/team.h"
#include "core/vec3.h"
#include "physics/boundary.h"
#include "physics/eos.h"
#include "physics/kernels.h"
#include "physics/sph_params.h"
#include "physics/time_step.h"
#include "physics/wall_weight.h"

namespace weir {

// Structure-of-arrays particle data by attribute, in the grid's cell order. Vector attributes
// are padded to four components: one aligned 16-byte load per neighbour on the GPU. The density
// rides in the velocity's fourth component, so the force loop reads two vectors per neighbour
// (pressure follows from density by eq. 3); the density stage reads only positions, so writing
// it there races with nothing.
struct ParticleView {
    Real4* pos;          // x, y, z, ghost flag (isGhost)
    Real4* vel;          // vx, vy, vz, density
    Real4* acc;          // ax, ay, az, unused
    Real* pressureTerm;  // pressureTermOf(density), by the density stage for the force stage
    Index count;
    BoundaryView boundary;  // static wall particles (physics/boundary.h); empty: none

    WEIR_HD Real density(Index i) const { return vel[i].w; }
    WEIR_HD Vec3 position(Index i) const { return pos[i].xyz(); }
    WEIR_HD Vec3 velocity(Index i) const { return vel[i].xyz(); }
};

struct ObstacleBox {
    Vec3 min, max;
};
struct ObstacleSphere {
    Vec3 center;
    Real radius;
};
struct ObstacleView {
    const ObstacleBox* boxes;
    int boxCount;
    const ObstacleSphere* spheres;
    int sphereCount;
};

// A ghost is a copy of another rank's particle near this rank's border (distributed runs,
// cluster/): it lends its density and velocity to the owned particles' sums but is neither
// moved, nor checked, nor counted in the time step here; its owner does that.
// pos.w marks them: 1 a ghost of this step, 2 one just arrived for the next step (the grid build
// turns it into 1 and drops the 1s of the step before).
constexpr Real kGhostMark = 1;
constexpr Real kArrivingGhostMark = 2;
WEIR_HD inline bool isGhost(const Real4& pos) { return pos.w != Real(0); }

// Why a run had to stop. The first particle to fail records itself; the host reads it back.
enum class FaultCode : int { None = 0, NotFinite = 1, TooFast = 2, Escaped = 3 };
struct FaultRecord {
    int code;      // FaultCode
    int step;      // step number at which it happened
    int particle;  // index in cell order at that step
    float value;   // speed, for TooFast
    float time;    // simulated time at the end of that step, s
};

WEIR_HD inline bool claimFault(FaultRecord* record, FaultCode code) {
#if defined(__CUDA_ARCH__)
    return atomicCAS(&record->code, 0, int(code)) == 0;
#else
    int expected = 0;
    return __atomic_compare_exchange_n(&record->code, &expected, int(code), false, __ATOMIC_RELAXED,
                                       __ATOMIC_RELAXED);
#endif
}

// What the force stage needs of a neighbour's pressure: p / rho^2 for the symmetric pressure
// force, p for the paper's eq. 4 (see pairForce). Computed once per particle by the density
// stage rather than once per pair: the equation of state is a quarter of the pair's arithmetic.
WEIR_HD inline Real pressureTermOf(const SphParams& params, Real rho) {
    const Real p = pressureFromDensity(params, rho);
    return params.pressureForce == PressureForm::Symmetric ? p / (rho * rho) : p;
}

// Eq. 2 with poly6: density of particle i (its pressure follows by eq. 3 where it is needed).
// One thread per particle: teams measured slower here (bench/NOTES.md #12, #14).
template <class Neighbours>
WEIR_HD inline void densityPressureAt(Index i, const ParticleView& pv, const Neighbours& nb,
                                      const SphParams& params) {
    const Vec3 xi = pv.position(i);
    Real sum = 0;
    nb.forEachCandidate(
        i, [&](Index j) { sum += poly6(params.kernel, lengthSquared(xi - pv.position(j))); });
    const Real walls =
        params.walls == WallKind::Simple
            ? wallDensity(params.wallWeight, params.boxMin, params.boxMax, params.restDensity, xi)
            : boundaryDensity(pv.boundary, params.kernel, xi);
    const Real rho = params.mass * sum + walls;
    pv.vel[i].w = rho;
    pv.pressureTerm[i] = pressureTermOf(params, rho);
}

// The pressure (spiky gradient) and viscous (eq. 5, its Laplacian) force density on i from j,
// for r_vec = x_i - x_j and 0 < r < h. Pressure by the paper's eq. 4, m_j (p_i + p_j) / (2 rho_j),
// or by the symmetric form rho_i m_j (p_i / rho_i^2 + p_j / rho_j^2) (Monaghan 1992): both
// conserve momentum, but only the latter tends to grad p as particles get finer; eq. 4 tends to
// grad p / 2 (its p_i term vanishes over a full neighbourhood), so a tank at rest under eq. 4
// holds twice the hydrostatic pressure. termI, termJ: pressureTermOf the two densities, so the
// symmetric form is m_j rho_i (termI + termJ).
WEIR_HD inline Vec3 pairForce(const SphParams& params, const Vec3& rVec, Real r, Real invR,
                              Real termI, Real termJ, Real rhoi, Real rhoj, const Vec3& vi,
                              const Vec3& vj) {
    const Real massOverRho = params.mass * reciprocal(rhoj);
    const Real pressureDensity = params.pressureForce == PressureForm::Symmetric
                                     ? params.mass * rhoi * (termI + termJ)
                                     : massOverRho * Real(0.5) * (termI + termJ);
    Real pressure = -pressureDensity * spikyGradientFactor(params.kernel, r, invR);
    Real viscous = params.viscosity * massOverRho * viscosityLaplacian(params.kernel, r);
    return rVec * pressure + (vj - vi) * viscous;
}

// Acceleration of particle i: (pressure + viscous force density) / rho_i + gravity. A team
// (core/team.h) shares the neighbours, and every lane gets the whole acceleration.
template <class Neighbours, int TeamSize = 1>
WEIR_HD inline Vec3 accelerationOf(Index i, const ParticleView& pv, const Neighbours& nb,
                                   const SphParams& params, Team<TeamSize> team = {}) {
    const Vec3 xi = pv.position(i);
    const Real4 vi = pv.vel[i];
    const Real rhoi = vi.w, pi = pressureFromDensity(params, rhoi), h2 = params.kernel.h2;
    const Real termI = pv.pressureTerm[i];
    Vec3 force;
    nb.forEachCandidate(
        i,
        [&](Index j) {
            Vec3 rVec = xi - pv.position(j);
            Real r2 = lengthSquared(rVec);
            if (r2 < h2 && r2 > Real(0)) {
                const Real4 vj = pv.vel[j];
                const Real invR = reciprocalSqrt(r2);
                force += pairForce(params, rVec, r2 * invR, invR, termI, pv.pressureTerm[j], rhoi,
                                   vj.w, vi.xyz(), vj.xyz());
            }
        },
        team);
    force = Vec3(team.sum(force.x), team.sum(force.y), team.sum(force.z));
    const Vec3 walls =
        params.walls == WallKind::Simple
            ? wallAcceleration(params.wallWeight, params.boxMin, params.boxMax, xi, rhoi, pi)
            : boundaryAcceleration(pv.boundary, params.kernel, xi, vi.xyz(), rhoi, pi,
                                   params.wallViscosity, params.invRestDensity);
    return force / rhoi + params.gravity + walls;
}

template <class Neighbours, int TeamSize = 1>
WEIR_HD inline void accelerationAt(Index i, const ParticleView& pv, const Neighbours& nb,
                                   const SphParams& params, Team<TeamSize> team = {}) {
    const Vec3 a = accelerationOf(i, pv, nb, params, team);
    if (team.leader()) {
        pv.acc[i] = Real4::from(a);
    }
}

// Removes the part of v along unit normal n that points into the wall, keeping `restitution` of
// it (bounced back), and `1 - friction` of the tangential part.
WEIR_HD inline void reflectVelocity(Vec3& v, const Vec3& n, const SphParams& params) {
    Real vn = dot(v, n);
    if (vn < 0) {
        Vec3 tangential = v - n * vn;
        v = tangential * (Real(1) - params.friction) - n * (vn * params.restitution);
    }
}

// The paper's simple collision response: particles are put back on the container walls and off
// obstacle boxes and spheres, and lose their velocity into the surface.
WEIR_HD inline void collide(Vec3& x, Vec3& v, const SphParams& params,
                            const ObstacleView& obstacles) {
    for (int a = 0; a < 3; ++a) {
        Vec3 n;
        if (x[a] < params.boxMin[a]) {
            x[a] = params.boxMin[a];
            n[a] = 1;
            reflectVelocity(v, n, params);
        } else if (x[a] > params.boxMax[a]) {
            x[a] = params.boxMax[a];
            n[a] = -1;
            reflectVelocity(v, n, params);
        }
    }
    for (int b = 0; b < obstacles.boxCount; ++b) {
        const ObstacleBox box = obstacles.boxes[b];
        bool inside = x.x > box.min.x && x.x < box.max.x && x.y > box.min.y && x.y < box.max.y &&
                      x.z > box.min.z && x.z < box.max.z;
        if (!inside) {
            continue;
        }
        // Leave through the nearest face.
        int axis = 0;
        Real best = Real(1e30), side = 1;
        for (int a = 0; a < 3; ++a) {
            Real toMin = x[a] - box.min[a], toMax = box.max[a] - x[a];
            if (toMin < best) {
                best = toMin;
                axis = a;
                side = -1;
            }
            if (toMax < best) {
                best = toMax;
                axis = a;
                side = 1;
            }
        }
        x[axis] = side < 0 ? box.min[axis] : box.max[axis];
        Vec3 n;
        n[axis] = side;
        reflectVelocity(v, n, params);
    }
    for (int s = 0; s < obstacles.sphereCount; ++s) {
        const ObstacleSphere sphere = obstacles.spheres[s];
        Vec3 d = x - sphere.center;
        Real r2 = lengthSquared(d);
        if (r2 >= sphere.radius * sphere.radius) {
            continue;
        }
        Real r = std::sqrt(r2);
        Vec3 n = r > Real(0) ? d / r : Vec3(0, 1, 0);
        x = sphere.center + n * sphere.radius;
        reflectVelocity(v, n, params);
    }
}

// Time integration of one particle over the clock's dt (semi-implicit Euler by default; the
// paper's explicit Euler selectable), collision response, the blow-up checks, and the largest
// speed and acceleration for the next step's dt; updates x and v in place.
WEIR_HD inline void advanceParticle(Vec3& x, Vec3& v, const Vec3& a, Index i,
                                    const SphParams& params, const ObstacleView& obstacles,
                                    FaultRecord* fault, StepClock* clock) {
    const Real dt = clock->dt;
    if (params.integrator == IntegratorKind::SemiImplicitEuler) {
        v += a * dt;
        x += v * dt;
    } else {
        x += v * dt;
        v += a * dt;
    }
    collide(x, v, params, obstacles);

    const Real speed2 = lengthSquared(v);
    recordMax(&clock->maxSpeed2, speed2);
    recordMax(&clock->maxAccel2, lengthSquared(a));
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
    }
}

// The paper's displacement stage: integrates particle i with the acceleration of the force stage.
WEIR_HD inline void integrateAt(Index i, const ParticleView& pv, const SphParams& params,
                                const ObstacleView& obstacles, FaultRecord* fault,
                                StepClock* clock) {
    if (isGhost(pv.pos[i])) {
        return;
    }
    Vec3 x = pv.position(i), v = pv.velocity(i);
    advanceParticle(x, v, pv.acc[i].xyz(), i, params, obstacles, fault, clock);
    pv.pos[i] = Real4::from(x);
    pv.vel[i] = Real4::from(v, pv.vel[i].w);  // keeps the step's density for output
}

// Force and displacement fused: the new state goes to separate arrays, since other particles
// still read this one's position and velocity in the same pass. Saves the acceleration array
// and a pass over the particles.
template <class Neighbours, int TeamSize = 1>
WEIR_HD inline void accelerateAndIntegrateAt(Index i, const ParticleView& pv, const Neighbours& nb,
                                             const SphParams& params, const ObstacleView& obstacles,
                                             FaultRecord* fault, StepClock* clock, Real4* newPos,
                                             Real4* newVel, Team<TeamSize> team = {}) {
    const Real4 v4 = pv.vel[i];
    if (clock->dt == Real(0) || isGhost(pv.pos[i])) {  // a no-op step, or a ghost: carried over
        if (team.leader()) {
            newPos[i] = pv.pos[i];
            newVel[i] = v4;
        }
        return;
    }
    const Vec3 a = accelerationOf(i, pv, nb, params, team);
    if (!team.leader()) {
        return;
    }
    Vec3 x = pv.position(i), v = v4.xyz();
    advanceParticle(x, v, a, i, params, obstacles, fault, clock);
    newPos[i] = Real4::from(x);
    newVel[i] = Real4::from(v, v4.w);
}

}  // namespace weir
