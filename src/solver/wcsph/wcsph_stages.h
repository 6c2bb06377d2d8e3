// The stages of weakly compressible SPH (paper §6.3, Müller et al. 2003), written once for CPU
// and CUDA: density and pressure (eqs. 2-3), pressure and viscous force (eqs. 4-5), and the
// displacement. Each stage reads what it needs and writes only particle i's own outputs.
#pragma once

#include <cmath>

#include "core/config.h"
#include "core/team.h"
#include "core/vec3.h"
#include "physics/boundary.h"
#include "physics/collision.h"
#include "physics/delta_sph.h"
#include "physics/density.h"
#include "physics/emitter.h"
#include "physics/eos.h"
#include "physics/faults.h"
#include "physics/integration.h"
#include "physics/kernels.h"
#include "physics/particle_view.h"
#include "physics/rigid_body.h"
#include "physics/sph_params.h"
#include "physics/time_step.h"
#include "physics/wall_weight.h"

namespace weir {

// What the force stage needs of a neighbour's pressure: p / rho^2 for the symmetric pressure
// force, p for the paper's eq. 4 (see pairForce). Computed once per particle by the density
// stage rather than once per pair: the equation of state is a quarter of the pair's arithmetic.
WEIR_HD inline Real pressureTermOf(const SphParams& params, Real rho) {
    const Real p = pressureFromDensity(params, rho);
    return params.pressureForce == PressureForm::Symmetric ? p / (rho * rho) : p;
}

// Eq. 2 with poly6, then the pressure term of eq. 3 for the force stage.
// One thread per particle: teams measured slower here (bench/NOTES.md #12, #14).
template <class Neighbours>
WEIR_HD inline void densityPressureAt(Index i, const ParticleView& pv, const Neighbours& nb,
                                      const SphParams& params) {
    const Real rho = densityAt(i, pv, nb, params);
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
    const Vec3 walls = params.walls == WallKind::Simple
                           ? wallAcceleration(params.wallWeight, params.boxMin, params.boxMax, xi,
                                              rhoi, pi, params.periodicAxes)
                           : boundaryAcceleration(pv.boundary, params.kernel, xi, vi.xyz(), rhoi,
                                                  pi, params.wallViscosity, params.invRestDensity);
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

// The paper's displacement stage: integrates particle i with the acceleration of the force stage.
WEIR_HD inline void integrateAt(Index i, const ParticleView& pv, const SphParams& params,
                                const ObstacleView& obstacles, FaultRecord* fault,
                                StepClock* clock) {
    if (isGhost(pv.pos[i])) {
        return;
    }
    Vec3 x = pv.position(i), v = pv.velocity(i);
    advanceParticle(x, v, pv.acc[i].xyz(), i, params, obstacles, fault, clock);
    checkDensity(pv.vel[i].w, false, i, x, params, fault, clock);
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
    checkDensity(v4.w, false, i, x, params, fault, clock);
    newPos[i] = Real4::from(x);
    newVel[i] = Real4::from(v, v4.w);
}

// ---- The delta-SPH model (FluidModel::DeltaSph, physics/delta_sph.h) ----
//
// Two passes over the neighbours, a symplectic Euler step: the first gives each particle its new
// velocity from the forces of the step's start (v' = v + dt a(x, v, rho)), the second its density
// rate from the new velocities (rho' = rho + dt D(x, v')), and the particle moves by the new
// velocity (x' = x + dt v'). Both rates from the old state (explicit Euler for the pressure
// waves) grow any wave by sqrt(1 + (omega dt)^2) a step: the fluid then holds together only at a
// time step a third as large, and only thanks to its dissipation.

// Walls of the simple model: the container planes push by the particle's own pressure times
// the gradient of their density share (physics/wall_weight.h) ...
WEIR_HD inline Vec3 wallWeightAcceleration(const SphParams& p, const Vec3& x, Real rhoi, Real pi) {
    return wallAcceleration(p.wallWeight, p.boxMin, p.boxMax, x, rhoi, pi, p.periodicAxes);
}
// ... and their share of the density changes as the particle moves through it, by the same
// gradient (the push's adjoint: together they conserve energy).
WEIR_HD inline Real wallWeightDensityRate(const SphParams& p, const Vec3& x, const Vec3& v) {
    return wallDensityRate(p.wallWeight, p.boxMin, p.boxMax, x, v, p.periodicAxes);
}

// ... their share of the kernel sum at x (the fluid they stand for; particle shifting's surface
// test) ...
WEIR_HD inline Real wallWeightShare(const SphParams& p, const Vec3& x) {
    Real share = 0;
    for (int a = 0; a < 3; ++a) {
        if (isPeriodic(p, a)) {
            continue;
        }
        for (int side = 0; side < 2; ++side) {
            Real s, push;
            wallSample(p.wallWeight, side == 0 ? x[a] - p.boxMin[a] : p.boxMax[a] - x[a], s, push);
            share += s;
        }
    }
    return share;
}

// ... and, for particle shifting, whether a plane is within the support of x.
WEIR_HD inline bool nearWallWeight(const SphParams& p, const Vec3& x) {
    for (int a = 0; a < 3; ++a) {
        if (!isPeriodic(p, a) &&
            (x[a] - p.boxMin[a] < p.wendland.h || p.boxMax[a] - x[a] < p.wendland.h)) {
            return true;
        }
    }
    return false;
}

// Before the first pass, each boundary particle b: the pressure and velocity the fluid near it
// extrapolates to it (physics/delta_sph.h); walls far from the fluid keep the wall's velocity and
// no pressure.
template <class Neighbours>
WEIR_HD inline void deltaWallAt(Index b, const ParticleView& pv, const Neighbours& nb,
                                const SphParams& params, Real4* state) {
    const BoundaryView& bv = pv.boundary;
    const Vec3 xb = bv.pos[b].xyz();
    const Vec3 vWall = bv.velocity != nullptr ? bv.velocity[b].xyz() : Vec3();
    state[b] = extrapolateToWall(params, nb, xb, vWall, pv.pos, pv.vel, pv.pressureTerm);
}

// A body's boundary particle in wall slot b (physics/rigid_body.h): the fluid's force on it, the
// opposite of what it adds to each fluid particle's momentum in the first pass
// (addBoundaryMomentum, from the same state) times that particle's mass, and the force's torque
// about the body's centre, into bodies.loads. Static wall particles are skipped.
template <class Neighbours>
WEIR_HD inline void deltaBodyLoadAt(Index b, const ParticleView& pv, const Neighbours& nb,
                                    const SphParams& params, const RigidBodyView& bodies) {
    const Index source = bodies.slotSource[b];
    if (source < bodies.staticCount) {
        return;
    }
    const Index j = source - bodies.staticCount;
    const BoundaryView& bv = pv.boundary;
    const Real4 pb = bv.pos[b];
    const Vec3 xb = pb.xyz();
    const Real4 state = bv.state[b];
    const Real h2 = params.wendland.h2;
    Vec3 momentum;  // what b adds to the fluid's momentum per unit fluid mass, summed
    nb.forEachNearPoint(xb, [&](Index f) {
        const Vec3 rVec = pv.position(f) - xb;
        const Real r2 = lengthSquared(rVec);
        if (r2 < h2 && r2 > Real(0)) {
            const Real4 vf = pv.vel[f];
            addBoundaryMomentum(params, rVec, r2, vf.w, pv.pressureTerm[f], vf.xyz(), pb.w, state,
                                momentum);
        }
    });
    const Vec3 force = momentum * (-params.mass);
    const Vec3 torque = cross(xb - bodies.bodies[bodies.bodyOf[j]].x, force);
    const Index n = bodies.particleCount;
    Real* loads = bodies.loads;
    loads[j] = force.x;
    loads[n + j] = force.y;
    loads[2 * n + j] = force.z;
    loads[3 * n + j] = torque.x;
    loads[4 * n + j] = torque.y;
    loads[5 * n + j] = torque.z;
}

// First pass: the forces on i (pressure, the fluid's viscosity, artificial viscosity, walls,
// gravity) and its new velocity, with the collision safety net applied to where it will be;
// newPos, newVel get that place and velocity (the density is still the old one). Ghosts (of a
// distributed run) are moved too, without records: the owned particles' second pass reads their
// new velocities.
// With particle shifting on, kernelSum[i] gets i's kernel sum sum_j V_j W_ij over fluid and walls
// (itself included), for the second pass's free-surface test.
template <class Neighbours, int TeamSize = 1>
WEIR_HD inline void deltaForceAt(Index i, const ParticleView& pv, const Neighbours& nb,
                                 const SphParams& params, const ObstacleView& obstacles,
                                 FaultRecord* fault, StepClock* clock, Real4* newPos, Real4* newVel,
                                 Real* kernelSum, Team<TeamSize> team = {}) {
    const Real4 v4 = pv.vel[i];
    if (clock->dt == Real(0) ||
        isParked(pv.pos[i])) {  // a no-op step, or no particle: carried over
        if (team.leader()) {
            newPos[i] = pv.pos[i];
            newVel[i] = v4;
        }
        return;
    }
    const Vec3 xi = pv.position(i), vi = v4.xyz();
    const Real rhoi = v4.w, termI = pv.pressureTerm[i], h2 = params.wendland.h2;
    const bool shifts = kernelSum != nullptr;
    Vec3 acc;
    Real sum = 0;
    bool collapsed = false;
    nb.forEachCandidate(
        i,
        [&](Index j) {
            const Vec3 rVec = xi - pv.position(j);
            const Real r2 = lengthSquared(rVec);
            if (r2 < h2 && r2 > Real(0)) {
                const Real4 vj = pv.vel[j];
                addFluidMomentum(params, rVec, r2, rhoi, vj.w, termI, pv.pressureTerm[j], vi,
                                 vj.xyz(), acc);
                if (shifts) {
                    sum += kernelSumTerm(params, r2, params.mass * reciprocal(vj.w));
                }
            } else if (r2 == Real(0) && j != i) {
                collapsed = true;
            }
        },
        team);
    acc = Vec3(team.sum(acc.x), team.sum(acc.y), team.sum(acc.z));
    collapsed = team.sum(collapsed ? Real(1) : Real(0)) > Real(0);
    if (shifts) {
        sum = team.sum(sum);
    }
    if (!team.leader()) {
        return;
    }
    const Real pi = pressureFromDensity(params, rhoi);
    if (params.walls == WallKind::Particles) {
        const BoundaryView& bv = pv.boundary;
        forEachBoundaryNeighbour(bv, params, xi, [&](Index b, const Vec3& rVec, Real r2) {
            addBoundaryMomentum(params, rVec, r2, rhoi, termI, vi, bv.pos[b].w, bv.state[b], acc);
            if (shifts) {
                sum += kernelSumTerm(params, r2, bv.pos[b].w * params.invRestDensity);
            }
        });
    } else {
        acc += wallWeightAcceleration(params, xi, rhoi, pi);
        if (shifts) {
            sum += wallWeightShare(params, xi);
        }
    }
    if (shifts) {
        kernelSum[i] = sum + params.mass * reciprocal(rhoi) * params.wendland.value(Real(0));
    }
    const Vec3 a = acc + params.gravity;
    Vec3 x = xi, v = vi;
    if (isGhost(pv.pos[i])) {  // its owner records and checks it
        v += a * clock->dt;
        x += v * clock->dt;
        collide(x, v, params, obstacles);
        newPos[i] = Real4::from(x, pv.pos[i].w);
    } else {
        advanceParticle(x, v, a, i, params, obstacles, fault, clock);
        checkDensity(rhoi, collapsed, i, xi, params, fault, clock);
        newPos[i] = Real4::from(x);
    }
    newVel[i] = Real4::from(v, rhoi);
}

// Second pass: i's density rate from the new velocities (`moved`: the first pass's newVel) at the
// old positions, continuity and density diffusion with the old densities (`density`), written
// into the new velocity's w; with particle shifting on (kernelSum: the first pass's), i's shift
// from the same neighbours is added to its new position (`movedPos`: the first pass's newPos),
// and the collision response keeps it out of obstacles and walls.
template <class Neighbours, int TeamSize = 1>
WEIR_HD inline void deltaDensityAt(Index i, const ParticleView& pv, const Neighbours& nb,
                                   const SphParams& params, const Real* density, Real4* moved,
                                   Real4* movedPos, const Real* kernelSum,
                                   const ObstacleView& obstacles, FaultRecord* fault,
                                   const StepClock* clock, Team<TeamSize> team = {}) {
    if (clock->dt == Real(0) || isGhost(pv.pos[i])) {
        return;  // carried over; a ghost's density is its owner's
    }
    const Vec3 xi = pv.position(i);
    const Vec3 vi = moved[i].xyz();
    const Real rhoi = density[i], h2 = params.wendland.h2;
    const bool shifts = kernelSum != nullptr;
    Real rate = 0;
    bool atSurface = shifts && kernelSum[i] < params.surfaceKernelSum;
    Vec3 gradient, surfaceNormal;
    Real relative2 = 0;  // the largest |v_i - v_j|^2 over the neighbours
    bool nearWall = false;
    nb.forEachCandidate(
        i,
        [&](Index j) {
            const Vec3 rVec = xi - pv.position(j);
            const Real r2 = lengthSquared(rVec);
            if (r2 < h2 && r2 > Real(0)) {
                const Real rhoj = density[j];
                const Vec3 vj = moved[j].xyz();
                rate += fluidDensityRate(params, rVec, r2, rhoi, rhoj, vi, vj);
                if (shifts) {
                    const Real rel2 = lengthSquared(vi - vj);
                    relative2 = rel2 > relative2 ? rel2 : relative2;
                    addShiftingNeighbour(params, rVec, r2, params.mass * reciprocal(rhoj),
                                         kernelSum[j], gradient, surfaceNormal, atSurface);
                }
            }
        },
        team);
    rate = team.sum(rate);
    if (shifts) {
        gradient = Vec3(team.sum(gradient.x), team.sum(gradient.y), team.sum(gradient.z));
        surfaceNormal =
            Vec3(team.sum(surfaceNormal.x), team.sum(surfaceNormal.y), team.sum(surfaceNormal.z));
        atSurface = team.sum(atSurface ? Real(1) : Real(0)) > Real(0);
        relative2 = team.max(relative2);
    }
    if (!team.leader()) {
        return;
    }
    if (params.walls == WallKind::Particles) {
        const BoundaryView& bv = pv.boundary;
        forEachBoundaryNeighbour(bv, params, xi, [&](Index b, const Vec3& rVec, Real r2) {
            const Vec3 vb = bv.velocity != nullptr ? bv.velocity[b].xyz() : Vec3();
            rate += boundaryDensityRate(params, rVec, r2, vi, bv.pos[b].w, vb);
            nearWall = true;
        });
    } else {
        rate += wallWeightDensityRate(params, xi, vi);
        nearWall = nearWallWeight(params, xi);
    }
    const Real rho = rhoi + clock->dt * rate;
    checkDensity(rho, false, i, xi, params, fault, clock);
    moved[i].w = rho;
    if (shifts && !nearWall && kernelSum[i] >= params.splashKernelSum) {
        const Vec3 shift =
            shiftingDisplacement(params, gradient, surfaceNormal, atSurface, relative2, clock->dt);
        Vec3 x = movedPos[i].xyz() + shift, v = vi;  // the velocity is not changed by the shift
        wrapPeriodic(x, params);  // in the box, or its ghosts would land among the fluid
        collide(x, v, params, obstacles);
        movedPos[i] = Real4::from(x, movedPos[i].w);
    }
}

}  // namespace weir
