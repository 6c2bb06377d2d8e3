// The per-frame density deviation from rest density that weir reports: how compressible the
// weakly compressible fluid really was. Only compression counts: particles at the free surface
// lack neighbours and read light by construction, which is not an error of the solver.
#pragma once

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "solver/particles.h"

namespace weir {

struct DensityDeviation {
    double max = 0;   // max over particles of (rho - rho0) / rho0, >= 0
    double mean = 0;  // mean over particles of max(0, rho - rho0) / rho0
    // The compression that all but one particle in a thousand stay under: a measure of the
    // tail that does not grow with the particle count as the single largest value does.
    double p999 = 0;

    std::string text() const {
        char buf[96];
        std::snprintf(buf, sizeof buf, "density +%.2f%% max, +%.3f%% mean", 100 * max, 100 * mean);
        return buf;
    }
};

// withTail: also p999 (a partial sort of a copy: 10-20 ms at 1M particles, which a run's
// progress line, showing max and mean, does without).
inline DensityDeviation densityDeviation(const HostParticles& p, double restDensity,
                                         bool withTail = true) {
    DensityDeviation d;
    if (p.size() == 0) {
        return d;
    }
    double sum = 0;
    std::vector<float> excesses(withTail ? p.size() : 0);
    for (std::size_t i = 0; i < p.size(); ++i) {
        const double excess = std::max(0.0, (double(p.rho[i]) - restDensity) / restDensity);
        d.max = std::max(d.max, excess);
        sum += excess;
        if (withTail) {
            excesses[i] = float(excess);
        }
    }
    d.mean = sum / double(p.size());
    if (!withTail) {
        return d;
    }
    const std::size_t at = std::min(p.size() - 1, p.size() * 999 / 1000);
    std::nth_element(excesses.begin(), excesses.begin() + std::ptrdiff_t(at), excesses.end());
    d.p999 = excesses[at];
    return d;
}

}  // namespace weir
