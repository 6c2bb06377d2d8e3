// `weir validate`: a hydrostatic tank and the Martin & Moyce (1952) dam break, run through the
// ordinary scene path (derived parameters, boundary-particle walls) and checked against physics
// and experiment with documented tolerances (docs/physics.md).
#pragma once

#include <string>
#include <vector>

#include "core/backend.h"

namespace weir {

struct ValidationOptions {
    Backend backend = Backend::Cpu;
    int tankResolution = 15;    // particles over the tank's water depth
    int columnResolution = 12;  // particles across the dam-break column's width a
    double settleTime = 1.0;    // s of tank simulation; the last 40% are averaged
    double damEndT = 5.0;       // dam break run to T = t sqrt(2 g / a)
    bool quiet = false;
};

struct ValidationCheck {
    std::string name;
    double value = 0;
    double tolerance = 0;  // passes when value <= tolerance
    std::string unit;
    bool passed() const { return value <= tolerance; }
};

struct ValidationReport {
    std::vector<ValidationCheck> checks;
    // Hydrostatic profile: layer height, mean pressure over the averaged frames, reference.
    std::vector<double> layerY, layerPressure, layerReference;
    double tankDepth = 0, rho0gH = 0;
    // Dam break: simulated front over time and the reference.
    std::vector<double> simT, simZ;
    double frontRms = 0;
    int tankParticles = 0, columnParticles = 0;
    double tankSeconds = 0, damSeconds = 0;  // wall-clock
    bool passed() const {
        for (const ValidationCheck& c : checks) {
            if (!c.passed()) {
                return false;
            }
        }
        return !checks.empty();
    }
};

// Tolerances (justified in docs/physics.md).
constexpr double kHydrostaticPressureTolerance = 0.10;  // RMS of layer means, / (rho0 g H)
constexpr double kDensityDeviationTolerance = 0.03;     // max (rho - rho0) / rho0
constexpr double kMeanDensityDeviationTolerance = 0.01;
constexpr double kStraySpeedTolerance = 0.05;  // RMS |v| / sqrt(2 g H) at rest
constexpr double kFrontRmsTolerance = 0.3;     // RMS of Z_sim - Z_ref
constexpr double kFrontBandRelative = 0.15;    // band drawn: Z_ref (1 +- 0.15) +- 0.2
constexpr double kFrontBandAbsolute = 0.2;

ValidationReport runValidation(const ValidationOptions& options);

// Writes hydrostatic.csv, dam_break.csv, martin_moyce_1952.csv, validation.json and plot.py to
// dir; runs python3 plot.py for the PNGs and returns false (with a message) if it cannot.
bool writeValidation(const ValidationReport& report, const std::string& dir, bool plots,
                     std::string* message);

}  // namespace weir
