// Test helpers for the surface tests: particles on a cubic lattice filling a ball or a box.
#pragma once

#include <cmath>
#include <random>

#include "core/vec3.h"
#include "solver/particles.h"

namespace weir::testing {

// Lattice points (multiples of d from a lattice anchor) inside the ball: a fluid ball of radius
// `radius` as the seeder fills it, each particle standing for a d^3 cube.
inline HostParticles latticeBall(const Vec3d& centre, double radius, double d,
                                 const Vec3d& anchor = Vec3d(0.31, 0.17, 0.23)) {
    HostParticles particles;
    const int reach = int(std::ceil(radius / d)) + 1;
    for (int k = -reach; k <= reach; ++k) {
        for (int j = -reach; j <= reach; ++j) {
            for (int i = -reach; i <= reach; ++i) {
                const Vec3d p = centre + (Vec3d(i, j, k) + anchor) * d;
                if (lengthSquared(p - centre) < radius * radius) {
                    particles.push(p, Vec3d());
                }
            }
        }
    }
    return particles;
}

// A box of counts[0] x counts[1] x counts[2] particles at the centres of d-cubes from boxMin: the
// fluid fills [boxMin, boxMin + counts * d].
inline HostParticles latticeBox(const Vec3d& boxMin, const int counts[3], double d) {
    HostParticles particles;
    for (int k = 0; k < counts[2]; ++k) {
        for (int j = 0; j < counts[1]; ++j) {
            for (int i = 0; i < counts[0]; ++i) {
                particles.push(boxMin + (Vec3d(i, j, k) + Vec3d(0.5, 0.5, 0.5)) * d, Vec3d());
            }
        }
    }
    return particles;
}

// Moves every particle by up to `amplitude` along each axis, uniformly at random (x, y, z of
// each particle in turn from rng).
inline void jitterPositions(HostParticles& particles, std::mt19937& rng, double amplitude) {
    std::uniform_real_distribution<double> jitter(-amplitude, amplitude);
    for (std::size_t i = 0; i < particles.size(); ++i) {
        particles.x[i] += Real(jitter(rng));
        particles.y[i] += Real(jitter(rng));
        particles.z[i] += Real(jitter(rng));
    }
}

// Adds the positions of `more` to `particles`, at rest.
inline void appendPositions(HostParticles& particles, const HostParticles& more) {
    for (std::size_t i = 0; i < more.size(); ++i) {
        particles.push(Vec3d(more.x[i], more.y[i], more.z[i]), Vec3d());
    }
}

constexpr double kPiForTests = 3.14159265358979323846;

}  // namespace weir::testing
