// Kernel normalisation and shape: sum W V = 1 on a lattice, sum grad W V = 0, signs and support.
#include "physics/kernels.h"

#include <gtest/gtest.h>

#include <cmath>

#include "physics/kernels.h"

namespace weir {
namespace {

// Sums over a cubic lattice of spacing d around a point at fractional offset `shift`.
struct LatticeSums {
    double w = 0;
    double grad[3] = {0, 0, 0};
};

LatticeSums latticeSums(double ratio, double d, const double shift[3]) {
    KernelCoefficients k = KernelCoefficients::forRadius(ratio * d);
    LatticeSums s;
    int reach = int(std::ceil(ratio)) + 1;
    for (int i = -reach; i <= reach; ++i) {
        for (int j = -reach; j <= reach; ++j) {
            for (int l = -reach; l <= reach; ++l) {
                double r[3] = {(i + shift[0]) * d, (j + shift[1]) * d, (l + shift[2]) * d};
                double r2 = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
                s.w += poly6(k, Real(r2)) * d * d * d;
                double rr = std::sqrt(r2);
                if (rr > 0 && rr < ratio * d) {
                    double g = spikyGradientFactor(k, Real(rr));
                    for (int a = 0; a < 3; ++a) {
                        s.grad[a] += g * r[a] * d * d * d;
                    }
                }
            }
        }
    }
    return s;
}

TEST(Kernels, Poly6SumsToOneOnALattice) {
    // sum_j W(x - x_j) V_j -> 1 as the lattice refines; within a few percent at usual ratios.
    const double centre[3] = {0, 0, 0};
    for (double ratio : {2.0, 2.5, 3.0, 4.0}) {
        EXPECT_NEAR(latticeSums(ratio, 0.01, centre).w, 1.0, 0.015) << "h/d = " << ratio;
    }
    EXPECT_NEAR(latticeSums(6.0, 0.01, centre).w, 1.0, 1e-3);
}

TEST(Kernels, LatticeSumMatchesSetupAndGivesRestDensity) {
    const double centre[3] = {0, 0, 0};
    for (double ratio : {1.5, 2.0, 3.0}) {
        double sum = latticeKernelSum(ratio);
        EXPECT_NEAR(sum, latticeSums(ratio, 1.0, centre).w, 1e-5);
        // With the calibrated mass m = rho0 d^3 / sum, sum_j m W = rho0 exactly on the lattice.
        double rho0 = 1000, d = 0.02, mass = rho0 * d * d * d / sum;
        EXPECT_NEAR(mass * latticeSums(ratio, d, centre).w / (d * d * d), rho0, 1e-2);
    }
}

TEST(Kernels, GradientSumsToZeroOnASymmetricLattice) {
    const double centre[3] = {0, 0, 0};
    for (double ratio : {2.0, 3.0}) {
        LatticeSums s = latticeSums(ratio, 0.01, centre);
        for (double g : s.grad) {
            EXPECT_NEAR(g, 0.0, 1e-6);
        }
    }
    // Off a lattice site the sum approximates the gradient of a constant: small against 1/h,
    // and smaller for wider kernels.
    const double shifted[3] = {0.3, 0.1, 0.45};
    double previous = 1e9;
    for (double ratio : {2.0, 3.0, 4.0}) {
        LatticeSums s = latticeSums(ratio, 0.01, shifted);
        double magnitude =
            std::sqrt(s.grad[0] * s.grad[0] + s.grad[1] * s.grad[1] + s.grad[2] * s.grad[2]) *
            (ratio * 0.01);
        EXPECT_LT(magnitude, previous) << "h/d = " << ratio;
        previous = magnitude;
    }
    EXPECT_LT(previous, 0.1);  // at h = 4d
}

TEST(Kernels, ShapeAndSupport) {
    KernelCoefficients k = KernelCoefficients::forRadius(0.1);
    EXPECT_GT(poly6(k, 0), poly6(k, Real(0.0025)));
    EXPECT_EQ(poly6(k, Real(0.01)), 0);  // r = h
    EXPECT_EQ(poly6(k, Real(0.02)), 0);  // r > h
    // Spiky gradient factor is negative: grad W points from i towards j, so pressure pushes apart.
    EXPECT_LT(spikyGradientFactor(k, Real(0.05)), 0);
    EXPECT_LT(std::fabs(spikyGradientFactor(k, Real(0.0999))),
              1e-5 * std::fabs(spikyGradientFactor(k, Real(0.05))));
    // Viscosity Laplacian is positive and vanishes at h.
    EXPECT_GT(viscosityLaplacian(k, Real(0.05)), 0);
    EXPECT_NEAR(viscosityLaplacian(k, Real(0.1)), 0, 1e-3);
    // Magnitudes against the closed forms at r = h/2.
    double h = 0.1, r = 0.05;
    EXPECT_NEAR(poly6(k, Real(r * r)),
                315.0 / (64 * kPi * std::pow(h, 9)) * std::pow(h * h - r * r, 3),
                1e-3 * poly6(k, Real(r * r)));
    EXPECT_NEAR(spikyGradientFactor(k, Real(r)) * r,
                -45.0 / (kPi * std::pow(h, 6)) * (h - r) * (h - r),
                1e-3 * std::fabs(spikyGradientFactor(k, Real(r)) * r));
    EXPECT_NEAR(viscosityLaplacian(k, Real(r)), 45.0 / (kPi * std::pow(h, 6)) * (h - r),
                1e-3 * viscosityLaplacian(k, Real(r)));
}

}  // namespace
}  // namespace weir
