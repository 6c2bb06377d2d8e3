// The pair terms of the delta-SPH fluid model (FluidModel::DeltaSph), written once for CPU and
// CUDA: for a fluid particle i and a neighbour j (fluid) or b (boundary particle), what they add
// to i's acceleration and to its density's rate of change.
//
//   pressure     a_i -= m_j (p_i / rho_i^2 + p_j / rho_j^2) grad W_ij          (symmetric form)
//   continuity   drho_i/dt += m_j (v_i - v_j) . grad W_ij
//   diffusion    drho_i/dt -= delta c h 2 (rho_j - rho_i - rho^H_ji) g_ij m_j / rho_j
//                (Molteni & Colagrossi 2009, with grad W = g r_vec; Fourtakas et al. 2019 leave
//                the hydrostatic part rho^H_ji = rho0 g . (x_j - x_i) / c^2 alone, so a tank at
//                rest keeps its hydrostatic density)
//   viscosity    a_i += m_j 2 mu / (rho_i rho_j) (r . grad W) / (r^2 + eta^2) (v_i - v_j)
//                (Morris, Fox & Zhu 1997: the fluid's own, laminar viscosity)
//   artificial   a_i -= m_j Pi_ij grad W_ij, Pi_ij = -alpha c (h/2) (v_ij . r) / ((r^2 + eta^2)
//                rho_ij) for approaching pairs only (Monaghan 1992, alpha small)
//
// Walls are boundary particles b (physics/boundary.h) that stand for the fluid beyond them
// (Adami, Hu & Adams 2012): each step every one takes the pressure and velocity that the fluid
// near it extrapolates to its place (extrapolateToWall), and acts on the fluid as a fluid
// particle would, so the layer next to a wall feels the pressure the missing fluid would exert
// (not squeezed to twice hydrostatic) and, at no-slip walls, its shear. Extrapolating from the one
// fluid particle of the pair instead (p_b = p_i + rho_i g . (x_b - x_i)) pushes it by twice its own
// pressure, more than its density's share of the wall (Akinci's term) returns: measured, a tank at
// rest gained energy until it churned at 0.2 m/s.
#pragma once

#include <cmath>

#include "core/config.h"
#include "core/vec3.h"
#include "physics/boundary.h"
#include "physics/eos.h"
#include "physics/kernels.h"
#include "physics/sph_params.h"

namespace weir {

// Fluid neighbour j of fluid particle i, momentum: rVec = x_i - x_j, 0 < r2 < h^2; termI, termJ:
// p / rho^2. Adds to i's acceleration.
WEIR_HD inline void addFluidMomentum(const SphParams& p, const Vec3& rVec, Real r2, Real rhoi,
                                     Real rhoj, Real termI, Real termJ, const Vec3& vi,
                                     const Vec3& vj, Vec3& acceleration) {
    const Real r = r2 * reciprocalSqrt(r2);
    const Real g = p.wendland.gradientFactor(r);  // grad W = g rVec, g < 0
    const Vec3 vij = vi - vj;
    const Real vDotR = dot(vij, rVec);
    const Real softened = reciprocal(r2 + p.viscositySoftening);
    // Pressure, then viscosity: the fluid's own (Morris) and, approaching, the artificial one.
    // Under tension (p < 0) a pair attracts, and Wendland's gradient, zero at r = 0, would not
    // stop two particles closing onto one point: Monaghan's (2000) artificial pressure adds a
    // repulsion that grows as (W / W(h / 3))^4 once they are closer than h / 3 (d at h = 3 d).
    Real pairTerm = termI + termJ;
    const Real tension = p.tensileCorrection * ((termI < Real(0) ? -termI : Real(0)) +
                                                (termJ < Real(0) ? -termJ : Real(0)));
    if (tension > Real(0)) {
        const Real f = p.wendland.value(r) * p.invKernelAtReference, f2 = f * f;
        pairTerm += tension * f2 * f2;
    }
    Real alongR = -p.mass * pairTerm * g;
    if (vDotR < Real(0)) {
        alongR += p.artificialViscosity * vDotR * softened * Real(2) * p.mass *
                  reciprocal(rhoi + rhoj) * g;
    }
    const Real viscous =
        Real(2) * p.dynamicViscosity * p.mass * reciprocal(rhoi * rhoj) * g * r2 * softened;
    acceleration += rVec * alongR + vij * viscous;
}

// Fluid neighbour j of fluid particle i, continuity and density diffusion: the rate of i's
// density, with the velocities of the step's end (see the method's two passes).
WEIR_HD inline Real fluidDensityRate(const SphParams& p, const Vec3& rVec, Real r2, Real rhoi,
                                     Real rhoj, const Vec3& vi, const Vec3& vj) {
    const Real r = r2 * reciprocalSqrt(r2);
    const Real g = p.wendland.gradientFactor(r);
    const Real hydrostatic = -dot(p.hydrostaticGradient, rVec);  // rho^H_j - rho^H_i
    return p.mass * g *
           (dot(vi - vj, rVec) -
            p.densityDiffusion * Real(2) * (rhoj - rhoi - hydrostatic) * reciprocal(rhoj));
}

// A boundary particle's state this step (Adami, Hu & Adams 2012), from the fluid near it:
// pressure p_b = (sum_f p_f W_bf + g . sum_f rho_f (x_b - x_f) W_bf) / sum_f W_bf, the fluid's
// pressure extrapolated to b with the hydrostatic part of its gradient, never negative (walls do
// not pull); velocity for the viscous term 2 v_wall - (sum_f v_f W_bf) / sum_f W_bf (no-slip:
// the fluid's velocity mirrored through the wall) or v_wall (free slip). Returns (v_b, p_b /
// rho_b^2) with rho_b from p_b by the equation of state. Neighbours: the fluid's neighbour view,
// queried at b's position; pressureTerm: each fluid particle's p / rho^2.
template <class Neighbours>
WEIR_HD inline Real4 extrapolateToWall(const SphParams& p, const Neighbours& nb, const Vec3& xb,
                                       const Vec3& vWall, const Real4* pos, const Real4* vel,
                                       const Real* pressureTerm) {
    Real sumW = 0, sumP = 0;
    Vec3 sumRhoR, sumV;
    const Real h2 = p.wendland.h2;
    nb.forEachNearPoint(xb, [&](Index f) {
        const Vec3 r = xb - pos[f].xyz();
        const Real r2 = lengthSquared(r);
        if (r2 < h2) {
            const Real w = p.wendland.value(r2 * reciprocalSqrt(r2 > Real(0) ? r2 : h2));
            const Real4 vf = vel[f];
            sumW += w;
            sumP += pressureTerm[f] * vf.w * vf.w * w;
            sumRhoR += r * (vf.w * w);
            sumV += vf.xyz() * w;
        }
    });
    if (!(sumW > Real(0))) {
        return Real4::from(vWall, Real(0));
    }
    const Real invW = Real(1) / sumW;
    Real pb = (sumP + dot(p.gravity, sumRhoR)) * invW;
    pb = pb > Real(0) ? pb : Real(0);
    const Real rhob = densityFromPressure(p, pb);
    const Vec3 vb = p.noSlip ? vWall * Real(2) - sumV * invW : vWall;
    return Real4::from(vb, pb / (rhob * rhob));
}

// Boundary particle b of fluid particle i, momentum: rVec = x_i - x_b, 0 < r2 < h^2; psi the
// mass it stands for; state its extrapolated velocity and p / rho^2 (extrapolateToWall).
WEIR_HD inline void addBoundaryMomentum(const SphParams& p, const Vec3& rVec, Real r2, Real rhoi,
                                        Real termI, const Vec3& vi, Real psi, const Real4& state,
                                        Vec3& acceleration) {
    const Real r = r2 * reciprocalSqrt(r2);
    const Real g = p.wendland.gradientFactor(r);
    Real alongR = -psi * (termI + state.w) * g;
    if (p.noSlip) {
        const Vec3 vib = vi - state.xyz();
        const Real softened = reciprocal(r2 + p.viscositySoftening);
        acceleration += vib * (Real(2) * p.dynamicViscosity * psi * p.invRestDensity *
                               reciprocal(rhoi) * g * r2 * softened);
        const Real vDotR = dot(vib, rVec);
        if (vDotR < Real(0)) {
            alongR += p.artificialViscosity * vDotR * softened * Real(2) * psi *
                      reciprocal(rhoi + p.restDensity) * g;
        }
    }
    acceleration += rVec * alongR;
}

// Boundary particle b of fluid particle i, continuity: its share of i's density rate, with the
// wall's own velocity (the fluid may not flow through it).
WEIR_HD inline Real boundaryDensityRate(const SphParams& p, const Vec3& rVec, Real r2,
                                        const Vec3& vi, Real psi, const Vec3& vWall) {
    const Real r = r2 * reciprocalSqrt(r2);
    return psi * p.wendland.gradientFactor(r) * dot(vi - vWall, rVec);
}

// ---- Particle shifting (SphParams::shifting > 0) ----
//
// Particles in a shear flow line up along its streamlines and, where the flow stretches them
// (the stagnation points of a vortex), tear apart: the pressure gradient of a disordered lattice
// is wrong, the lattice does not heal, and the flow loses its energy to noise (measured: the
// Taylor-Green vortex followed the analytic decay until particles had moved half a spacing,
// then collapsed). Each step every particle is moved a little down the gradient of the particle
// concentration C = sum_j V_j W_ij, towards where particles are sparse (Lind et al. 2012), by
// the delta-plus-SPH form of Sun et al. 2017:
//   delta x_i = -A dt sum_j V_j (1 + R (W_ij / W(d))^4) grad W_ij,   A = 2 r_s c / 10
// (r_s the support radius; their CFL Ma (2h)^2 with Ma = 0.1, CFL = c dt / h), R = 0.2: the
// tensile term pushes apart pairs closer than the spacing d. The shift moves matter, not
// momentum: velocities and densities are carried unchanged. Where that would move fluid that
// should not move, it is restricted (each rule measured necessary on a tank at rest or on the
// vortex, docs/physics.md):
// - Only where the fluid deforms. A fluid at rest or in rigid motion needs no regularising, and
//   a tank at rest shifted at full strength never settled (its particles kept drifting through
//   the pressure field, 0.04-0.07 sqrt(2 g H) of stray speed). The shift is scaled by the largest
//   speed of a neighbour relative to the particle over SphParams::shiftingGateSpeed (a tenth of
//   the flow's speed scale c / 10), up to 1: full where the flow is sheared or stretched across
//   the kernel, nothing at rest; unlike a particle's own speed (Skillen et al. 2013), the same
//   in every frame of reference.
// - At a free surface C is truncated and its gradient would push particles out of the fluid (a
//   tank blew up). The kernel sum of every particle is taken in the force pass; a particle whose
//   own sum is under SphParams::surfaceKernelSum, or that has a neighbour under
//   SphParams::surfaceNeighbourKernelSum (a surface particle: the layer under the surface is
//   truncated too), moves along the surface only: the part of its shift along its fluid kernel
//   gradient sum_j V_j grad W_ij (the surface normal) is dropped. The neighbour threshold is the
//   lower one: a small void in a stretched bulk (sums 0.9-0.95) must not switch off the shift
//   that heals it (the vortex blew up when it did).
// - Spray (a particle's own kernel sum under SphParams::splashKernelSum: a drop, a sheet one or
//   two particles thick) has no surface to slide along and is not shifted (Sun et al. 2017 do
//   the same; a dam break's run-up jet blew up when it was).
// - Next to walls (a boundary particle or a simple wall's plane within the support) particles
//   are not shifted: neither the walls' particles nor the planes stand for the fluid beyond them
//   exactly enough, at edges and corners least (a tank churned). The collision response keeps a
//   shifted particle out of obstacles and in the container.
// The shift is held to SphParams::shiftingLimit a step.
// Off by default (fluid.shifting 1 turns it on): on an H200 the Martin & Moyce column with it
// blew up at 80 and 160 particles across (a particle at 2681 m/s, t = 0.18 s), where without it
// the same runs hold. A shift moves a particle through the fluid without the continuity equation
// seeing it, so particles it crowds together gain no pressure; the consistent ALE form (the
// shift's velocity in the continuity and momentum equations, Antuono et al. 2021) is what
// remains to do.

// V_j W_ij of a neighbour at distance^2 r2 < h^2 with volume vj: its share of the kernel sum.
WEIR_HD inline Real kernelSumTerm(const SphParams& p, Real r2, Real vj) {
    return vj * p.wendland.value(r2 * reciprocalSqrt(r2 > Real(0) ? r2 : p.wendland.h2));
}

// Fluid neighbour j of fluid particle i (0 < r2 < h^2), volume vj = m / rho_j, kernel sum of j
// sumJ: adds to the concentration gradient (with the tensile term) and to the surface normal
// (without it), and notes a surface particle among the neighbours.
WEIR_HD inline void addShiftingNeighbour(const SphParams& p, const Vec3& rVec, Real r2, Real vj,
                                         Real sumJ, Vec3& gradient, Vec3& normal, bool& atSurface) {
    const Real r = r2 * reciprocalSqrt(r2);
    const Real ratio = p.wendland.value(r) * p.shiftingInvW, ratio2 = ratio * ratio;
    const Vec3 grad = rVec * (vj * p.wendland.gradientFactor(r));
    gradient += grad * (Real(1) + Real(0.2) * ratio2 * ratio2);
    normal += grad;
    atSurface = atSurface || sumJ < p.surfaceNeighbourKernelSum;
}

// Particle i's shift this step from its concentration gradient; relative2: the largest
// |v_i - v_j|^2 over its neighbours (the gate); at a surface the part along surfaceNormal is
// dropped; held to the limit.
WEIR_HD inline Vec3 shiftingDisplacement(const SphParams& p, const Vec3& gradient,
                                         const Vec3& surfaceNormal, bool atSurface, Real relative2,
                                         Real dt) {
    Real gate = Real(1);
    if (relative2 < p.shiftingGateSpeed * p.shiftingGateSpeed) {
        gate = relative2 > Real(0) ? relative2 * reciprocalSqrt(relative2) / p.shiftingGateSpeed
                                   : Real(0);
    }
    Vec3 shift = gradient * (-p.shifting * dt * gate);
    const Real n2 = lengthSquared(surfaceNormal);
    if (atSurface && n2 > Real(0)) {
        shift -= surfaceNormal * (dot(shift, surfaceNormal) / n2);
    }
    const Real s2 = lengthSquared(shift), limit2 = p.shiftingLimit * p.shiftingLimit;
    if (s2 > limit2) {
        shift *= p.shiftingLimit * reciprocalSqrt(s2);
    }
    return shift;
}

// Calls f(b, rVec, r2) for the boundary particles within h of x.
template <class F>
WEIR_HD inline void forEachBoundaryNeighbour(const BoundaryView& bv, const SphParams& p,
                                             const Vec3& x, F&& f) {
    const Real h2 = p.wendland.h2;
    bv.forEachNear(x, [&](Index b) {
        const Vec3 rVec = x - bv.pos[b].xyz();
        const Real r2 = lengthSquared(rVec);
        if (r2 < h2 && r2 > Real(0)) {
            f(b, rVec, r2);
        }
    });
}

}  // namespace weir
