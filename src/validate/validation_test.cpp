// `weir validate` at its CI resolution on the CPU, delta-SPH model: the hydrostatic tank passes
// every check of docs/physics.md; the dam break holds its density and keeps its front within a
// regression bound of Martin & Moyce (the validation's own 10% / 15% tolerances are for the
// converged resolution on the GPU, docs/physics.md); water, oil and honey give different fronts.
#include "validate/validation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace weir {
namespace {

void print(const ValidationReport& report) {
    for (const ValidationCheck& c : report.checks) {
        std::cout << (c.passed() ? "PASS " : "FAIL ") << c.name << ": " << c.value << " (tolerance "
                  << c.tolerance << ")\n";
    }
}

const ValidationCheck& check(const ValidationReport& report, const std::string& start) {
    for (const ValidationCheck& c : report.checks) {
        if (c.name.rfind(start, 0) == 0) {
            return c;
        }
    }
    throw std::runtime_error("no check named " + start);
}

// A case whose scene the solver refuses (DFSPH: the dam break's periodic z) is reported as not
// run, with the setup's reason; the others still run, and validation does not pass.
TEST(Validate, CasesTheSolverRefusesAreReportedAndFail) {
    // DFSPH runs delta-SPH's physics only: under the paper's model every case is refused, and the
    // report says which and why.
    ValidationOptions options;
    options.backend = Backend::Cpu;
    options.solver = "dfsph";
    options.model = "paper";
    options.hydrostatic = false;
    options.damBreak = true;
    ValidationReport report = runValidation(options);
    EXPECT_EQ(report.solver, "dfsph");
    ASSERT_EQ(report.notRun.size(), 1u);
    EXPECT_NE(report.notRun[0].find("dam-break"), std::string::npos) << report.notRun[0];
    EXPECT_NE(report.notRun[0].find("fluid.model"), std::string::npos) << report.notRun[0];
    EXPECT_FALSE(report.passed());
}

TEST(Validate, DfsphRunsThePeriodicDamBreak) {
    // The Martin & Moyce column is a slab periodic across: DFSPH runs it since it takes periodic
    // axes (its ghosts take their owners' state after every sweep). Regression bound at 12
    // across (measured 0.098 RMS, 0.153 max on 2026-12-05; WCSPH 0.077, 0.117).
    ValidationOptions options;
    options.backend = Backend::Cpu;
    options.solver = "dfsph";
    options.hydrostatic = false;
    options.damBreak = true;
    ValidationReport report = runValidation(options);
    EXPECT_TRUE(report.notRun.empty()) << report.notRun.front();
    EXPECT_LT(check(report, "dam break: front RMS relative error").value, 0.15);
    EXPECT_LT(check(report, "dam break: front max relative error").value, 0.25);
    EXPECT_TRUE(check(report, "dam break: max density deviation").passed());
}

TEST(Validate, DfsphChannelsFollowTheMorrisSeries) {
    // Start-up Poiseuille and Couette flow under DFSPH at 10 across (the checks' own tolerances:
    // start-up 5%, steady 2%). Measured 2026-12-05: Poiseuille start-up 1.2%, steady 1.7%;
    // Couette 1.5%, 0.04%. With the raw kernel gradient in its viscous forces (before
    // dfsphForceParams) the fluid's viscosity read 5% low and Poiseuille's steady profile was
    // 6.7% fast: this fails then.
    ValidationOptions options;
    options.backend = Backend::Cpu;
    options.solver = "dfsph";
    options.hydrostatic = false;
    options.damBreak = false;
    options.channels = true;
    options.channelResolution = 10;
    ValidationReport report = runValidation(options);
    print(report);
    EXPECT_TRUE(report.notRun.empty()) << report.notRun.front();
    for (const char* name :
         {"poiseuille: start-up", "poiseuille: steady", "couette: start-up", "couette: steady"}) {
        EXPECT_TRUE(check(report, name).passed()) << name;
    }
}

TEST(Validate, DeltaSphTankIsHydrostaticAndTheDamBreakFollowsMartinMoyceAtCiResolution) {
    ValidationOptions options;  // CI defaults: 24 particles over the depth, 12 across the column
    options.backend = Backend::Cpu;
    options.model = "delta-sph";
    ValidationReport report = runValidation(options);
    print(report);
    for (const ValidationCheck& c : report.checks) {
        if (c.name.rfind("hydrostatic", 0) == 0) {
            EXPECT_TRUE(c.passed()) << c.name << " = " << c.value << " > " << c.tolerance;
        }
    }
    EXPECT_TRUE(check(report, "dam break: max density deviation").passed());
    // Regression bound at 12 across (measured 0.077 RMS, 0.117 max on this machine at the default
    // smoothing ratio 3; 0.10 and 0.16 at 2): the front
    // neither stalls nor runs off as the Ritter limit would (RMS 0.5 there).
    EXPECT_LT(check(report, "dam break: front RMS relative error").value, 0.15);
    EXPECT_LT(check(report, "dam break: front max relative error").value, 0.25);
    // The comparison used the data: the simulated front moved over the measured range.
    EXPECT_GE(report.layerY.size(), 10u);
    ASSERT_EQ(report.ladder.size(), 1u);
    ASSERT_FALSE(report.ladder.back().Z.empty());
    EXPECT_GT(report.ladder.back().Z.back(), 4.0);
    EXPECT_GE(report.ladder.back().points, 7);

    const std::filesystem::path dir = std::filesystem::temp_directory_path() / "weir_validate_test";
    std::filesystem::remove_all(dir);
    std::string message;
    EXPECT_TRUE(writeValidation(report, dir.string(), /*plots=*/false, &message)) << message;
    for (const char* file : {"hydrostatic.csv", "dam_break.csv", "viscous_dam_break.csv",
                             "martin_moyce_1952.csv", "validation.json", "plot.py"}) {
        EXPECT_TRUE(std::filesystem::exists(dir / file)) << file;
    }
    std::filesystem::remove_all(dir);
}

// The paper's model fails the hydrostatic checks that delta-SPH passes: its spiky gradient sums
// to 0.947 over the lattice at h = 2 d and its walls squeeze the floor layer (issue 14).
TEST(Validate, ThePapersModelIsNotHydrostatic) {
    ValidationOptions options;
    options.backend = Backend::Cpu;
    options.model = "paper";
    options.damBreak = false;
    ValidationReport report = runValidation(options);
    print(report);
    EXPECT_FALSE(check(report, "hydrostatic: pressure gradient").passed());
    EXPECT_FALSE(check(report, "hydrostatic: floor layer pressure").passed());
}

TEST(Validate, WaterOilAndHoneyGiveDifferentFronts) {
    ValidationOptions options;
    options.backend = Backend::Cpu;
    options.model = "delta-sph";
    options.hydrostatic = options.damBreak = false;
    options.viscous = true;
    options.columnResolutions = {10};
    ValidationReport report = runValidation(options);
    print(report);
    ASSERT_EQ(report.viscous.size(), 3u);
    for (const ValidationCheck& c : report.checks) {
        EXPECT_TRUE(c.passed()) << c.name << " = " << c.value << " > " << c.tolerance;
    }
}

// Lobovsky et al. (2014) timed their front from the gate's measured opening: weir's front, with no
// time shift, follows it within 5% of the travel to the wall at a coarse resolution already. (The
// wall pressure peaks are reported, not asserted: at this resolution the weakly compressible
// fluid's acoustic noise swamps them, docs/physics.md.)
TEST(Validate, LobovskyFrontFollowsTheExperimentWithoutATimeShift) {
    ValidationOptions options;
    options.backend = Backend::Cpu;
    options.model = "delta-sph";
    options.hydrostatic = options.damBreak = false;
    options.lobovsky = true;
    options.lobovskyResolution = 15;
    ValidationReport report = runValidation(options);
    print(report);
    ASSERT_EQ(report.lobovsky.size(), 1u);
    EXPECT_TRUE(check(report, "Lobovsky: front RMS error").passed());
    EXPECT_GT(report.lobovsky[0].frontX.back(), 3.3);  // it reached the wall
}

// The Taylor-Green vortex at Re 100 (periodic box): with particle shifting the kinetic energy
// decays at the analytic rate within the 5% tolerance already at 32 across (measured on this
// machine: 1.9%; 16 across: coarser, and worse), and the error does not grow from 16 to 32;
// without shifting the lattice tears at the stagnation points and the vortex loses most of its
// energy at once.
TEST(Validate, TaylorGreenVortexConvergesWithParticleShiftingAndCollapsesWithout) {
    ValidationOptions options;
    options.backend = Backend::Cpu;
    options.model = "delta-sph";
    options.hydrostatic = options.damBreak = false;
    options.taylorGreen = true;
    options.taylorGreenResolutions = {16, 32};
    // At smoothing ratio 2, where the collapse without shifting was measured, and at a third of
    // the default's cost on CI's two cores; at the default 3 the vortex passes too (H200: 1.6%,
    // 0.2%, 0.8% at 32, 64, 128 across; CPU: 1.6% at 32; docs/physics.md).
    options.smoothingRatio = 2.0;
    ValidationReport report = runValidation(options);
    print(report);
    ASSERT_EQ(report.taylorGreen.size(), 2u);
    const TaylorGreenRun &coarse = report.taylorGreen[0], &fine = report.taylorGreen[1];
    EXPECT_TRUE(check(report, "Taylor-Green vortex, Re 100").passed()) << fine.error;
    EXPECT_TRUE(check(report, "Taylor-Green ladder").passed()) << coarse.error << " " << fine.error;
    // At t = 0.5 L / U the analytic vortex keeps exp(-16 pi^2 0.5 / 100) = 45% of its energy.
    const double kept = fine.energy[4] / fine.energy[0];
    EXPECT_NEAR(kept, std::exp(2 * report.tgvDecayReference * fine.t[4]), 0.15);

    options.shifting = 0;
    options.taylorGreenResolutions = {16};
    ValidationReport unshifted = runValidation(options);
    print(unshifted);
    ASSERT_EQ(unshifted.taylorGreen.size(), 1u);
    EXPECT_LT(unshifted.taylorGreen[0].energy[4] / unshifted.taylorGreen[0].energy[0],
              0.5 * coarse.energy[4] / coarse.energy[0]);
}

// The analytic series that the channel checks compare against reproduce the published tables
// (shared/data, computed there with 200 and 2000 terms), where those tables are beside the
// checkout.
TEST(Validate, ChannelSeriesMatchTheTabulatedMorrisSolutions) {
    const std::filesystem::path data =
        std::filesystem::path(WEIR_SOURCE_DIR).parent_path() / "shared" / "data";
    int compared = 0;
    for (const char* name :
         {"poiseuille_startup_morris1997.csv", "couette_startup_morris1997.csv"}) {
        std::ifstream f(data / name);
        if (!f) {
            GTEST_SKIP() << "no " << (data / name) << " beside the checkout";
        }
        const bool poiseuille = std::string(name).rfind("poiseuille", 0) == 0;
        std::string line;
        std::vector<double> thetas;
        while (std::getline(f, line)) {
            if (line.empty() || line[0] == '#') {
                continue;
            }
            std::stringstream cells(line);
            std::string cell;
            std::vector<std::string> row;
            while (std::getline(cells, cell, ',')) {
                row.push_back(cell);
            }
            if (thetas.empty()) {  // header: eta_y_over_L,theta_0.01,...,steady
                for (std::size_t k = 1; k < row.size(); ++k) {
                    thetas.push_back(row[k] == "steady" ? 100.0 : std::stod(row[k].substr(6)));
                }
                continue;
            }
            const double eta = std::stod(row[0]);
            for (std::size_t k = 1; k < row.size(); ++k) {
                const double u = poiseuille ? poiseuilleVelocity(eta, thetas[k - 1])
                                            : couetteVelocity(eta, thetas[k - 1]);
                EXPECT_NEAR(u, std::stod(row[k]), 2e-4)
                    << name << " eta " << eta << " theta " << thetas[k - 1];
                ++compared;
            }
        }
    }
    EXPECT_GT(compared, 200);
}

}  // namespace
}  // namespace weir
