// The scalar field the surface is the iso-surface of: Zhu & Bridson's (2005) distance to the
// kernel-weighted mean of nearby particle positions, sampled from particles sorted into bins.
#pragma once

#include <cmath>

#include "core/config.h"
#include "core/vec3.h"
#include "grid/cell_walk.h"

namespace weir {

// Particles sorted by bin (grid/dense_grid.h), looked up around any point in space.
struct ParticleBinsView {
    CellTableView bins;  // bins + 1 bounds: particles of bin b are [cellBound[b], cellBound[b + 1])
    const Real4* pos;    // positions in bin order
    int reach;           // bins per search radius, rounded up

    // Calls f(j) for each particle j that can lie within sqrt(radius2) of p: rows of bins whose
    // slab is out of reach are skipped and each row is cut to the chord of the sphere.
    template <class F>
    WEIR_HD void forEachNear(const Vec3& p, Real radius2, F&& f) const {
        bins.forEachRun<true>(p, reach, radius2, [&](Index first, Index end) {
            for (Index j = first; j < end; ++j) {
                f(j);
            }
        });
    }
};

// phi(x) = (|x - xbar(x)| - r) / d, with xbar the mean of the particle positions weighted by
// k(s) = (1 - s^2)^3, s = |x - x_j| / R (R the kernel radius, r the particle radius, d the
// particle spacing). Negative in the fluid, zero on its surface, positive outside; far from every
// particle it is (R - r) / d, the value it tends to at the edge of the kernel's reach.
struct ZhuBridsonField {
    ParticleBinsView particles;
    Real kernelRadius2;
    Real inverseKernelRadius2;
    Real particleRadius;
    Real inverseSpacing;
    Real farValue;

    // The value beyond every particle's reach.
    WEIR_HD float valueFarAway() const { return float(farValue); }

    WEIR_HD float valueAt(const Vec3& x) const {
        Real weightSum = 0;
        Vec3 weightedOffset;  // sum of k_j (x_j - x): the mean taken relative to x keeps precision
        particles.forEachNear(x, kernelRadius2, [&](Index j) {
            const Vec3 offset = particles.pos[j].xyz() - x;
            const Real r2 = lengthSquared(offset);
            if (r2 < kernelRadius2) {
                const Real s = Real(1) - r2 * inverseKernelRadius2;
                const Real weight = s * s * s;
                weightSum += weight;
                weightedOffset += offset * weight;
            }
        });
        if (!(weightSum > Real(0))) {
            return float(farValue);
        }
        const Vec3 meanOffset = weightedOffset / weightSum;
        return float((length(meanOffset) - particleRadius) * inverseSpacing);
    }
};

// The particle radius r, in particle spacings, for which a flat surface of a cubic lattice lies
// half a spacing beyond its outer layer (where the fluid's volume ends), for kernel radius
// R = ratio * d. Seen from that height the layers are at distances a_k = (k + 1/2) d and a layer
// weighs (1 - a_k^2 / R^2)^4 (the kernel integrated over the plane), so xbar lies at the
// weighted mean of the a_k; r is that distance. About 0.545 for ratio 2.
inline double zhuBridsonParticleRadius(double ratio) {
    double weightSum = 0, distanceSum = 0;
    for (int k = 0; k + 0.5 < ratio; ++k) {
        const double a = (k + 0.5) / ratio;
        const double weight = std::pow(1 - a * a, 4);
        weightSum += weight;
        distanceSum += weight * (k + 0.5);
    }
    return distanceSum / weightSum;
}

}  // namespace weir
