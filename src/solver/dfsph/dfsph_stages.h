// The stages of divergence-free SPH (Bender & Koschier 2015, 2017), written once for CPU and
// CUDA. Each stage reads what it needs and writes only particle i's own outputs; the solvers'
// iterations are Jacobi sweeps of two passes each (a prediction that gives every particle its
// stiffness, then a velocity update from its own and its neighbours' stiffness).
//
// With kappa_i = p_i / rho_i, the pressure acceleration of the symmetric form is
//   a_i = -sum_j m_j (kappa_i / rho_i + kappa_j / rho_j) grad W_ij - sum_b psi_b kappa_i / rho_i
//   grad W_ib
// (boundary particles b mirror i's pressure, Akinci et al. 2012). Asking that one velocity update
// remove the predicted density change drho_i gives kappa_i = drho_i alpha_i / dt^2 with the factor
//   alpha_i = rho_i / (|sum_j m_j grad W_ij + sum_b psi_b grad W_ib|^2 + sum_j |m_j grad W_ij|^2)
// computed once a step: the constant-density solver drives the density predicted at the step's
// end to rho0 (only compression: a free surface reads light and must not pull), the
// divergence-free solver drives the density's rate of change to zero.
#pragma once

#include <cmath>

#include "core/config.h"
#include "core/vec3.h"
#include "physics/boundary.h"
#include "physics/collision.h"
#include "physics/delta_sph.h"
#include "physics/faults.h"
#include "physics/integration.h"
#include "physics/kernels.h"
#include "physics/particle_view.h"
#include "physics/sph_params.h"
#include "physics/time_step.h"

namespace weir {

// The state of one solve (the constant-density or the divergence-free one), in device memory, so
// that the iterations test convergence with no host round trip; and what a frame's log reports.
struct DfsphMonitor {
    float errorSum;  // this iteration's sum of per-particle errors (the backend's reduction)
    float errorMax;  // ... and the largest (the backend's reduction; the density solve only)
    int done;        // this solve has converged or run out of iterations
    int iterations;  // velocity updates of this solve so far
    // Since the last read by the host (one frame's worth):
    long long totalIterations;  // velocity updates over all solves
    int solves;                 // solves (steps that ran)
    int maxIterations;          // the most one solve took
    int unconverged;            // solves that stopped at the iteration limit
    float worstError;           // the largest mean error a solve ended with
};

// Fewer neighbours than this (the full lattice has about 33 at h = 2 d): a particle at a free
// surface or in spray, whose density rate the divergence-free solver leaves alone (Bender &
// Koschier 2017 use 20 in 3-D).
constexpr int kDfsphDivergenceNeighbours = 20;

// After the grid build: particle i's density by summation over fluid and boundary particles
// (into vel.w) and its factor alpha_i (0 where it has no neighbour).
// wallShepardSum (null: no boundary particles): each boundary particle's sum of W over the fluid
// near it (dfsphWallShepardSumAt), whose stiffness the density solve extrapolates from i's among
// others (dfsphWallStiffnessAt): the share that comes back to push i is part of the factor.
template <class Neighbours>
WEIR_HD inline void dfsphDensityFactorAt(Index i, const ParticleView& pv, const Neighbours& nb,
                                         const SphParams& p, Real* factor, unsigned char* interior,
                                         const Real* wallShepardSum) {
    const Vec3 xi = pv.position(i);
    const Real h2 = p.wendland.h2;
    Real rho = p.mass * p.wendland.value(Real(0));
    Vec3 gradSum, wallGradSum, ownWallPush;
    Real gradSquares = 0;
    int neighbours = 0;
    nb.forEachCandidate(i, [&](Index j) {
        const Vec3 rVec = xi - pv.position(j);
        const Real r2 = lengthSquared(rVec);
        if (r2 < h2 && r2 > Real(0)) {
            const Real r = r2 * reciprocalSqrt(r2);
            rho += p.mass * p.wendland.value(r);
            const Vec3 g = rVec * (p.mass * p.wendland.gradientFactor(r));
            gradSum += g;
            gradSquares += lengthSquared(g);
            ++neighbours;
        }
    });
    if (p.walls == WallKind::Particles) {
        const BoundaryView& bv = pv.boundary;
        forEachBoundaryNeighbour(bv, p, xi, [&](Index b, const Vec3& rVec, Real r2) {
            const Real r = r2 * reciprocalSqrt(r2);
            const Real psi = bv.pos[b].w;
            const Real w = p.wendland.value(r);
            rho += psi * w;
            const Vec3 g = rVec * (psi * p.wendland.gradientFactor(r));
            wallGradSum += g;
            if (wallShepardSum != nullptr && wallShepardSum[b] > Real(0)) {
                ownWallPush += g * (w / wallShepardSum[b]);
            }
            ++neighbours;
        });
    }
    pv.vel[i].w = rho;
    interior[i] = neighbours >= kDfsphDivergenceNeighbours ? 1 : 0;
    // The walls push i by its own stiffness (Akinci et al. 2012) and, with
    // WEIR_DFSPH_WALLS=extrapolated, in the density solve by theirs, extrapolated from the fluid
    // near them: i's share of that (ownWallPush, W_bi over b's Shepard sum) is i's too, and leaving
    // it out of the factor let the sweeps overshoot where a wall particle sees few fluid particles
    // (measured: a tank's floor edge blew up in its first step). (Walls that push by twice i's
    // stiffness instead, the factor made consistent, stirred a tank at rest ten times more within
    // 0.5 s.) Floored at half a full neighbourhood's: where the fluid neighbours are few and the
    // walls' gradient cancels theirs (a particle wedged in a corner) the sum nearly vanishes, and
    // the stiffness it would give pushes the few neighbours apart at once (measured: a 1M-particle
    // dam break compressed past 50% in its second step). A small factor only under-corrects.
    const Vec3 sum = gradSum + wallGradSum;
    Real denominator =
        lengthSquared(sum) + gradSquares + dot(ownWallPush, sum) * rho * p.invRestDensity;
    denominator = denominator > p.minFactorDenominator ? denominator : p.minFactorDenominator;
    factor[i] = denominator > Real(0) ? rho / denominator : Real(0);
}

// Each boundary particle's velocity for the viscous term at no-slip walls: the fluid's velocity
// near it mirrored through the wall, 2 v_wall - (sum_f v_f W_bf) / sum_f W_bf (Adami et al. 2012,
// as delta-SPH's walls); the wall's own velocity where no fluid is near or the walls slip.
template <class Neighbours>
WEIR_HD inline void dfsphWallVelocityAt(Index b, const ParticleView& pv, const Neighbours& nb,
                                        const SphParams& p, Real4* state) {
    const BoundaryView& bv = pv.boundary;
    const Vec3 xb = bv.pos[b].xyz();
    const Vec3 vWall = bv.velocity != nullptr ? bv.velocity[b].xyz() : Vec3();
    Real sumW = 0;
    Vec3 sumV;
    if (p.noSlip) {
        const Real h2 = p.wendland.h2;
        nb.forEachNearPoint(xb, [&](Index f) {
            const Real r2 = lengthSquared(xb - pv.position(f));
            if (r2 < h2) {
                const Real w = p.wendland.value(r2 * reciprocalSqrt(r2 > Real(0) ? r2 : h2));
                sumW += w;
                sumV += pv.velocity(f) * w;
            }
        });
    }
    const Vec3 v = sumW > Real(0) ? vWall * Real(2) - sumV / sumW : vWall;
    state[b] = Real4::from(v, Real(0));
}

// The parameters of the non-pressure forces: the solves' own kernel gradient is the raw one
// (scene/setup.cpp), the viscous forces take it divided by its lattice moment, as delta-SPH's do,
// so that Morris's Laplacian of a quadratic flow is exact on the lattice (measured with the raw
// one: a Poiseuille channel's steady profile 6% fast, the wall's drag 5% weak).
inline SphParams dfsphForceParams(const SphParams& p) {
    SphParams forces = p;
    forces.wendland = p.wendland.withGradientDividedBy(p.rawGradientMoment);
    return forces;
}

// The acceleration of everything but pressure: gravity, the fluid's own viscosity (Morris et al.
// 1997) and the small artificial viscosity between approaching particles, and at no-slip walls
// their shear, all as delta-SPH has them (physics/delta_sph.h, with no pressure terms; `p` from
// dfsphForceParams). Writes
// i's velocity after it, v* = v + dt a, into `predicted` (the density rides along in w), and
// records |a| for the next dt.
template <class Neighbours>
WEIR_HD inline void dfsphNonPressureAt(Index i, const ParticleView& pv, const Neighbours& nb,
                                       const SphParams& p, const Real4* wallState, StepClock* clock,
                                       Real4* predicted) {
    const Real4 v4 = pv.vel[i];
    if (clock->dt == Real(0)) {
        predicted[i] = v4;
        return;
    }
    const Vec3 xi = pv.position(i), vi = v4.xyz();
    const Real rhoi = v4.w, h2 = p.wendland.h2;
    Vec3 acc;
    if (p.dynamicViscosity > Real(0) || p.artificialViscosity > Real(0)) {
        nb.forEachCandidate(i, [&](Index j) {
            const Vec3 rVec = xi - pv.position(j);
            const Real r2 = lengthSquared(rVec);
            if (r2 < h2 && r2 > Real(0)) {
                const Real4 vj = pv.vel[j];
                addFluidMomentum(p, rVec, r2, rhoi, vj.w, Real(0), Real(0), vi, vj.xyz(), acc);
            }
        });
        if (p.walls == WallKind::Particles && p.noSlip && wallState != nullptr) {
            const BoundaryView& bv = pv.boundary;
            forEachBoundaryNeighbour(bv, p, xi, [&](Index b, const Vec3& rVec, Real r2) {
                addBoundaryMomentum(p, rVec, r2, rhoi, Real(0), vi, bv.pos[b].w, wallState[b], acc);
            });
        }
    }
    const Vec3 a = acc + p.gravity;
    // The next dt's force condition sees these forces even where pressure balances them (a
    // tank at rest: the move's own acceleration is then zero, and dt would grow unbounded).
    recordMax(&clock->maxAccel2, lengthSquared(a));
    predicted[i] = Real4::from(vi + a * clock->dt, rhoi);
}

// What the move over `ahead` seconds adds to W_ij's change beyond its first order, over `ahead`:
// with the pair's displacement dx = ahead u (u = v_i - v_j, r = x_i - x_j, grad W = g(r) r),
// (1/2) dx . (grad grad W) dx / ahead = (ahead / 2) (g |u|^2 + g'(r) (r . u)^2 / r).
WEIR_HD inline Real dfsphSecondOrderRate(const WendlandKernel& k, Real r, const Vec3& rVec,
                                         const Vec3& u, Real ahead) {
    const Real along = dot(u, rVec);
    return Real(0.5) * ahead *
           (k.gradientFactor(r) * lengthSquared(u) + k.gradientFactorSlope(r) * along * along / r);
}

// The rate of i's density under velocities `vel`: sum_j m_j (v_i - v_j) . grad W_ij plus the walls'
// sum_b psi_b (v_i - v_b) . grad W_ib; `neighbours` gets the number of fluid and boundary
// neighbours. With `ahead` > 0, the rate that takes the density to its value after a move of
// that length at these velocities to second order (dfsphSecondOrderRate; opt-in,
// WEIR_DFSPH_SECOND_ORDER=1): the first order alone lets a particle moving 0.4 d a step onto a
// wall or a neighbour overshoot the solve's bound (a pair closing 0.4 d a step at half the radius
// adds about 0.5% of rho0 beyond the first order). It held a 20k dam break's every particle
// within 0.3% where the first order let 4-5 of 60 frames pass 1%, but the stability sweep's
// coarse cases (h = 1.5 d) blew up with it: the sweeps, linear in the stiffness, chase a
// prediction that is not.
template <class Neighbours>
WEIR_HD inline Real dfsphDensityRate(Index i, const ParticleView& pv, const Neighbours& nb,
                                     const SphParams& p, const Real4* vel, int& neighbours,
                                     Real ahead = Real(0)) {
    const Vec3 xi = pv.position(i), vi = vel[i].xyz();
    const Real h2 = p.wendland.h2;
    Real rate = 0;
    int count = 0;
    nb.forEachCandidate(i, [&](Index j) {
        const Vec3 rVec = xi - pv.position(j);
        const Real r2 = lengthSquared(rVec);
        if (r2 < h2 && r2 > Real(0)) {
            const Real r = r2 * reciprocalSqrt(r2);
            const Vec3 u = vi - vel[j].xyz();
            rate += p.mass * p.wendland.gradientFactor(r) * dot(u, rVec);
            if (ahead > Real(0)) {
                rate += p.mass * dfsphSecondOrderRate(p.wendland, r, rVec, u, ahead);
            }
            ++count;
        }
    });
    if (p.walls == WallKind::Particles) {
        const BoundaryView& bv = pv.boundary;
        forEachBoundaryNeighbour(bv, p, xi, [&](Index b, const Vec3& rVec, Real r2) {
            const Vec3 vb = bv.velocity != nullptr ? bv.velocity[b].xyz() : Vec3();
            rate += boundaryDensityRate(p, rVec, r2, vi, bv.pos[b].w, vb);
            if (ahead > Real(0)) {
                rate += bv.pos[b].w * dfsphSecondOrderRate(p.wendland, r2 * reciprocalSqrt(r2),
                                                           rVec, vi - vb, ahead);
            }
            ++count;
        });
    }
    neighbours = count;
    return rate;
}

// The error a solve removes at particle i under velocities `vel` (w: the density), kg/m^3 over
// the step: the density solve (divergence false) the density predicted at the step's end, rho_i +
// dt drho_i/dt, less rho0; the divergence solve dt drho_i/dt (none at a free surface, fewer than
// kDfsphDivergenceNeighbours). Negative where the fluid expands.
template <class Neighbours>
WEIR_HD inline Real dfsphExcess(Index i, const ParticleView& pv, const Neighbours& nb,
                                const SphParams& p, const Real4* vel, bool divergence, Real dt) {
    int neighbours = 0;
    const Real rate = dfsphDensityRate(i, pv, nb, p, vel, neighbours,
                                       divergence || !p.dfsphSecondOrder ? Real(0) : dt);
    if (divergence) {
        return neighbours >= kDfsphDivergenceNeighbours ? rate * dt : Real(0);
    }
    return vel[i].w + dt * rate - p.restDensity;
}

// The share of each sweep's correction that is applied (relaxed Jacobi): full at smoothing ratios
// up to h = 2 d, half above. Jacobi sweeps converge only while the operator's largest eigenvalue
// over its diagonal stays under 2 / relaxation, and the neighbours' share of the operator grows
// with their number (about 33 at 2 d, 110 at 3 d). Measured on the stability sweep (CPU, 600
// particles, every shipped scene DFSPH runs): at 3 d, full sweeps blew up in 7 of 9 scenes and 0.7
// in 5; 0.5 passed all 9 (IISPH's relaxation, Ihmsen et al. 2014). At 2 d full sweeps pass, and 0.5
// would cost 1.7 times the time (a 10k dam break, 0.5 s).
WEIR_HD inline Real dfsphRelaxation(const SphParams& p) {
    const Real spacing = cbrt(p.mass * p.invRestDensity);
    return p.wendland.h > Real(2.05) * spacing ? Real(0.5) : Real(1);
}

// The share of a stiffness given back in one sweep (below).
constexpr Real kDfsphReleaseRelaxation = Real(0.5);

// One sweep's prediction for particle i: the stiffness change kappa = excess alpha_i / dt^2 that
// one velocity update would need to remove the excess, kept as kappa / rho_i (what the update
// reads). A fluid pushes, it does not pull: the stiffness the solve has summed for i (with the
// warm start) never goes below zero, so where i expands it gives back what it holds, and no more
// (a projected Jacobi sweep), inside the fluid only: at a free surface (fewer than
// kDfsphDivergenceNeighbours neighbours) a light summed density is the kernel's deficit, not an
// expansion, and nothing is given back or pulled. Given back at half the rate: at the full rate the
// sweeps overshoot both ways and grow (measured: a tank at rest blew up in its first step). The
// error for the mean is |excess| / rho0 where i holds a stiffness, the compression alone where it
// holds none (a free surface, light by summation, is no error). accumulated keeps the sum for the
// next step's warm start, in a form that does not depend on dt: kappa itself for the density solve
// (a steady pressure field p = rho kappa holds whatever the step), kappa dt for the divergence
// solve (the velocity it removes, dt kappa / h, does not depend on dt). Nothing once the solve is
// done. `relaxation`: dfsphRelaxation's share of each correction.
template <class Neighbours>
WEIR_HD inline void dfsphPredictAt(Index i, const ParticleView& pv, const Neighbours& nb,
                                   const SphParams& p, const Real4* vel, const Real* factor,
                                   bool divergence, const StepClock* clock,
                                   const DfsphMonitor* monitor, Real* kappaOverRho, float* error,
                                   Real* accumulated, const unsigned char* interior,
                                   Real relaxation) {
    if (monitor->done != 0) {
        return;
    }
    const Real dt = clock->dt;
    Real excess = dfsphExcess(i, pv, nb, p, vel, divergence, dt);
    excess = interior[i] != 0 || excess > Real(0) ? excess : Real(0);
    Real k = relaxation * excess * factor[i] / (dt * dt);
    k = excess < Real(0) ? k * kDfsphReleaseRelaxation : k;
    const Real before = accumulated[i];
    Real stored = divergence ? k * dt : k;
    if (before + stored < Real(0)) {
        stored = -before;
        k = divergence ? stored / dt : stored;
    }
    const Real after = before + stored;
    accumulated[i] = after;
    kappaOverRho[i] = k * reciprocal(vel[i].w);
    const Real counted = after > Real(0) ? fabs(excess) : (excess > Real(0) ? excess : Real(0));
    error[i] = float(counted * p.invRestDensity);
}

// Before a solve's sweeps, its warm start (Bender & Koschier 2017): the stiffness i's last solve
// summed to (in the form dfsphPredictAt keeps), times `share`, applied as a first velocity update;
// the sum goes on from it: whole, so in a steady flow it is the answer, and the sweeps give back
// what the flow no longer needs. (With WEIR_DFSPH_WALLS=extrapolated, Dfsph keeps the two solves'
// sums as one: the density solve starts from the whole step's, the divergence solve from
// nothing.) Only inside the fluid (at least kDfsphDivergenceNeighbours neighbours): at a
// free surface or in spray the summed density reads light, the sweeps only push, and a warm start
// would push on for as long as it is carried. (Half of it, only where compressed, as SPlisHSPlasH
// starts, took 23-32 sweeps a step on a 1M dam break on the H200 against 2: each step rebuilt half
// the column's pressure.)
WEIR_HD inline void dfsphWarmStartAt(Index i, const Real4* vel, bool divergence, Real share,
                                     const StepClock* clock, Real* kappaOverRho, Real* accumulated,
                                     const unsigned char* interior) {
    const Real dt = clock->dt;
    if (dt == Real(0)) {
        return;
    }
    const Real warm = accumulated[i];
    const Real start = warm > Real(0) && interior[i] != 0 ? share * warm : Real(0);
    kappaOverRho[i] = (divergence ? start / dt : start) * reciprocal(vel[i].w);
    accumulated[i] = start;
}

// One thread, after the errors' sum (and largest): the iteration's mean error against the
// tolerance and, where worstTolerance > 0, its largest against that. The solve is done once both
// are under them after at least minIterations updates, or at maxIterations.
WEIR_HD inline void dfsphCheck(DfsphMonitor* monitor, Index count, Real tolerance,
                               Real worstTolerance, int minIterations, int maxIterations) {
    if (monitor->done != 0) {
        return;
    }
    const float mean = count > 0 ? monitor->errorSum / float(count) : 0.0f;
    const bool converged =
        mean <= float(tolerance) &&
        (worstTolerance <= Real(0) || monitor->errorMax <= float(worstTolerance)) &&
        monitor->iterations >= minIterations;
    if (converged || monitor->iterations >= maxIterations) {
        monitor->done = 1;
        monitor->totalIterations += monitor->iterations;
        monitor->solves += 1;
        monitor->maxIterations = monitor->iterations > monitor->maxIterations
                                     ? monitor->iterations
                                     : monitor->maxIterations;
        monitor->unconverged += converged ? 0 : 1;
        monitor->worstError = mean > monitor->worstError ? mean : monitor->worstError;
        return;
    }
    monitor->iterations += 1;
}

// One thread, before a solve: its state reset (done at once in a no-op step).
WEIR_HD inline void dfsphBeginSolve(DfsphMonitor* monitor, const StepClock* clock) {
    monitor->done = clock->dt == Real(0) ? 1 : 0;
    monitor->iterations = 0;
}

// Each boundary particle's sum of W over the fluid near it: the denominator of the Shepard means
// of dfsphWallStiffnessAt, once a step (the positions stay put until the move).
template <class Neighbours>
WEIR_HD inline void dfsphWallShepardSumAt(Index b, const ParticleView& pv, const Neighbours& nb,
                                          const SphParams& p, Real* shepardSum) {
    const Vec3 xb = pv.boundary.pos[b].xyz();
    const Real h2 = p.wendland.h2;
    Real sumW = 0;
    nb.forEachNearPoint(xb, [&](Index f) {
        const Real r2 = lengthSquared(xb - pv.position(f));
        if (r2 < h2) {
            sumW += p.wendland.value(r2 * reciprocalSqrt(r2 > Real(0) ? r2 : h2));
        }
    });
    shepardSum[b] = sumW;
}

// With WEIR_DFSPH_WALLS=extrapolated, the density solve's walls push back as the fluid would
// (Adami et al. 2012's pressure
// extrapolation, as Band et al. 2018 take it to implicit solvers): boundary particle b's
// stiffness is the Shepard mean of the stiffness the solve has summed for the fluid near it, plus
// the hydrostatic part g . (x_b - x_f) (over the lattice moment, as the solves' stiffness is), and
// never negative (walls do not pull). Along periodic axes no pressure holds the body force, so
// that part leaves them out. Kept over rho0 in `total` (what the sweeps so far have applied);
// `change` gets what the next velocity update adds. Once the solve is done, nothing. (Akinci et
// al. 2012's walls push i by its own stiffness only: the layer by a wall then holds twice its
// share, and a tank's floor layer read 1.6-1.8 times hydrostatic at every resolution.)
template <class Neighbours>
WEIR_HD inline void dfsphWallStiffnessAt(Index b, const ParticleView& pv, const Neighbours& nb,
                                         const SphParams& p, const Real* summedStiffness,
                                         const Real* shepardSum, const DfsphMonitor* monitor,
                                         Real* total, Real* change) {
    if (monitor->done != 0) {
        change[b] = Real(0);
        return;
    }
    Real k = 0;
    if (shepardSum[b] > Real(0)) {
        const Vec3 xb = pv.boundary.pos[b].xyz();
        const Real h2 = p.wendland.h2;
        Real sumK = 0;
        Vec3 sumR;
        nb.forEachNearPoint(xb, [&](Index f) {
            const Vec3 r = xb - pv.position(f);
            const Real r2 = lengthSquared(r);
            if (r2 < h2) {
                const Real w = p.wendland.value(r2 * reciprocalSqrt(r2 > Real(0) ? r2 : h2));
                sumK += summedStiffness[f] * w;
                sumR += r * w;
            }
        });
        Vec3 g = p.gravity;
        g.x = isPeriodic(p, 0) ? Real(0) : g.x;
        g.y = isPeriodic(p, 1) ? Real(0) : g.y;
        g.z = isPeriodic(p, 2) ? Real(0) : g.z;
        k = (sumK + dot(g, sumR) / p.rawGradientMoment) / shepardSum[b];
        k = k > Real(0) ? k * p.invRestDensity : Real(0);
    }
    change[b] = k - total[b];
    total[b] = k;
}

// The velocity update of one iteration for particle i: v_i -= dt (sum_j m_j (kappa_i / rho_i +
// kappa_j / rho_j) grad W_ij + sum_b psi_b (kappa_i / rho_i + kappa_b / rho0) grad W_ib), from
// each particle's kappa / rho this sweep and, in the density solve, each wall's change of
// kappa_b / rho0 (wallChange, dfsphWallStiffnessAt; null in the divergence solve, whose walls push
// by i's own stiffness alone). Velocities are updated in place: this pass reads only positions
// and the kappa / rho of others.
template <class Neighbours>
WEIR_HD inline void dfsphUpdateAt(Index i, const ParticleView& pv, const Neighbours& nb,
                                  const SphParams& p, Real4* vel, const Real* kappaOverRho,
                                  const StepClock* clock, const DfsphMonitor* monitor,
                                  const Real* wallChange) {
    if (monitor->done != 0) {
        return;
    }
    const Vec3 xi = pv.position(i);
    const Real4 v4 = vel[i];
    const Real termI = kappaOverRho[i], h2 = p.wendland.h2;
    Vec3 acc;
    nb.forEachCandidate(i, [&](Index j) {
        const Vec3 rVec = xi - pv.position(j);
        const Real r2 = lengthSquared(rVec);
        if (r2 < h2 && r2 > Real(0)) {
            const Real sum = termI + kappaOverRho[j];
            if (sum != Real(0)) {
                const Real r = r2 * reciprocalSqrt(r2);
                acc += rVec * (-p.mass * sum * p.wendland.gradientFactor(r));
            }
        }
    });
    if (p.walls == WallKind::Particles && (termI != Real(0) || wallChange != nullptr)) {
        const BoundaryView& bv = pv.boundary;
        forEachBoundaryNeighbour(bv, p, xi, [&](Index b, const Vec3& rVec, Real r2) {
            const Real r = r2 * reciprocalSqrt(r2);
            const Real term = termI + (wallChange != nullptr ? wallChange[b] : Real(0));
            acc += rVec * (-bv.pos[b].w * term * p.wendland.gradientFactor(r));
        });
    }
    vel[i] = Real4::from(v4.xyz() + acc * clock->dt, v4.w);
}

// The move: x' = x + dt v (v: the solved velocity), the collision response as a safety net, the
// blow-up checks and the step's largest speed and acceleration for the next dt. Writes the new
// position and velocity to newPos, newVel (`solved` may be newVel itself).
WEIR_HD inline void dfsphAdvanceAt(Index i, const ParticleView& pv, const SphParams& p,
                                   const ObstacleView& obstacles, FaultRecord* fault,
                                   StepClock* clock, const Real4* solved, Real4* newPos,
                                   Real4* newVel) {
    const Real4 start = pv.vel[i];
    if (clock->dt == Real(0) || isGhost(pv.pos[i])) {  // a no-op step, or a ghost: carried over
        newPos[i] = pv.pos[i];
        newVel[i] = start;
        return;
    }
    const Real4 v4 = solved[i];
    Vec3 x = pv.position(i), v = v4.xyz();
    const Vec3 a = (v - start.xyz()) * reciprocal(clock->dt);
    // advanceParticle applies v += a dt, x += v dt: the solved velocity and the move by it.
    Vec3 vStart = start.xyz();
    // The force condition sees the non-pressure forces only (dfsphNonPressureAt records them):
    // the pressure is solved for, whatever dt. Counting it too cut a 30k dam break's steps by
    // pressure spikes at the walls to 0.8x the CFL step.
    advanceParticle(x, vStart, a, i, p, obstacles, fault, clock, false);
    checkDensity(start.w, false, i, x, p, fault, clock);
    newPos[i] = Real4::from(x, pv.pos[i].w);
    newVel[i] = Real4::from(vStart, start.w);
}

}  // namespace weir
