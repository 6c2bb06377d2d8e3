// `weir validate`: runs the hydrostatic tank, the Martin & Moyce dam break over a resolution
// ladder and the viscous dam break, prints each check against its tolerance and writes results
// and plots.
#include <cstdio>
#include <iostream>
#include <sstream>

#include "cli/commands.h"
#include "core/check.h"
#include "validate/validation.h"

namespace weir {

int validateCommand(const ValidateOptions& options) {
    try {
        ValidationOptions o;
        o.backend = parseBackend(options.backend);
        o.model = options.model;
        o.solver = options.solver;
        o.tankResolution = options.tankResolution;
        o.columnResolutions = options.columnResolutions;
        o.damEndT = options.damEndT;
        o.channelResolution = options.channelResolution;
        o.lobovskyResolution = options.lobovskyResolution;
        o.taylorGreenResolutions = options.taylorGreenResolutions;
        if (options.shifting >= 0) {
            o.shifting = options.shifting;
        }
        if (options.smoothingRatio >= 0) {
            o.smoothingRatio = options.smoothingRatio;
        }
        o.hydrostatic = o.damBreak = o.viscous = false;
        std::stringstream cases(options.cases);
        for (std::string c; std::getline(cases, c, ',');) {
            if (c == "hydrostatic") {
                o.hydrostatic = true;
            } else if (c == "dam-break") {
                o.damBreak = true;
            } else if (c == "viscous") {
                o.viscous = true;
            } else if (c == "channels") {
                o.channels = true;
            } else if (c == "lobovsky") {
                o.lobovsky = true;
            } else if (c == "taylor-green") {
                o.taylorGreen = true;
            } else {
                std::cerr << "weir validate: --cases: unknown case \"" << c
                          << "\"; allowed are hydrostatic, dam-break, viscous, channels, lobovsky, "
                             "taylor-green\n";
                return kExitUsage;
            }
        }
        std::cerr << "weir validate: fluid model " << (o.model.empty() ? "default" : o.model)
                  << ", solver " << (o.solver.empty() ? "wcsph" : o.solver) << " on "
                  << backendName(o.backend) << "\n";
        ValidationReport report = runValidation(o);
        for (const ValidationCheck& c : report.checks) {
            char line[400];
            std::snprintf(line, sizeof line, "  %s  %-95s %.4g (tolerance %.4g)",
                          c.passed() ? "PASS" : "FAIL", c.name.c_str(), c.value, c.tolerance);
            std::cout << line << "\n";
        }
        for (const std::string& why : report.notRun) {
            std::cout << "  NOT RUN  " << why << "\n";
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
