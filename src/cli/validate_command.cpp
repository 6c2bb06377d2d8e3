// `weir validate`: runs the hydrostatic tank and the Martin & Moyce dam break, prints each check
// against its tolerance and writes results and plots.
#include <cstdio>
#include <iostream>

#include "cli/commands.h"
#include "core/check.h"
#include "validate/validation.h"

namespace weir {

int validateCommand(const ValidateOptions& options) {
    try {
        ValidationOptions o;
        o.backend = parseBackend(options.backend);
        o.tankResolution = options.tankResolution;
        o.columnResolution = options.columnResolution;
        o.damEndT = options.damEndT;
        std::cerr << "weir validate: hydrostatic tank (" << o.tankResolution
                  << " particles over the depth) and Martin & Moyce dam break ("
                  << o.columnResolution << " across the column) on " << backendName(o.backend)
                  << "\n";
        ValidationReport report = runValidation(o);
        std::cerr << "weir validate: tank " << report.tankParticles << " particles in "
                  << report.tankSeconds << " s, dam break " << report.columnParticles
                  << " particles in " << report.damSeconds << " s\n";
        for (const ValidationCheck& c : report.checks) {
            char line[400];
            std::snprintf(line, sizeof line, "  %s  %-95s %.4g (tolerance %.4g)",
                          c.passed() ? "PASS" : "FAIL", c.name.c_str(), c.value, c.tolerance);
            std::cout << line << "\n";
        }
        std::string message;
        if (!writeValidation(report, options.outDir, !options.noPlot, &message)) {
            std::cerr << "weir validate: " << message << "\n";
        }
        std::cerr << "weir validate: results in " << options.outDir << "/\n";
        std::cout << (report.passed() ? "validation passed" : "validation FAILED") << "\n";
        return report.passed() ? kExitOk : kExitValidationFailed;
    } catch (...) {
        return reportCaughtError("weir validate");
    }
}

}  // namespace weir
