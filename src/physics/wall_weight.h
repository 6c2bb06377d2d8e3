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
// and pushes by the particle's own pressure as Akinci's boundary particles do
// (physics/boundary.h). The lattice sum and not the kernel's integral: the fluid's own sum is a
// lattice sum (the mass is calibrated on it), and at h = 2d the two differ by 2.6% of rho0 at
// the first layer (3.5% at edges and corners), which threw a small tank at rest off its walls.
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
    Real push[kMaxSamples] = {};   // m sum of -grad W . n over it (n into the fluid), kg/m^4
};

// The table for smoothing radius h, spacing d and particle mass m (host, at set-up).
inline WallWeightTable wallWeightTable(double h, double d, double mass, double restDensity) {
    WallWeightTable t;
    const double ratio = h / d;
    const int k = std::max(2, 2 * int(std::floor(32 / ratio)));
    t.samples = std::min(WallWeightTable::kMaxSamples, int(std::ceil(ratio * k)) + 1);
    t.invStep = Real(k / d);
    const double poly6 = 315.0 / (64.0 * kPi * h * h * h), spiky = 45.0 / (kPi * h * h * h * h);
    const int reach = int(std::floor(ratio));
    for (int m = 0; m < t.samples; ++m) {
        const double s = m * d / k;
        double w = 0, g = 0;
        for (int n = 0; s + (n + 0.5) * d < h; ++n) {
            const double a = s + (n + 0.5) * d;  // distance to the layer, along the normal
            for (int i = -reach; i <= reach; ++i) {
                for (int j = -reach; j <= reach; ++j) {
                    const double r2 = a * a + (i * i + j * j) * d * d;
                    if (r2 < h * h) {
                        const double r = std::sqrt(r2), u = 1 - r2 / (h * h), v = 1 - r / h;
                        w += poly6 * u * u * u;
                        g += spiky * v * v * a / r;
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

// Acceleration of a fluid particle at x from the container's planes: Akinci's term with the
// pressure mirrored, p_i / rho_i^2 times each plane's push along its inward normal, less the share
// beyond the other planes (counted there). One pressure term, as the boundary particles have
// (physics/boundary.h), not the two a mirrored pair of the symmetric form would have: the fluid
// pushes the wall-side layer in until it is compressed to about twice its neighbours' pressure
// (tank at rest, h = 2d: 2437 Pa at the floor layer, 1058 Pa one layer up, 1430 Pa hydrostatic),
// but with two terms the same tank drifted sideways (95% of particles moved 5.9 cm in 1.5 s,
// against 1.3 cm with one) and failed the rest-state test.
WEIR_HD inline Vec3 wallAcceleration(const WallWeightTable& t, const Vec3& boxMin,
                                     const Vec3& boxMax, const Vec3& x, Real rhoi, Real pi,
                                     int periodicAxes = 0) {
    Vec3 acc;
    if (pi <= Real(0)) {
        return acc;
    }
    Real share[6], push[6];
    wallSamples(t, boxMin, boxMax, x, share, push, periodicAxes);
    const Real scale = pi / (rhoi * rhoi);
    for (int k = 0; k < 6; ++k) {
        if (push[k] == Real(0)) {
            continue;
        }
        Real others = 1;
        for (int l = 0; l < 6; ++l) {
            others *= l == k ? Real(1) : Real(1) - share[l];
        }
        acc[k / 2] += (k % 2 == 0 ? scale : -scale) * push[k] * others;
    }
    return acc;
}

}  // namespace weir
