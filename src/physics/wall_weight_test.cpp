// The simple walls' analytic share of the kernel beyond a plane agrees with the kernels summed
// over a fine lattice, and a particle of a lattice against a wall reads rest density with it.
#include "physics/wall_weight.h"

#include <gtest/gtest.h>

#include <cmath>

namespace weir {
namespace {

// Sums f(point) over a fine lattice of the half-space beyond a plane at distance q h (h = 1).
template <class F>
double sumBeyondPlane(double q, F f) {
    const int n = 80;
    const double step = 2.0 / n, cell = step * step * step;
    double sum = 0;
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
            for (int k = 0; k < n; ++k) {
                const Vec3 r(Real(-1 + (i + 0.5) * step), Real(-1 + (j + 0.5) * step),
                             Real(-1 + (k + 0.5) * step));
                if (r.x < -q) {  // the plane x = -q, the particle at the origin
                    sum += f(r) * cell;
                }
            }
        }
    }
    return sum;
}

TEST(WallWeight, Poly6BeyondPlaneMatchesTheKernelSummedOverTheHalfSpace) {
    const KernelCoefficients k = KernelCoefficients::forRadius(1.0);
    EXPECT_NEAR(poly6BeyondPlane(0), 0.5, 1e-6);
    EXPECT_EQ(poly6BeyondPlane(1), 0);
    EXPECT_EQ(poly6BeyondPlane(1.5), 0);
    for (double q : {0.0, 0.1, 0.25, 0.5, 0.75}) {
        const double sum =
            sumBeyondPlane(q, [&](const Vec3& r) { return double(poly6(k, lengthSquared(r))); });
        EXPECT_NEAR(poly6BeyondPlane(Real(q)), sum, 2e-3) << "q = " << q;
    }
}

TEST(WallWeight, SpikyGradientBeyondPlaneMatchesTheGradientSummedOverTheHalfSpace) {
    const KernelCoefficients k = KernelCoefficients::forRadius(1.0);
    EXPECT_NEAR(spikyGradientBeyondPlane(0), 1.5, 1e-6);
    EXPECT_EQ(spikyGradientBeyondPlane(1), 0);
    for (double q : {0.1, 0.25, 0.5, 0.75}) {
        // The gradient at the particle (origin) of W(0 - r), along the plane's normal: grad W is
        // g (x_i - x_b), and x_i - x_b = -r.
        const double sum = sumBeyondPlane(q, [&](const Vec3& r) {
            const double len = std::sqrt(double(lengthSquared(r)));
            return len < 1 ? double(spikyGradientFactor(k, Real(len))) * -double(r.x) : 0.0;
        });
        EXPECT_NEAR(spikyGradientBeyondPlane(Real(q)), -sum, 0.02) << "q = " << q;
    }
}

// A particle of a cubic lattice whose first layer sits d/2 from the wall reads rest density
// once the wall adds its share, at the ratios the sweep uses: within 3% from h = 2d; at 1.5 d the
// first layer reads 5.8% high (the lattice is too coarse a quadrature of so narrow a kernel).
TEST(WallWeight, LatticeAgainstTheWallReadsRestDensity) {
    for (double ratio : {1.5, 2.0, 3.0}) {
        const double d = 1.0, h = ratio * d;
        SphParams p;
        p.kernel = KernelCoefficients::forRadius(h);
        p.restDensity = 1000;
        p.boxMin = Vec3(0, -100, -100);
        p.boxMax = Vec3(100, 100, 100);
        const int reach = int(std::ceil(ratio)) + 1;
        double full = 0;
        for (int i = -reach; i <= reach; ++i) {
            for (int j = -reach; j <= reach; ++j) {
                for (int l = -reach; l <= reach; ++l) {
                    full += double(poly6(p.kernel, Real(i * i + j * j + l * l)));
                }
            }
        }
        const double mass = p.restDensity / full;  // the lattice at rest density, as in setup
        for (int layer = 0; layer < reach; ++layer) {
            const Vec3 x(Real((layer + 0.5) * d), 0, 0);
            double rho = 0;
            for (int i = -reach; i <= reach; ++i) {
                if ((layer + 0.5 + i) * d < 0) {
                    continue;  // behind the wall
                }
                for (int j = -reach; j <= reach; ++j) {
                    for (int l = -reach; l <= reach; ++l) {
                        rho += mass * double(poly6(p.kernel, Real(i * i + j * j + l * l)));
                    }
                }
            }
            rho += double(wallDensity(p, x));
            EXPECT_NEAR(rho / p.restDensity, 1.0, ratio < 2 ? 0.06 : 0.03)
                << "h/d = " << ratio << ", layer " << layer;
        }
    }
}

}  // namespace
}  // namespace weir
