// Divergence-free SPH on the CPU: a tank at rest holds its density, a dam break stays within the
// solver's tolerance and agrees with WCSPH on where the water goes, the iterations are reported,
// and the combinations it does not support fail at once, naming the field.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include "scene/scene.h"
#include "scene/setup.h"
#include "solver/dfsph/dfsph_stages.h"
#include "solver/solver_test_support.h"

namespace weir {
namespace {

using namespace weir::testing;

Scene dfsphScene(const std::string& body) {
    return parseScene(
        R"({"name": "dfsph_test", "solver": "dfsph", "fluid": {"preset": "water"}, )" + body + "}",
        "<test dfsph>");
}

// The density solve's prediction of a pair's kernel after the move, to second order
// (dfsphSecondOrderRate): W(|r + dt u|) - W(|r|) less the first order dt grad W . u and the second,
// dt times the rate, leaves a third-order residual (8 times smaller when dt halves), where the
// first order alone leaves a second-order one (4 times smaller); over pairs across the support,
// closing and parting, head-on and sideways.
TEST(Dfsph, SecondOrderPredictionOfAPairsKernelIsThirdOrderAccurate) {
    const double h = 0.02;
    const WendlandKernel k = WendlandKernel::forRadius(h);
    struct Pair {
        Vec3 r, u;
    };
    const Pair pairs[] = {{{0.5 * h, 0, 0}, {-1, 0, 0}},
                          {{0.3 * h, 0.2 * h, 0}, {-2, 0.5, 1}},
                          {{0.7 * h, -0.1 * h, 0.2 * h}, {1, 1, -1}},
                          {{0.1 * h, 0.1 * h, 0.1 * h}, {0, 3, 0}},
                          {{0, 0.85 * h, 0}, {0.5, -1.5, 0}}};
    for (const Pair& pair : pairs) {
        const double r = double(length(pair.r));
        auto residual = [&](double dt, bool secondOrder) {
            const Vec3 moved = pair.r + pair.u * Real(dt);
            double change = double(k.value(length(moved))) - double(k.value(Real(r)));
            change -= dt * double(k.gradientFactor(Real(r))) * double(dot(pair.u, pair.r));
            if (secondOrder) {
                change -= dt * double(dfsphSecondOrderRate(k, Real(r), pair.r, pair.u, Real(dt)));
            }
            return std::fabs(change);
        };
        // A step that moves the pair 1% of h, then half of it. (Near the support's edge the
        // third order is large: at r = 0.73 h it is a third of the second at this step.)
        const double dt = 0.01 * h / double(length(pair.u));
        const double first = residual(dt, false) / residual(dt / 2, false);
        const double second = residual(dt, true) / residual(dt / 2, true);
        EXPECT_NEAR(first, 4.0, 0.8) << "r/h " << r / h;
        EXPECT_GT(second, 6.5) << "r/h " << r / h;
        EXPECT_LT(residual(dt, true), 0.5 * residual(dt, false)) << "r/h " << r / h;
    }
}

// Density deviation from rho0 over the particles a full support below the surface and away from
// the walls' corners is meaningful for every particle: a summation density reads light only at
// the free surface, which the solver leaves alone (it removes compression only).
struct Compression {
    double mean = 0, max = 0;
};
Compression compressionOf(const HostParticles& p, double restDensity) {
    Compression c;
    for (Real rho : p.rho) {
        const double excess = std::max(0.0, double(rho) / restDensity - 1);
        c.mean += excess;
        c.max = std::max(c.max, excess);
    }
    c.mean /= double(p.size());
    return c;
}

// The tank at rest of the tests below: water 0.2 m deep, d = 1 cm, walls of boundary particles.
Scene tankScene() {
    return dfsphScene(R"(
        "container": {"min": [0, 0, 0], "max": [0.2, 0.3, 0.1]},
        "blocks": [{"min": [0, 0, 0], "max": [0.2, 0.2, 0.1]}],
        "particles": {"spacing": 0.01},
        "time": {"duration": 0.5, "frameRate": 10})");
}

// The tanks below: 1 cm layers of a tank of water 0.2 m deep. Each layer's mean pressure from
// `first` to `last` against rho0 g (depth) within `layerTolerance` (relative), and the pressure's
// fitted gradient against rho0 g within `gradientTolerance`.
void expectHydrostaticLayers(const HostParticles& p, double restDensity, int first, int last,
                             double layerTolerance, double gradientTolerance) {
    const double d = 0.01, top = 0.2, g = 9.81;
    std::vector<double> sum(20, 0.0), ySum(20, 0.0);
    std::vector<int> count(20, 0);
    for (std::size_t i = 0; i < p.size(); ++i) {
        const int layer = std::clamp(int(p.y[i] / d), 0, 19);
        sum[std::size_t(layer)] += p.p[i];
        ySum[std::size_t(layer)] += p.y[i];
        ++count[std::size_t(layer)];
    }
    double sy = 0, sp = 0, syy = 0, syp = 0;
    int used = 0;
    for (int layer = first; layer <= last; ++layer) {
        ASSERT_GT(count[std::size_t(layer)], 0);
        const double y = ySum[std::size_t(layer)] / count[std::size_t(layer)];
        const double pressure = sum[std::size_t(layer)] / count[std::size_t(layer)];
        const double hydrostatic = restDensity * g * (top - y);
        EXPECT_NEAR(pressure / hydrostatic, 1.0, layerTolerance)
            << "layer " << layer << " at y = " << y;
        sy += y, sp += pressure, syy += y * y, syp += y * pressure;
        ++used;
    }
    const double slope = (used * syp - sy * sp) / (used * syy - sy * sy);
    EXPECT_NEAR(-slope / (restDensity * g), 1.0, gradientTolerance);
}

TEST(Dfsph, TankAtRestHoldsRestDensityAndStaysAtRest) {
    const Scene scene = tankScene();
    SetupReport report;
    auto sim = makeSimulation(Backend::Cpu, NeighbourMode::Auto, buildSetup(scene, {}, &report));
    ASSERT_EQ(sim->method(), "dfsph");
    sim->computeDensity();
    HostParticles p;
    auto rmsSpeed = [](const HostParticles& p) {
        double squares = 0;
        for (std::size_t i = 0; i < p.size(); ++i) {
            squares +=
                double(p.vx[i]) * p.vx[i] + double(p.vy[i]) * p.vy[i] + double(p.vz[i]) * p.vz[i];
        }
        return std::sqrt(squares / double(p.size()));
    };
    double rmsEarly = 0;
    for (int frame = 1; frame <= 5; ++frame) {
        sim->advanceTo(0.1 * frame);
        ASSERT_EQ(sim->fault().code, 0) << describeFault(sim->fault(), sim->params());
        const SolverReport solves = sim->takeSolverReport();
        ASSERT_TRUE(solves.iterative);
        EXPECT_GT(solves.density.solves, 0);
        // From rest the first steps build the deep column's pressure from nothing, and the
        // Jacobi sweeps reach the limit (100) before the tolerance in a few of them; after that
        // the warm start carries it. The stir left (below) still makes a rare solve end at the
        // limit, near the tolerance: measured 1 of 50 in the fifth frame, at 1.03 times it.
        if (frame > 1) {
            EXPECT_LE(solves.density.unconverged * 20, solves.density.solves) << "frame " << frame;
            EXPECT_LE(solves.density.worstError, 1.5e-4) << "frame " << frame;
        }
        sim->download(p);
        if (frame == 2) {
            rmsEarly = rmsSpeed(p);
        }
        const Compression c = compressionOf(p, scene.restDensity);
        // The issue's check: a tank at rest holds rho0 within 0.1%.
        EXPECT_LT(c.mean, 1e-3) << "frame " << frame;
        EXPECT_LT(c.max, 1e-2) << "frame " << frame;
    }
    // Near rest. The Jacobi sweeps converge the deep column's pressure slowly, and what the
    // first steps leave unconverged stays as a stir that only the small artificial viscosity
    // damps: measured RMS speed 0.09 m/s at 0.2 s, 0.045 m/s at 0.5 s, 2-4% of U = sqrt(2 g H)
    // (delta-SPH's weakly compressible tank keeps 3e-5 U; TankAtRest). It must die down, and be
    // under 3% of U by 0.5 s; the stray speeds are a known gap (docs/dfsph.md).
    const double rms = rmsSpeed(p);
    std::cout << "dfsph tank at rest: RMS speed " << rmsEarly << " m/s at 0.2 s, " << rms
              << " m/s at 0.5 s, max " << maxSpeed(p) << " m/s, U = " << report.expectedSpeed
              << " m/s\n";
    EXPECT_LT(rms, 0.03 * report.expectedSpeed);
    EXPECT_LT(rms, rmsEarly);
    // No particle sits on a container plane held there by the collision response.
    int onPlanes = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        onPlanes += p.y[i] <= 1e-6 || p.x[i] <= 1e-6 || p.x[i] >= 0.2 - 1e-6 ? 1 : 0;
    }
    EXPECT_EQ(onPlanes, 0);
    // The frames carry the pressure the solves applied (their impulses over the steps since the
    // last download, per unit time), not the equation of state's, which for a fluid held at rho0
    // within 0.1% reads about 0. Below the top and above the floor layer each 1 cm layer's mean
    // is hydrostatic, rho0 g (depth), within 20%, and the pressure grows with depth at rho0 g
    // within 20% (fitted). Measured: the fitted gradient 1.155 rho0 g (WCSPH's tanks read 8-10%
    // steep before the kernel gradient's lattice correction, docs/physics.md), the floor layer
    // pressed onto the wall, the top layer light by summation.
    expectHydrostaticLayers(p, scene.restDensity, 2, 16, 0.2, 0.2);
}

// WEIR_DFSPH_WALLS=extrapolated (experimental): walls that push back as the fluid near them does,
// one warm start for both solves, the first from the seeded hydrostatic pressure. The same tank
// as above, 0.3 s: in the last frame every 1 cm layer from the floor layer (the wall layer) to
// 2 h under the surface within 6% of rho0 g (depth) (measured 2026-12-05: within 4.1%; weir
// validate's 2%, which it passes at 0.4-1%, is on the mean of 9 frames), the fitted gradient
// within 2% (its tolerance), the surface within a spacing of where it was seeded, and the stir
// under 1.5% of U = sqrt(2 g H) (measured 0.7-1%). The default walls read 1.8 times hydrostatic in
// the floor layer and 10% steep (above).
TEST(Dfsph, TankWithPushingWallsIsHydrostaticInEveryLayer) {
    ::setenv("WEIR_DFSPH_WALLS", "extrapolated", 1);
    const Scene scene = tankScene();
    SetupReport report;
    auto sim = makeSimulation(Backend::Cpu, NeighbourMode::Auto, buildSetup(scene, {}, &report));
    ::unsetenv("WEIR_DFSPH_WALLS");  // read when the method is made
    sim->computeDensity();
    HostParticles p;
    for (int frame = 1; frame <= 3; ++frame) {
        sim->advanceTo(0.1 * frame);
        ASSERT_EQ(sim->fault().code, 0) << describeFault(sim->fault(), sim->params());
        sim->download(p);
        const Compression c = compressionOf(p, scene.restDensity);
        EXPECT_LT(c.mean, 1e-3) << "frame " << frame;
        EXPECT_LT(c.max, 1e-2) << "frame " << frame;
    }
    double squares = 0, top = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        squares +=
            double(p.vx[i]) * p.vx[i] + double(p.vy[i]) * p.vy[i] + double(p.vz[i]) * p.vz[i];
        top = std::max(top, double(p.y[i]));
    }
    const double rms = std::sqrt(squares / double(p.size()));
    const double d = 0.01, surface = 0.2;
    std::cout << "tank with pushing walls: RMS speed " << rms << " m/s, top particle at " << top
              << " m (seeded " << surface - 0.5 * d << ")\n";
    EXPECT_LT(rms, 0.015 * report.expectedSpeed);
    EXPECT_NEAR(top, surface - 0.5 * d, d);
    expectHydrostaticLayers(p, scene.restDensity, 0, 15, 0.06, 0.02);
}

// The dam break: every frame within the solver's tolerance (mean compression under 0.1%), the
// front where the weakly compressible solver puts it (the same physics but for the compression),
// and much the larger time step.
TEST(Dfsph, DamBreakHoldsDensityAndAgreesWithWcsph) {
    const std::string body = R"(
        "container": {"min": [0, 0, 0], "max": [0.6, 0.4, 0.1]},
        "blocks": [{"min": [0, 0, 0], "max": [0.2, 0.3, 0.1]}],
        "particles": {"spacing": 0.0125},
        "time": {"duration": 0.25, "frameRate": 20})";
    const Scene scene = dfsphScene(body);
    const Scene weakly = withSolver(scene, "wcsph");
    auto dfsph = makeSimulation(Backend::Cpu, NeighbourMode::Auto, buildSetup(scene, {}, nullptr));
    auto wcsph = makeSimulation(Backend::Cpu, NeighbourMode::Auto, buildSetup(weakly, {}, nullptr));
    dfsph->computeDensity();
    wcsph->computeDensity();
    HostParticles a, b;
    long long iterations = 0;
    int solves = 0;
    for (int frame = 1; frame <= 5; ++frame) {
        const double t = 0.05 * frame;
        dfsph->advanceTo(t);
        wcsph->advanceTo(t);
        ASSERT_EQ(dfsph->fault().code, 0) << describeFault(dfsph->fault(), dfsph->params());
        ASSERT_EQ(wcsph->fault().code, 0);
        const SolverReport report = dfsph->takeSolverReport();
        EXPECT_EQ(report.density.unconverged, 0) << "frame " << frame;
        iterations += report.density.iterations;
        solves += report.density.solves;
        dfsph->download(a);
        EXPECT_LT(compressionOf(a, scene.restDensity).mean, 1e-3) << "frame " << frame;
    }
    wcsph->download(b);
    std::cout << "dfsph: " << dfsph->stepCount() << " steps, " << double(iterations) / solves
              << " density sweeps a step; wcsph: " << wcsph->stepCount() << " steps\n";
    EXPECT_LT(dfsph->stepCount() * 3, wcsph->stepCount());
    const Compression weak = compressionOf(b, scene.restDensity);
    const Compression strong = compressionOf(a, scene.restDensity);
    std::cout << "mean compression: dfsph " << strong.mean << ", wcsph " << weak.mean << "\n";
    EXPECT_LT(strong.mean * 3, weak.mean);
    // The front (furthest particle along x) and the centre of mass.
    auto front = [](const HostParticles& p) { return *std::max_element(p.x.begin(), p.x.end()); };
    auto centre = [](const HostParticles& p, const std::vector<Real>& axis) {
        double sum = 0;
        for (Real v : axis) {
            sum += v;
        }
        return sum / double(p.size());
    };
    const double d = 0.0125;
    EXPECT_GT(front(a), 0.35);  // it moved: the column's foot was at 0.2
    EXPECT_NEAR(front(a), front(b), 3 * d);
    // The centres part by a few spacings: DFSPH's fluid does not compress (WCSPH's by up to
    // 3% here) and its free surface reads light (a summed density).
    EXPECT_NEAR(centre(a, a.x), centre(b, b.x), 3 * d);
    EXPECT_NEAR(centre(a, a.y), centre(b, b.y), 3 * d);
}

// The scene's "dfsph" settings reach the solver: tolerances in percent, the sweep limit, the CFL
// number on d; divergenceError 0 drops the divergence-free solve.
TEST(Dfsph, EveryDownloadBetweenTwoStepsGetsTheSamePressure) {
    // The frames' pressure is the solves' mean since it was last asked for: a second download
    // before the next step (the renderer after the frame writer) must not see an empty window.
    const Scene scene = dfsphScene(R"(
        "container": {"min": [0, 0, 0], "max": [0.2, 0.3, 0.1]},
        "blocks": [{"min": [0, 0, 0], "max": [0.2, 0.2, 0.1]}],
        "particles": {"spacing": 0.02})");
    auto sim = makeSimulation(Backend::Cpu, NeighbourMode::Auto, buildSetup(scene, {}, nullptr));
    sim->computeDensity();
    sim->advance(20);
    HostParticles first, second;
    sim->download(first);
    sim->download(second);
    ASSERT_EQ(first.p.size(), second.p.size());
    EXPECT_EQ(first.p, second.p);
    // The solves hold the tank up: its pressure is not the equation of state's of densities held
    // at rho0 (about 0), but of the order of rho0 g (depth).
    double sum = 0;
    for (Real p : first.p) {
        sum += p;
    }
    EXPECT_GT(sum / double(first.p.size()), 0.2 * scene.restDensity * 9.81 * 0.1);
}

TEST(Dfsph, SceneSettingsReachTheSolver) {
    const std::string body = R"(
        "container": {"min": [0, 0, 0], "max": [0.2, 0.3, 0.1]},
        "blocks": [{"min": [0, 0, 0], "max": [0.2, 0.2, 0.1]}],
        "particles": {"spacing": 0.02})";
    const SimulationSetup defaults = buildSetup(dfsphScene(body), {}, nullptr);
    EXPECT_NEAR(double(defaults.params.densityTolerance), 1e-4, 1e-9);
    EXPECT_NEAR(double(defaults.params.divergenceTolerance), 1e-3, 1e-9);
    EXPECT_NEAR(double(defaults.params.worstDensityTolerance), 1e-2, 1e-9);
    EXPECT_EQ(defaults.params.maxSolverIterations, 100);
    const SimulationSetup set =
        buildSetup(dfsphScene(body + R"(, "dfsph": {"densityError": 0.05, "divergenceError": 0,
                                         "worstDensityError": 0, "maxSweeps": 40, "cfl": 0.2})"),
                   {}, nullptr);
    EXPECT_NEAR(double(set.params.densityTolerance), 5e-4, 1e-9);
    EXPECT_EQ(double(set.params.worstDensityTolerance), 0.0);
    EXPECT_EQ(double(set.params.divergenceTolerance), 0.0);
    EXPECT_EQ(set.params.maxSolverIterations, 40);
    EXPECT_NEAR(double(set.params.cflNumber), 0.5 * double(defaults.params.cflNumber), 1e-6);
    // No divergence-free solve: its report stays empty while the density solve runs.
    auto sim = makeSimulation(Backend::Cpu, NeighbourMode::Auto, set);
    sim->computeDensity();
    sim->advance(3);
    const SolverReport report = sim->takeSolverReport();
    EXPECT_EQ(report.divergence.solves, 0);
    EXPECT_EQ(report.density.solves, 3);
    EXPECT_LE(report.density.maxIterations, 40);
}

// The constant-density solve also sweeps while one particle's error is past
// dfsph.worstDensityError (a mean over millions of particles hides a few compressed ones: a 10M
// dam break blew up at a column's foot with the mean met in 2 sweeps a step). With a loose mean
// (1%, met at once: 2 sweeps a step) the worst particle's bound is what keeps the solve going:
// more sweeps, and each solve still ends converged. (The frames' largest compression is not
// compared: the two runs part ways, and at 0.05 s it read 0.15% and 0.18%.)
TEST(Dfsph, WorstParticleKeepsTheSolveGoing) {
    const std::string body = R"(
        "container": {"min": [0, 0, 0], "max": [0.6, 0.4, 0.1]},
        "blocks": [{"min": [0, 0, 0], "max": [0.2, 0.3, 0.1]}],
        "particles": {"spacing": 0.0125},
        "time": {"duration": 0.1, "frameRate": 20},
        "dfsph": {"densityError": 1, "worstDensityError": )";
    struct Outcome {
        long long sweeps = 0, steps = 0;
        int unconverged = 0;
        double worstCompression = 0;
    };
    auto run = [&](const std::string& worst) {
        const Scene scene = dfsphScene(body + worst + "}");
        auto sim =
            makeSimulation(Backend::Cpu, NeighbourMode::Auto, buildSetup(scene, {}, nullptr));
        sim->computeDensity();
        Outcome out;
        HostParticles p;
        for (int frame = 1; frame <= 2; ++frame) {
            sim->advanceTo(0.05 * frame);
            EXPECT_EQ(sim->fault().code, 0) << describeFault(sim->fault(), sim->params());
            const SolverReport report = sim->takeSolverReport();
            out.sweeps += report.density.iterations;
            out.unconverged += report.density.unconverged;
            sim->download(p);
            out.worstCompression =
                std::max(out.worstCompression, compressionOf(p, scene.restDensity).max);
        }
        out.steps = sim->stepCount();
        return out;
    };
    const Outcome loose = run("0"), bound = run("0.25");
    std::cout << "density sweeps: " << loose.sweeps << " with the mean alone, " << bound.sweeps
              << " with every particle within 0.25%; worst frame compression "
              << loose.worstCompression << ", " << bound.worstCompression << "\n";
    EXPECT_GT(bound.sweeps, loose.sweeps + loose.sweeps / 2);
    EXPECT_EQ(loose.sweeps, 2 * loose.steps);  // the least a solve takes
    EXPECT_EQ(bound.unconverged, 0);
}

TEST(Dfsph, UnsupportedCombinationsFailNamingTheField) {
    const std::string body = R"(
        "container": {"min": [0, 0, 0], "max": [0.2, 0.3, 0.1]},
        "blocks": [{"min": [0, 0, 0], "max": [0.2, 0.2, 0.1]}],
        "particles": {"spacing": 0.02})";
    auto messageOf = [](const Scene& scene) {
        try {
            buildSetup(scene, {}, nullptr);
        } catch (const SceneError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    const Scene paper = withFluidModel(dfsphScene(body), "paper");
    EXPECT_NE(messageOf(paper).find("fluid.model is \"paper\""), std::string::npos)
        << messageOf(paper);
    const Scene simple = dfsphScene(body + R"(, "walls": {"model": "simple"})");
    EXPECT_NE(messageOf(simple).find("walls.model is \"simple\""), std::string::npos)
        << messageOf(simple);
    try {
        parseScene(R"({"solver": "dfsp", "container": {"min": [0, 0, 0], "max": [1, 1, 1]},
                       "blocks": [{"min": [0, 0, 0], "max": [0.5, 0.5, 0.5]}]})",
                   "<test>");
        ADD_FAILURE() << "an unknown solver was accepted";
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("dfsph"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace weir
