// The container's planes under the simple walls (walls.model "simple"): the fluid that is not
// there. No particle stands behind these walls, so a fluid particle within h of one misses the
// kernel's share beyond it, reads light, gets no pressure and is pushed onto the wall by its
// neighbours: particles pile onto the wall planes and, worst, onto the edges where two meet (a
// quarter neighbourhood; measured: edges held 3-5x their lattice share at h = 3d), where they
// pack to 0.01-0.3 d and their pressure pushes them along the edge like a rail (jets of 3-5x
// the expected speed at 10k particles, past 10x at 100k). As Harada et al. 2007 ("wall weight"),
// the missing share is added analytically: the wall stands for rest-density fluid beyond the
// plane, adds rho0 times poly6's mass beyond it to the density, and pushes by the particle's own
// pressure as Akinci's boundary particles do (physics/boundary.h), with the spiky gradient
// integrated over the half-space. Edges and corners combine the planes as if the kernel were
// separable: exact for the quarter and eighth at the edge and corner themselves.
#pragma once

#include "core/config.h"
#include "core/vec3.h"
#include "physics/kernels.h"
#include "physics/sph_params.h"

namespace weir {

// Share of poly6's mass beyond a plane at distance q h (0 <= q): 1/2 at q = 0, 0 from q = 1.
// 315/256 (128/315 - P(q)), P(q) = integral of (1 - t^2)^4 from 0 to q.
WEIR_HD inline Real poly6BeyondPlane(Real q) {
    if (q >= Real(1)) {
        return Real(0);
    }
    q = q > Real(0) ? q : Real(0);
    const Real q2 = q * q;
    const Real p =
        q * (Real(1) -
             q2 * (Real(4.0 / 3) - q2 * (Real(6.0 / 5) - q2 * (Real(4.0 / 7) - q2 * Real(1.0 / 9)))));
    return Real(315.0 / 256) * (Real(128.0 / 315) - p);
}

// |integral of the spiky gradient over the half-space beyond a plane at distance q h| times h:
// by the divergence theorem, the spiky kernel integrated over that plane, 30 (w^4 / 4 - w^5 / 5)
// with w = 1 - q (1.5 at q = 0, 0 from q = 1).
WEIR_HD inline Real spikyGradientBeyondPlane(Real q) {
    if (q >= Real(1)) {
        return Real(0);
    }
    const Real w = q > Real(0) ? Real(1) - q : Real(1);
    const Real w4 = w * w * w * w;
    return Real(30) * w4 * (Real(0.25) - Real(0.2) * w);
}

// Distances (in h) from x to the six planes of the container, lower then upper per axis.
WEIR_HD inline void wallDistances(const SphParams& p, const Vec3& x, Real q[6]) {
    for (int a = 0; a < 3; ++a) {
        q[2 * a] = (x[a] - p.boxMin[a]) * p.kernel.invH;
        q[2 * a + 1] = (p.boxMax[a] - x[a]) * p.kernel.invH;
    }
}

// Density the container's planes add at x: rho0 (1 - prod over planes of (1 - beyond)).
WEIR_HD inline Real wallDensity(const SphParams& p, const Vec3& x) {
    Real q[6];
    wallDistances(p, x, q);
    Real inside = 1;
    for (int k = 0; k < 6; ++k) {
        inside *= Real(1) - poly6BeyondPlane(q[k]);
    }
    return p.restDensity * (Real(1) - inside);
}

// Acceleration of a fluid particle at x from the container's planes: its pressure mirrored,
// rho0 (p_i / rho_i^2) times the spiky gradient beyond each plane, along the plane's inward
// normal, less the share beyond the other planes (counted there).
WEIR_HD inline Vec3 wallAcceleration(const SphParams& p, const Vec3& x, Real rhoi, Real pi) {
    Vec3 acc;
    if (pi <= Real(0)) {
        return acc;
    }
    Real q[6], beyond[6];
    wallDistances(p, x, q);
    for (int k = 0; k < 6; ++k) {
        beyond[k] = poly6BeyondPlane(q[k]);
    }
    const Real scale = p.restDensity * pi / (rhoi * rhoi) * p.kernel.invH;
    for (int k = 0; k < 6; ++k) {
        if (beyond[k] == Real(0)) {
            continue;
        }
        Real others = 1;
        for (int l = 0; l < 6; ++l) {
            others *= l == k ? Real(1) : Real(1) - beyond[l];
        }
        acc[k / 2] += (k % 2 == 0 ? scale : -scale) * spikyGradientBeyondPlane(q[k]) * others;
    }
    return acc;
}

}  // namespace weir
