// The container's planes under the simple walls (walls.model "simple"): the fluid that is not
// there. No particle stands behind these walls, so a fluid particle within h of one misses the
// kernel's share beyond it, reads light, gets no pressure and is pushed onto the wall by its
// neighbours: particles pile onto the wall planes and, worst, onto the edges where two meet (a
// quarter neighbourhood; measured: edges held 3-5x their lattice share at h = 3d), where they
// pack to 0.01-0.3 d and their pressure pushes them along the edge like a rail (jets of 3-5x
// the expected speed at 10k particles, past 10x at 100k). As Harada et al. 2007 ("wall weight"),
// each plane stands for a lattice of fluid particles beyond it (mass m, spacing d, layers d/2,
// 3d/2, ... behind it: the mirror of the seeded fluid) whose kernel sums, a function of the
// distance to the plane alone, are tabulated at set-up. The plane adds that lattice's density
// and pushes by the particle's own pressure times that density's gradient (wallAcceleration),
// with a barrier against reaching the plane (wallBarrier). The lattice sum and not the kernel's
// integral: the fluid's own sum is a lattice sum (the mass is calibrated on it), and at h = 2d
// the two differ by 2.6% of rho0 at the first layer (3.5% at edges and corners), which threw a
// small tank at rest off its walls.
// Edges and corners combine the planes as if the kernel were separable (exact at the edge and
// corner themselves for the continuum; on the lattice they read 0.6% and 1.5% light at h = 2d).
#pragma once

#include <algorithm>
#include <cmath>

#include "core/config.h"
#include "core/vec3.h"
#include "physics/kernels.h"

namespace weir {

// One plane's wall weight, sampled at steps of d / K (K even) from the plane out to h, so that
// the seeded layers (d/2, 3d/2, ...) fall on samples and read exactly; linear in between.
struct WallWeightTable {
    static constexpr int kMaxSamples = 65;
    int samples = 0;               // 0: no wall weight (the bare collision response)
    Real invStep = 0;              // 1 / sample step, 1/m
    Real share[kMaxSamples] = {};  // the lattice's density beyond the plane / rho0
    Real push[kMaxSamples] = {};   // -rho0 d share / ds: m sum of -grad W . n, kg/m^4
    Real barrierRange = 0;         // d/2: wallBarrier acts closer to the plane than this, m
    Real barrierAcceleration = 0;  // wallBarrier at the plane, m/s^2
};

// The table for smoothing radius h, spacing d, particle mass m and speed of sound c (host, at
// set-up): with the paper model's poly6, or with delta-SPH's Wendland kernel (its gradient as the
// fluid's, with the lattice-moment correction). The push is the share's own gradient, summed
// analytically over the same lattice, so that the planes do no net work on the fluid
// (wallAcceleration); the barrier is c^2 / d at the plane (wallBarrier; c = 0: none).
inline WallWeightTable wallWeightTable(double h, double d, double mass, double restDensity,
                                       double speedOfSound,
                                       const WendlandKernel* wendland = nullptr) {
    WallWeightTable t;
    t.barrierRange = Real(d / 2);
    t.barrierAcceleration = Real(speedOfSound * speedOfSound / d);
    const double ratio = h / d;
    const int k = std::max(2, 2 * int(std::floor(32 / ratio)));
    t.samples = std::min(WallWeightTable::kMaxSamples, int(std::ceil(ratio * k)) + 1);
    t.invStep = Real(k / d);
    const double poly6 = 315.0 / (64.0 * kPi * h * h * h);
    const int reach = int(std::floor(ratio));
    for (int m = 0; m < t.samples; ++m) {
        const double s = m * d / k;
        double w = 0, g = 0;
        for (int n = 0; s + (n + 0.5) * d < h; ++n) {
            const double a = s + (n + 0.5) * d;  // distance to the layer, along the normal
            for (int i = -reach; i <= reach; ++i) {
                for (int j = -reach; j <= reach; ++j) {
                    const double r2 = a * a + (i * i + j * j) * d * d;
                    if (r2 >= h * h) {
                        continue;
                    }
                    const double r = std::sqrt(r2);
                    if (wendland != nullptr) {  // grad W = gradientFactor r_vec
                        w += double(wendland->value(Real(r)));
                        g -= double(wendland->gradientFactor(Real(r))) * a;
                    } else {  // d/da poly6 (1 - r^2/h^2)^3 = -6 poly6 (1 - r^2/h^2)^2 a / h^2
                        const double u = 1 - r2 / (h * h);
                        w += poly6 * u * u * u;
                        g += 6 * poly6 * u * u * a / (h * h);
                    }
                }
            }
        }
        t.share[m] = Real(mass * w / restDensity);
        t.push[m] = Real(mass * g);
    }
    return t;
}

// The table at distance s from the plane (0 from the last sample on).
WEIR_HD inline void wallSample(const WallWeightTable& t, Real s, Real& share, Real& push) {
    const Real u = (s > Real(0) ? s : Real(0)) * t.invStep;
    const int j = int(u);
    if (j >= t.samples - 1) {
        share = push = Real(0);
        return;
    }
    const Real f = u - Real(j);
    share = t.share[j] + (t.share[j + 1] - t.share[j]) * f;
    push = t.push[j] + (t.push[j + 1] - t.push[j]) * f;
}

// The six planes of the container at x, lower then upper per axis: share and push of each.
// periodicAxes: bit a set, axis a has no planes (container.periodic): share and push 0.
WEIR_HD inline void wallSamples(const WallWeightTable& t, const Vec3& boxMin, const Vec3& boxMax,
                                const Vec3& x, Real share[6], Real push[6], int periodicAxes = 0) {
    for (int a = 0; a < 3; ++a) {
        if (((periodicAxes >> a) & 1) != 0) {
            share[2 * a] = push[2 * a] = share[2 * a + 1] = push[2 * a + 1] = Real(0);
            continue;
        }
        wallSample(t, x[a] - boxMin[a], share[2 * a], push[2 * a]);
        wallSample(t, boxMax[a] - x[a], share[2 * a + 1], push[2 * a + 1]);
    }
}

// Density the container's planes add at x: rho0 (1 - prod over planes of (1 - share)).
WEIR_HD inline Real wallDensity(const WallWeightTable& t, const Vec3& boxMin, const Vec3& boxMax,
                                Real restDensity, const Vec3& x, int periodicAxes = 0) {
    Real share[6], push[6];
    wallSamples(t, boxMin, boxMax, x, share, push, periodicAxes);
    Real inside = 1;
    for (int k = 0; k < 6; ++k) {
        inside *= Real(1) - share[k];
    }
    return restDensity * (Real(1) - inside);
}

// -grad of wallDensity at x: each plane's push along its inward normal times the share not
// beyond the other planes (the gradient of rho0 (1 - prod (1 - share))), kg/m^4.
WEIR_HD inline Vec3 wallPush(const WallWeightTable& t, const Vec3& boxMin, const Vec3& boxMax,
                             const Vec3& x, int periodicAxes = 0) {
    Vec3 g;
    Real share[6], push[6];
    wallSamples(t, boxMin, boxMax, x, share, push, periodicAxes);
    for (int k = 0; k < 6; ++k) {
        if (push[k] == Real(0)) {
            continue;
        }
        Real others = 1;
        for (int l = 0; l < 6; ++l) {
            others *= l == k ? Real(1) : Real(1) - share[l];
        }
        g[k / 2] += (k % 2 == 0 ? push[k] : -push[k]) * others;
    }
    return g;
}

// A particle closing on a plane meets the mirrored lattice's smooth density, not its own mirror
// image, so the share's gradient alone barely resists it: it reaches the plane (measured: 72 of
// 3072 particles of a tank at rest sat on one, and delta-SPH's tank churned at 0.033 m/s against
// the collision response). Within d/2 of a plane (the first layer's place: a lattice seeded
// against the walls feels none of it) a barrier pushes it off by c^2 / d (1 - 2 s / d)^2, a
// potential of the distance alone (it gives back what it takes), c^2 / 6 deep per unit mass: a
// particle must arrive at 0.58 c, 5.8x the expected speed, to reach the plane. The planes' barriers
// add. (Measured on the CPU stability sweep, delta-SPH: at 0.3 c^2 / d and at 3 c^2 / d the
// coarse wave tank, 600 particles at h = 3d, collapsed two particles onto one point, at 3 c^2 / d
// at corners of its obstacle staircase, where obstacles have only the collision response; at
// c^2 / d all 36 simple-wall cases pass.)
WEIR_HD inline Vec3 wallBarrier(const WallWeightTable& t, const Vec3& boxMin, const Vec3& boxMax,
                                const Vec3& x, int periodicAxes = 0) {
    Vec3 acc;
    if (t.barrierAcceleration <= Real(0)) {
        return acc;
    }
    const Real inv = Real(1) / t.barrierRange;
    for (int a = 0; a < 3; ++a) {
        if (((periodicAxes >> a) & 1) != 0) {
            continue;
        }
        const Real lo = Real(1) - (x[a] - boxMin[a]) * inv, hi = Real(1) - (boxMax[a] - x[a]) * inv;
        if (lo > Real(0)) {
            acc[a] += t.barrierAcceleration * (lo < Real(1) ? lo * lo : Real(1));
        }
        if (hi > Real(0)) {
            acc[a] -= t.barrierAcceleration * (hi < Real(1) ? hi * hi : Real(1));
        }
    }
    return acc;
}

// Acceleration of a fluid particle at x from the container's planes: -p_i / rho_i^2 times the
// gradient of the density they add (wallPush). That is the force the fluid's own Lagrangian gives
// a particle whose density holds a share that depends on its place alone: the work the planes
// do on it is what its pressure stores as the share changes (m p_i / rho_i^2 d rho_i), so a
// particle that leaves the wall weight gives back what it got going in. The earlier push, the
// spiky gradient's lattice sum by Akinci's rule, was 1.47x that gradient at the plane, 0.90x at
// d/2 and 0.58x at d: the planes did net work and a tank at rest rang at c / 4H (0.04 m/s mean
// speed, undamped, to 2 s; wall_defects_test.cpp). One pressure term, as the boundary particles
// have (physics/boundary.h); two terms, a mirrored pair of the symmetric form, would no longer be
// the share's gradient. Plus the barrier (wallBarrier), at any pressure.
WEIR_HD inline Vec3 wallAcceleration(const WallWeightTable& t, const Vec3& boxMin,
                                     const Vec3& boxMax, const Vec3& x, Real rhoi, Real pi,
                                     int periodicAxes = 0) {
    const Vec3 barrier = wallBarrier(t, boxMin, boxMax, x, periodicAxes);
    if (pi <= Real(0)) {
        return barrier;
    }
    return barrier + wallPush(t, boxMin, boxMax, x, periodicAxes) * (pi / (rhoi * rhoi));
}

// The rate of the density the planes add, for a particle at x moving at v: v . grad of it.
// With wallAcceleration, each other's adjoint (the continuity and momentum equations' wall terms
// conserve energy together).
WEIR_HD inline Real wallDensityRate(const WallWeightTable& t, const Vec3& boxMin,
                                    const Vec3& boxMax, const Vec3& x, const Vec3& v,
                                    int periodicAxes = 0) {
    return -dot(wallPush(t, boxMin, boxMax, x, periodicAxes), v);
}

}  // namespace weir
