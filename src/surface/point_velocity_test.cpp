// Tests for particleVelocityAt: the kernel-weighted mean of the particles' velocities, zero out of
// reach, the same for any particle order.
#include "surface/point_velocity.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace weir {
namespace {

// A 12^3 lattice at 1 cm with velocity (x, -2, 3 z).
HostParticles lattice() {
    HostParticles particles;
    for (int i = 0; i < 12; ++i) {
        for (int j = 0; j < 12; ++j) {
            for (int k = 0; k < 12; ++k) {
                const double x = 0.01 * i, y = 0.01 * j, z = 0.01 * k;
                particles.push({x, y, z}, {x, -2, 3 * z});
            }
        }
    }
    return particles;
}

TEST(PointVelocity, SymmetricNeighbourhoodsGiveTheLinearFieldsValue) {
    const std::vector<Vec3f> points = {{0.055f, 0.055f, 0.055f}, {0.05f, 0.06f, 0.04f}};
    const auto v = particleVelocityAt(lattice(), points, 0.02);
    ASSERT_EQ(v.size(), 2u);
    for (std::size_t p = 0; p < points.size(); ++p) {
        EXPECT_NEAR(v[p].x, points[p].x, 1e-5) << p;
        EXPECT_NEAR(v[p].y, -2, 1e-5) << p;
        EXPECT_NEAR(v[p].z, 3 * points[p].z, 1e-5) << p;
    }
}

TEST(PointVelocity, OutOfReachIsZeroAndOrderDoesNotMatter) {
    HostParticles particles = lattice();
    const std::vector<Vec3f> points = {{0.5f, 0.5f, 0.5f}, {0.115f, 0.03f, 0.02f}};
    const auto v = particleVelocityAt(particles, points, 0.02);
    EXPECT_EQ(v[0].x, 0);
    EXPECT_EQ(v[0].y, 0);
    EXPECT_EQ(v[0].z, 0);
    EXPECT_NEAR(v[1].y, -2, 1e-5);
    EXPECT_LT(v[1].x, 0.115f);  // at the edge only particles inside weigh in
    EXPECT_GT(v[1].x, 0.09f);
    // Reversed particle order: the same means (up to the sums' rounding).
    HostParticles reversed;
    for (std::size_t i = particles.size(); i-- > 0;) {
        reversed.push({particles.x[i], particles.y[i], particles.z[i]},
                      {particles.vx[i], particles.vy[i], particles.vz[i]});
    }
    const auto w = particleVelocityAt(reversed, points, 0.02);
    EXPECT_NEAR(w[1].x, v[1].x, 1e-6);
    EXPECT_NEAR(w[1].z, v[1].z, 1e-6);
    EXPECT_THROW(particleVelocityAt(particles, points, 0), std::invalid_argument);
}

}  // namespace
}  // namespace weir
