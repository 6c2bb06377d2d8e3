// The pair terms of the delta-SPH fluid model (FluidModel::DeltaSph), written once for CPU and
// CUDA: for a fluid particle i and a neighbour j (fluid) or b (boundary particle), what they add
// to i's acceleration and to its density's rate of change.
//
//   pressure     a_i -= m_j (p_i / rho_i^2 + p_j / rho_j^2) grad W_ij          (symmetric form)
//   continuity   drho_i/dt += m_j (v_i - v_j) . grad W_ij
//   diffusion    drho_i/dt += delta c h 2 (rho_j - rho_i - rho^H_ji) (-g_ij) m_j / rho_j
//                (Molteni & Colagrossi 2009, with grad W = g r_vec; Fourtakas et al. 2019 leave
//                the hydrostatic part rho^H_ji = rho0 g . (x_j - x_i) / c^2 alone, so a tank at
//                rest keeps its hydrostatic density)
//   viscosity    a_i += m_j 2 mu / (rho_i rho_j) (r . grad W) / (r^2 + eta^2) (v_i - v_j)
//                (Morris, Fox & Zhu 1997: the fluid's own, laminar viscosity)
//   artificial   a_i -= m_j Pi_ij grad W_ij, Pi_ij = -alpha c (h/2) (v_ij . r) / ((r^2 + eta^2)
//                rho_ij) for approaching pairs only (Monaghan 1992, alpha small)
//
// Walls are boundary particles b (physics/boundary.h) that stand for the fluid beyond them:
// their pressure is the fluid particle's extrapolated hydrostatically to b,
// p_b = p_i + rho_i g . (x_b - x_i) (so the layer next to a wall feels the pressure the missing
// fluid would exert, and is not squeezed to twice hydrostatic), their velocity the wall's, and at
// no-slip walls the viscous term sees the velocity mirrored through the wall surface,
// v_i - v_b* = min(1.5, 1 + d_b / d_i) (v_i - v_wall) (Morris et al. 1997: d_b, d_i the distances
// of b and i from the wall surface).
#pragma once

#include <cmath>

#include "core/config.h"
#include "core/vec3.h"
#include "physics/boundary.h"
#include "physics/kernels.h"
#include "physics/sph_params.h"

namespace weir {

// One particle's rates, summed over its neighbours.
struct ParticleRates {
    Vec3 acceleration;
    Real densityRate = 0;
};

// Fluid neighbour j of fluid particle i: rVec = x_i - x_j, 0 < r2 < h^2; termI, termJ: p / rho^2.
WEIR_HD inline void addFluidNeighbour(const SphParams& p, const Vec3& rVec, Real r2, Real rhoi,
                                      Real rhoj, Real termI, Real termJ, const Vec3& vi,
                                      const Vec3& vj, ParticleRates& rates) {
    const Real r = r2 * reciprocalSqrt(r2);
    const Real g = p.wendland.gradientFactor(r);  // grad W = g rVec, g < 0
    const Vec3 vij = vi - vj;
    const Real vDotR = dot(vij, rVec);
    const Real volumeJ = p.mass * reciprocal(rhoj);
    const Real softened = reciprocal(r2 + p.viscositySoftening);
    // Pressure, then viscosity: the fluid's own (Morris) and, approaching, the artificial one.
    Real alongR = -p.mass * (termI + termJ) * g;
    if (vDotR < Real(0)) {
        alongR += p.artificialViscosity * vDotR * softened * Real(2) * p.mass *
                  reciprocal(rhoi + rhoj) * g;
    }
    const Real viscous =
        Real(2) * p.dynamicViscosity * volumeJ * reciprocal(rhoi) * g * r2 * softened;
    rates.acceleration += rVec * alongR + vij * viscous;
    // Continuity and density diffusion.
    const Real hydrostatic = -dot(p.hydrostaticGradient, rVec);  // rho^H_j - rho^H_i
    rates.densityRate += p.mass * g * vDotR -
                         p.densityDiffusion * Real(2) * (rhoj - rhoi - hydrostatic) * g * volumeJ;
}

// Boundary particle b of fluid particle i: rVec = x_i - x_b, 0 < r2 < h^2; psi the mass it stands
// for, normal (into the fluid) and depth (its distance behind the wall surface), wall velocity vb.
WEIR_HD inline void addBoundaryNeighbour(const SphParams& p, const Vec3& rVec, Real r2, Real rhoi,
                                         Real pi, Real termI, const Vec3& vi, Real psi,
                                         const Vec3& normal, Real depth, const Vec3& vb,
                                         ParticleRates& rates) {
    const Real r = r2 * reciprocalSqrt(r2);
    const Real g = p.wendland.gradientFactor(r);
    const Vec3 vib = vi - vb;
    // The pressure the fluid would have at b, hydrostatically from i's (never negative).
    Real pb = pi - rhoi * dot(p.gravity, rVec);
    pb = pb > Real(0) ? pb : Real(0);
    const Real invRho2 = reciprocal(rhoi * rhoi);
    Real alongR = -psi * (termI + pb * invRho2) * g;
    Vec3 viscousVelocity;
    if (p.noSlip) {
        const Real di = dot(rVec, normal) - depth;  // i's distance from the wall surface
        Real factor = di > Real(0) ? Real(1) + depth * reciprocal(di) : p.maxWallVelocityFactor;
        factor = factor < p.maxWallVelocityFactor ? factor : p.maxWallVelocityFactor;
        const Real softened = reciprocal(r2 + p.viscositySoftening);
        viscousVelocity = vib * (Real(2) * p.dynamicViscosity * psi * p.invRestDensity *
                                 reciprocal(rhoi) * g * r2 * softened * factor);
        const Real vDotR = dot(vib, rVec);
        if (vDotR < Real(0)) {
            alongR += p.artificialViscosity * vDotR * softened * psi * reciprocal(rhoi) * g;
        }
    }
    rates.acceleration += rVec * alongR + viscousVelocity;
    rates.densityRate += psi * g * dot(vib, rVec);
}

// What the boundary particles near fluid particle i add to its rates.
WEIR_HD inline void addBoundaryRates(const BoundaryView& bv, const SphParams& p, const Vec3& xi,
                                     const Vec3& vi, Real rhoi, Real pi, Real termI,
                                     ParticleRates& rates) {
    const Real h2 = p.wendland.h2;
    bv.forEachNear(xi, [&](Index b) {
        const Real4 pb = bv.pos[b];
        const Vec3 rVec = xi - pb.xyz();
        const Real r2 = lengthSquared(rVec);
        if (r2 < h2 && r2 > Real(0)) {
            const Real4 n = bv.normal[b];
            const Vec3 vb = bv.velocity != nullptr ? bv.velocity[b].xyz() : Vec3();
            addBoundaryNeighbour(p, rVec, r2, rhoi, pi, termI, vi, pb.w, n.xyz(), n.w, vb, rates);
        }
    });
}

}  // namespace weir
