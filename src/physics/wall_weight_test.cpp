// The simple walls' wall weight: its table tends to the kernel's integral beyond a plane as the
// lattice gets finer, a lattice seeded against the walls reads rest density with it, its push is
// the gradient of the density it adds (no net work), and the barrier keeps particles off the plane.
#include "physics/wall_weight.h"

#include <gtest/gtest.h>

#include <cmath>

namespace weir {
namespace {

// Continuum references (h = 1): poly6's mass beyond a plane at distance q, 315/256 (128/315 -
// P(q)) with P(q) the integral of (1 - t^2)^4 from 0 to q; and its gradient's normal component
// integrated over that half-space, minus the derivative of the former: 315/256 (1 - q^2)^4.
double poly6BeyondPlane(double q) {
    const double q2 = q * q;
    const double p = q * (1 - q2 * (4.0 / 3 - q2 * (6.0 / 5 - q2 * (4.0 / 7 - q2 / 9))));
    return q >= 1 ? 0 : 315.0 / 256 * (128.0 / 315 - p);
}
double poly6GradientBeyondPlane(double q) {
    const double u = 1 - q * q;
    return q >= 1 ? 0 : 315.0 / 256 * u * u * u * u;
}

// poly6 summed over the full lattice (spacing 1, radius ratio), as the set-up calibrates the mass.
double fullLatticeSum(double ratio) {
    const KernelCoefficients k = KernelCoefficients::forRadius(ratio);
    const int reach = int(std::ceil(ratio));
    double sum = 0;
    for (int i = -reach; i <= reach; ++i) {
        for (int j = -reach; j <= reach; ++j) {
            for (int l = -reach; l <= reach; ++l) {
                sum += double(poly6(k, Real(i * i + j * j + l * l)));
            }
        }
    }
    return sum;
}

TEST(WallWeight, TableTendsToTheKernelIntegralBeyondThePlane) {
    const double h = 1, d = h / 8, rho0 = 1000, mass = rho0 * d * d * d / fullLatticeSum(8);
    const WallWeightTable t = wallWeightTable(h, d, mass, rho0, 0);
    ASSERT_GT(t.samples, 1);
    for (double q : {0.0, 0.1, 0.25, 0.5, 0.75}) {
        Real share, push;
        wallSample(t, Real(q * h), share, push);
        EXPECT_NEAR(share, poly6BeyondPlane(q), 0.01) << "q = " << q;
        EXPECT_NEAR(push / (rho0 / h), poly6GradientBeyondPlane(q), 0.01) << "q = " << q;
    }
    Real share, push;
    wallSample(t, Real(h), share, push);
    EXPECT_EQ(share, 0);
    EXPECT_EQ(push, 0);
}

// A particle of a cubic lattice seeded against the walls (first layer d/2 from each) reads rest
// density: exactly at a single wall, where the table is the lattice beyond it; at edges and
// corners, where the planes combine as if the kernel were separable, up to 2% light (a light
// particle gets no pressure and is not pushed; a heavy one would be) and never heavy.
TEST(WallWeight, LatticeAgainstTheWallsReadsRestDensity) {
    for (double ratio : {1.5, 2.0, 3.0}) {
        const double d = 1.0, h = ratio * d, rho0 = 1000;
        const KernelCoefficients k = KernelCoefficients::forRadius(h);
        const double mass = rho0 / fullLatticeSum(ratio);
        const WallWeightTable t = wallWeightTable(h, d, mass, rho0, 0);
        const Vec3 boxMin(0, 0, 0), boxMax(100, 100, 100);
        const int reach = int(std::ceil(ratio)) + 1;
        for (int walls = 1; walls <= 3; ++walls) {
            for (int layer = 0; layer < reach; ++layer) {
                // At `layer` from the x wall, and on the first layer of the others in play.
                const double at[3] = {layer + 0.5, walls > 1 ? 0.5 : 50.5, walls > 2 ? 0.5 : 50.5};
                double rho = 0;
                for (int i = -reach; i <= reach; ++i) {
                    for (int j = -reach; j <= reach; ++j) {
                        for (int l = -reach; l <= reach; ++l) {
                            if (at[0] + i < 0 || at[1] + j < 0 || at[2] + l < 0) {
                                continue;  // behind a wall
                            }
                            rho += mass * double(poly6(k, Real(i * i + j * j + l * l)));
                        }
                    }
                }
                rho +=
                    double(wallDensity(t, boxMin, boxMax, Real(rho0), Vec3(at[0], at[1], at[2])));
                SCOPED_TRACE("h/d = " + std::to_string(ratio) + ", " + std::to_string(walls) +
                             " wall(s), layer " + std::to_string(layer));
                if (walls == 1) {
                    EXPECT_NEAR(rho / rho0, 1.0, 1e-4);
                } else {
                    EXPECT_LT(rho / rho0, 1.0 + 1e-4);
                    EXPECT_GT(rho / rho0, 0.975);
                }
            }
        }
    }
}

// The push is minus the gradient of the density the planes add, for both kernels, at edges and
// corners too (where the planes combine), and the density rate is its adjoint: a particle moved
// through the wall weight and back out is given back the work its pressure took (the planes did
// the tank at rest's ringing when the push was the spiky gradient's sum, 1.47x the share's gradient
// at the plane, 0.90x at d/2, 0.58x at d).
TEST(WallWeight, PushIsTheGradientOfTheShare) {
    for (double ratio : {1.5, 2.0, 3.0}) {
        const double d = 1, h = ratio * d, rho0 = 1000;
        const WendlandKernel wendland = WendlandKernel::forRadius(h);
        for (const WendlandKernel* kernel : {(const WendlandKernel*)nullptr, &wendland}) {
            const WallWeightTable t =
                wallWeightTable(h, d, rho0 / fullLatticeSum(ratio), rho0, 0, kernel);
            const Vec3 boxMin(0, 0, 0), boxMax(100, 100, 100);
            const double eps = 1e-3;
            for (const Vec3& x : {Vec3(0.3f, 50, 50), Vec3(0.8f, 50, 50), Vec3(1.3f, 0.7f, 50),
                                  Vec3(0.4f, 0.9f, 99.4f)}) {
                const Vec3 push = wallPush(t, boxMin, boxMax, x);
                for (int a = 0; a < 3; ++a) {
                    Vec3 up = x, down = x;
                    up[a] += Real(eps);
                    down[a] -= Real(eps);
                    const double slope =
                        (double(wallDensity(t, boxMin, boxMax, Real(rho0), up)) -
                         double(wallDensity(t, boxMin, boxMax, Real(rho0), down))) /
                        (2 * eps);
                    SCOPED_TRACE("h/d = " + std::to_string(ratio) +
                                 (kernel != nullptr ? " Wendland" : " poly6") + ", axis " +
                                 std::to_string(a));
                    // Linear interpolation between samples d / K apart: within a few percent of
                    // the push at the plane.
                    EXPECT_NEAR(-slope, double(push[a]), 0.03 * double(t.push[0]));
                }
                const Vec3 v(0.3f, -0.5f, 0.2f);
                EXPECT_FLOAT_EQ(wallDensityRate(t, boxMin, boxMax, x, v), -dot(push, v));
            }
        }
    }
}

// The push points into the fluid, grows towards the wall, and is off without pressure.
TEST(WallWeight, PushesAwayFromTheWallByTheParticlesOwnPressure) {
    const double h = 2, d = 1, rho0 = 1000;
    const WallWeightTable t = wallWeightTable(h, d, rho0 / fullLatticeSum(2), rho0, 0);
    const Vec3 boxMin(0, 0, 0), boxMax(100, 100, 100);
    const Vec3 nearFloor = wallAcceleration(t, boxMin, boxMax, Vec3(50, 0.5, 50), 1000, 500);
    const Vec3 atFloor = wallAcceleration(t, boxMin, boxMax, Vec3(50, 0.1, 50), 1000, 500);
    EXPECT_GT(nearFloor.y, 0);
    EXPECT_GT(atFloor.y, nearFloor.y);
    EXPECT_EQ(nearFloor.x, 0);
    EXPECT_EQ(nearFloor.z, 0);
    const Vec3 nearCeiling = wallAcceleration(t, boxMin, boxMax, Vec3(50, 99.5, 50), 1000, 500);
    EXPECT_FLOAT_EQ(nearCeiling.y, -nearFloor.y);
    EXPECT_EQ(lengthSquared(wallAcceleration(t, boxMin, boxMax, Vec3(50, 0.5, 50), 990, 0)), 0);
    EXPECT_EQ(lengthSquared(wallAcceleration(t, boxMin, boxMax, Vec3(50, 50, 50), 1000, 500)), 0);
}

// The barrier: off from d/2 on (a lattice seeded against the walls feels none of it), pushing
// into the fluid closer in, at every particle's pressure (the potential of the distance alone:
// it gives back what it takes).
TEST(WallWeight, BarrierKeepsParticlesOffThePlanes) {
    const double h = 2, d = 1, rho0 = 1000, c = 10, barrier = c * c / d;
    const WallWeightTable t = wallWeightTable(h, d, rho0 / fullLatticeSum(2), rho0, c);
    const Vec3 boxMin(0, 0, 0), boxMax(100, 100, 100);
    EXPECT_EQ(lengthSquared(wallBarrier(t, boxMin, boxMax, Vec3(50, 0.5f, 50))), 0);
    EXPECT_EQ(lengthSquared(wallBarrier(t, boxMin, boxMax, Vec3(50, 50, 50))), 0);
    const Vec3 atFloor = wallBarrier(t, boxMin, boxMax, Vec3(50, 0, 50));
    EXPECT_FLOAT_EQ(atFloor.y, Real(barrier));
    const Vec3 inCorner = wallAcceleration(t, boxMin, boxMax, Vec3(0.25f, 0.25f, 99.75f), 990, 0);
    EXPECT_FLOAT_EQ(inCorner.x, Real(barrier / 4));
    EXPECT_FLOAT_EQ(inCorner.y, Real(barrier / 4));
    EXPECT_FLOAT_EQ(inCorner.z, -Real(barrier / 4));
}

}  // namespace
}  // namespace weir
