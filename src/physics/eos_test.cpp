// Equations of state: the paper's linear eq. 3 and Tait's (gamma = 7) share the speed of sound at
// rest density, Tait stiffens under compression, and negative pressure is scaled as asked.
#include "physics/eos.h"

#include <gtest/gtest.h>

#include <cmath>

namespace weir {
namespace {

SphParams paramsFor(EosKind eos, double c, double negativeScale) {
    SphParams p;
    p.restDensity = 1000;
    p.invRestDensity = Real(1.0 / 1000);
    p.eos = eos;
    p.stiffness = Real(c * c);
    p.taitB = Real(1000 * c * c / 7);
    p.negativePressureScale = Real(negativeScale);
    return p;
}

TEST(Eos, TaitAndLinearShareTheSpeedOfSoundAtRest) {
    const double c = 30;
    for (EosKind eos : {EosKind::Linear, EosKind::Tait}) {
        SphParams p = paramsFor(eos, c, 1);
        EXPECT_NEAR(double(pressureFromDensity(p, 1000)), 0.0, 1e-6 * c * c * 1000);
        // dP/drho at rho0 by a central difference: c^2 for both.
        const double dRho = 0.5;
        const double slope = (double(pressureFromDensity(p, Real(1000 + dRho))) -
                              double(pressureFromDensity(p, Real(1000 - dRho)))) /
                             (2 * dRho);
        EXPECT_NEAR(slope, c * c, 2e-3 * c * c) << int(eos);
    }
}

TEST(Eos, TaitIsSevenTimesTheRatioToTheSeventh) {
    SphParams p = paramsFor(EosKind::Tait, 20, 1);
    for (double ratio : {0.97, 1.01, 1.03, 1.1}) {
        const double expected = 1000.0 * 400.0 / 7.0 * (std::pow(ratio, 7.0) - 1.0);
        EXPECT_NEAR(double(pressureFromDensity(p, Real(1000 * ratio))), expected,
                    1e-5 * std::fabs(expected) + 1e-2);
    }
    // Stiffer than linear under compression, softer in tension.
    SphParams lin = paramsFor(EosKind::Linear, 20, 1);
    EXPECT_GT(pressureFromDensity(p, 1050), pressureFromDensity(lin, 1050));
    EXPECT_GT(pressureFromDensity(p, 950), pressureFromDensity(lin, 950));
}

TEST(Eos, NegativePressureIsScaled) {
    for (EosKind eos : {EosKind::Linear, EosKind::Tait}) {
        SphParams keep = paramsFor(eos, 20, 1), clamp = paramsFor(eos, 20, 0),
                  half = paramsFor(eos, 20, 0.5);
        const Real tension = pressureFromDensity(keep, 990);
        EXPECT_LT(tension, Real(0));
        EXPECT_EQ(pressureFromDensity(clamp, 990), Real(0));
        EXPECT_NEAR(double(pressureFromDensity(half, 990)), 0.5 * double(tension),
                    1e-5 * std::fabs(double(tension)));
        // Compression is never scaled.
        EXPECT_EQ(pressureFromDensity(clamp, 1010), pressureFromDensity(keep, 1010));
    }
}

}  // namespace
}  // namespace weir
