// `weir validate` at its CI resolution on the CPU: the hydrostatic tank and the Martin & Moyce
// dam break pass every check within the tolerances of docs/physics.md, and the results are
// written where the plots are made from.
#include "validate/validation.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <iostream>

namespace weir {
namespace {

TEST(Validate, HydrostaticTankAndMartinMoyceDamBreakPassAtCiResolution) {
    ValidationOptions options;  // CI defaults: 15 particles over the depth, 12 across the column
    options.backend = Backend::Cpu;
    ValidationReport report = runValidation(options);
    ASSERT_GE(report.checks.size(), 7u);
    for (const ValidationCheck& c : report.checks) {
        std::cout << (c.passed() ? "PASS " : "FAIL ") << c.name << ": " << c.value << " (tolerance "
                  << c.tolerance << ")\n";
        EXPECT_TRUE(c.passed()) << c.name << " = " << c.value << " > " << c.tolerance;
    }
    // The comparison used the data: the simulated front moved over the measured range.
    EXPECT_GE(report.layerY.size(), 5u);
    ASSERT_FALSE(report.simZ.empty());
    EXPECT_GT(report.simZ.back(), 4.0);

    const std::filesystem::path dir = std::filesystem::temp_directory_path() / "weir_validate_test";
    std::filesystem::remove_all(dir);
    std::string message;
    EXPECT_TRUE(writeValidation(report, dir.string(), /*plots=*/false, &message)) << message;
    for (const char* file : {"hydrostatic.csv", "dam_break.csv", "martin_moyce_1952.csv",
                             "validation.json", "plot.py"}) {
        EXPECT_TRUE(std::filesystem::exists(dir / file)) << file;
    }
    std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace weir
