// particleVelocityAt: particle bins (grid/dense_grid.h) and the bins' walk of the surface field.
#include "surface/point_velocity.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "core/exec_cpu.h"
#include "grid/dense_grid.h"
#include "surface/surface_field.h"

namespace weir {

std::vector<Vec3f> particleVelocityAt(const HostParticles& particles,
                                      const std::vector<Vec3f>& points, double radius) {
    if (!(radius > 0) || !std::isfinite(radius)) {
        throw std::invalid_argument("velocity radius is " + std::to_string(radius) +
                                    ", must be a length > 0");
    }
    std::vector<Vec3f> velocities(points.size(), Vec3f(0, 0, 0));
    const Index n = Index(particles.size());
    if (n == 0 || points.empty()) {
        return velocities;
    }
    Vec3d lo(particles.x[0], particles.y[0], particles.z[0]), hi = lo;
    std::vector<Real4> hostPos(static_cast<std::size_t>(n));
    for (Index i = 0; i < n; ++i) {
        const Vec3d p(particles.x[i], particles.y[i], particles.z[i]);
        for (int a = 0; a < 3; ++a) {
            lo[a] = std::min(lo[a], p[a]);
            hi[a] = std::max(hi[a], p[a]);
        }
        hostPos[std::size_t(i)] = {particles.x[i], particles.y[i], particles.z[i], 0};
    }
    // Bins of radius / 2, as the surface field's are of R / 2 (surface_pipeline.h).
    CpuExec exec;
    const double binSize = radius / 2;
    HostBuffer<Real4> pos, sortedPos(static_cast<std::size_t>(n));
    exec.upload(pos, hostPos.data(), hostPos.size());
    const GridSpec spec =
        makeGridSpec(lo, hi + Vec3d(1, 1, 1) * (1e-6 * binSize), binSize, 1 << 21);
    DenseGrid<CpuExec> bins(spec, 1);
    bins.build(exec, pos.data(), n);
    const Index* permutation = bins.permutation();
    for (Index k = 0; k < n; ++k) {
        sortedPos.data()[k] = pos.data()[permutation[k]];
    }
    const ParticleBinsView near{bins.cells(), sortedPos.data(), 2};
    const Real radius2 = Real(radius * radius);
    const Real inverseRadius2 = Real(1 / (radius * radius));
    exec.forEach(Index(points.size()), [&](Index v) {
        const Vec3f& at = points[std::size_t(v)];
        const Vec3 x(Real(at.x), Real(at.y), Real(at.z));
        Real weightSum = 0;
        Vec3 sum;
        near.forEachNear(x, radius2, [&](Index j) {
            const Real r2 = lengthSquared(near.pos[j].xyz() - x);
            if (r2 < radius2) {
                const Real s = Real(1) - r2 * inverseRadius2;
                const Real weight = s * s * s;
                const std::size_t i = std::size_t(permutation[j]);  // its index in particles
                weightSum += weight;
                sum += Vec3(particles.vx[i], particles.vy[i], particles.vz[i]) * weight;
            }
        });
        if (weightSum > Real(0)) {
            const Vec3 mean = sum / weightSum;
            velocities[std::size_t(v)] = Vec3f(float(mean.x), float(mean.y), float(mean.z));
        }
    });
    return velocities;
}

}  // namespace weir
