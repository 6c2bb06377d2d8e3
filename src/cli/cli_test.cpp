// End-to-end tests of the weir binary: usage, info, runs that write frames in each format,
// bad scenes, a blow-up, --explain and brute-force neighbours. Every run is tiny and on the CPU.
#include <gtest/gtest.h>
#include <omp.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <new>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>
#include <vector>

#include "cli/cli_test_support.h"
#include "cli/commands.h"
#include "io/frame_reader.h"

namespace weir {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;
using namespace cli_testing;

// A tiny dam break: an 8 x 12 x 10 lattice at 1 cm in a 20 x 20 x 10 cm box, 960 particles.
constexpr const char* kTinyScene = R"({
    "name": "tiny",
    "container": {"min": [0, 0, 0], "max": [0.2, 0.2, 0.1]},
    "blocks": [{"min": [0, 0, 0], "max": [0.08, 0.12, 0.1]}],
    "particles": {"spacing": 0.01},
    "time": {"duration": 1, "frameRate": 30}
})";
constexpr std::size_t kTinyCount = 8 * 12 * 10;
constexpr double kTinyFrameRate = 30;
constexpr double kRestDensity = 1000;
constexpr double kTinyBox[3] = {0.2, 0.2, 0.1};
constexpr const char* kCpu = " --backend cpu --quiet";

std::string frameName(int index, const std::string& extension) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%05d.%s", index, extension.c_str());
    return name;
}

double speedOf(const HostParticles& p, std::size_t i) {
    return std::sqrt(double(p.vx[i]) * p.vx[i] + double(p.vy[i]) * p.vy[i] +
                     double(p.vz[i]) * p.vz[i]);
}

double meanHeight(const HostParticles& p) {
    double sum = 0;
    for (Real y : p.y) {
        sum += y;
    }
    return sum / double(p.size());
}

// Every position finite and inside the tiny scene's container (walls included).
void expectInsideTinyBox(const HostParticles& p) {
    const std::vector<Real>* axes[3] = {&p.x, &p.y, &p.z};
    for (int a = 0; a < 3; ++a) {
        for (std::size_t i = 0; i < p.size(); ++i) {
            const double v = (*axes[a])[i];
            ASSERT_TRUE(std::isfinite(v)) << "axis " << a << " particle " << i;
            ASSERT_GE(v, -1e-6) << "axis " << a << " particle " << i;
            ASSERT_LE(v, kTinyBox[a] + 1e-6) << "axis " << a << " particle " << i;
        }
    }
}

// Densities plausible for a weakly compressible fluid without boundary particles: particles at
// the free surface and the walls lack neighbours and read low (a corner about half), none reads
// far above rest density, and the bulk sits near it.
void expectPlausibleDensities(const HostParticles& p) {
    std::vector<double> rho(p.rho.begin(), p.rho.end());
    std::size_t near = 0;
    for (double r : rho) {
        ASSERT_TRUE(std::isfinite(r));
        ASSERT_GT(r, 0.4 * kRestDensity);
        ASSERT_LT(r, 1.2 * kRestDensity);
        near += std::abs(r - kRestDensity) < 0.25 * kRestDensity;
    }
    EXPECT_GE(near, rho.size() * 3 / 4);
    std::nth_element(rho.begin(), rho.begin() + rho.size() / 2, rho.end());
    EXPECT_NEAR(rho[rho.size() / 2], kRestDensity, 0.1 * kRestDensity);
}

// --- usage --------------------------------------------------------------------------------

TEST_F(Cli, HelpListsTheSubcommandsAndOptions) {
    RunResult top = weir("--help");
    EXPECT_EQ(top.exitCode, 0) << top.output;
    EXPECT_TRUE(contains(top.output, "Usage: weir"));
    EXPECT_TRUE(contains(top.output, "run"));
    EXPECT_TRUE(contains(top.output, "info"));

    RunResult run = weir("run --help");
    EXPECT_EQ(run.exitCode, 0) << run.output;
    EXPECT_TRUE(contains(run.output, "Usage: weir run"));
    for (const char* option : {"--backend", "--neighbours", "--particles", "--frames", "--out",
                               "--format", "--explain", "--quiet", "dam_break"}) {
        EXPECT_TRUE(contains(run.output, option));
    }
    EXPECT_TRUE(entries(dir_).empty());  // help writes nothing
}

// Running out of memory is an error of the run (exit 1) that says what ran out and what to try,
// not the bare "std::bad_alloc".
TEST(CliErrors, OutOfMemorySaysWhatRanOutAndWhatToTry) {
    CaughtError error{"", 0};
    try {
        throw std::bad_alloc();
    } catch (...) {
        error = caughtError();
    }
    EXPECT_EQ(error.exitCode, kExitError);
    EXPECT_TRUE(contains(error.what, "out of memory")) << error.what;
    EXPECT_TRUE(contains(error.what, "--particles")) << error.what;
    EXPECT_TRUE(contains(error.what, "particles.spacing")) << error.what;
}

TEST_F(Cli, UsageErrorsExitWith2) {
    RunResult none = weir("");
    EXPECT_EQ(none.exitCode, 2) << none.output;
    EXPECT_TRUE(contains(none.output, "subcommand"));
    EXPECT_TRUE(contains(none.output, "--help"));

    RunResult gpu = weir("run --backend gpu");
    EXPECT_EQ(gpu.exitCode, 2) << gpu.output;
    EXPECT_TRUE(contains(gpu.output, "--backend"));
    EXPECT_TRUE(contains(gpu.output, "gpu"));
    EXPECT_TRUE(contains(gpu.output, "auto,cuda,cpu"));  // what is allowed
    EXPECT_TRUE(contains(gpu.output, "--help"));

    RunResult negative = weir("run --particles -5");
    EXPECT_EQ(negative.exitCode, 2) << negative.output;
    EXPECT_TRUE(contains(negative.output, "--particles"));
    EXPECT_TRUE(contains(negative.output, "-5"));
    EXPECT_TRUE(contains(negative.output, "--help"));

    RunResult format = weir("run --format obj");
    EXPECT_EQ(format.exitCode, 2) << format.output;
    EXPECT_TRUE(contains(format.output, "obj"));

    RunResult unknown = weir("simulate");
    EXPECT_EQ(unknown.exitCode, 2) << unknown.output;

    // None of them started a run: no out/ directory appeared.
    EXPECT_TRUE(entries(dir_).empty());
}

TEST_F(Cli, InfoNamesTheCpu) {
    RunResult info = weir("info");
    EXPECT_EQ(info.exitCode, 0) << info.output;
    EXPECT_TRUE(contains(info.output, "weir " WEIR_VERSION));
    // The CPU line carries the model name from /proc/cpuinfo where there is one.
    std::string model = "CPU";
    std::ifstream cpuinfo("/proc/cpuinfo");
    for (std::string line; std::getline(cpuinfo, line);) {
        if (line.rfind("model name", 0) == 0) {
            model = line.substr(line.find(':') + 2);
            break;
        }
    }
    EXPECT_TRUE(contains(info.output, "cpu: " + model));
    EXPECT_TRUE(contains(info.output, "OpenMP threads"));
    EXPECT_TRUE(contains(info.output, "gpu: "));
    EXPECT_TRUE(contains(info.output, "dam_break"));
    EXPECT_TRUE(contains(info.output,
                         "grid cell ids: 32-bit (10 bits per axis) up to 1024 cells "
                         "per axis, 64-bit (21 bits per axis) past that"))
        << info.output;
}

// --- runs ---------------------------------------------------------------------------------

TEST_F(Cli, RunWritesVtuFramesThatParse) {
    writeFile("tiny.json", kTinyScene);
    RunResult run = weir("run tiny.json" + std::string(kCpu) + " --frames 3 --out frames");
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_TRUE(contains(run.output, "scene tiny (tiny.json)"));
    EXPECT_TRUE(contains(run.output, std::to_string(kTinyCount) + " particles on cpu"));
    EXPECT_TRUE(contains(run.output, "done, 4 frames"));

    // Exactly the four frames, the series and the index: no temporary files left behind.
    const fs::path out = dir_ / "frames";
    EXPECT_EQ(entries(out),
              (std::vector<std::string>{"frame.pvd", "frame_00000.vtu", "frame_00001.vtu",
                                        "frame_00002.vtu", "frame_00003.vtu", "frames.json"}));

    const Json index = Json::parse(fileText(out / "frames.json"));
    EXPECT_EQ(index["format"], "vtu");
    EXPECT_EQ(index["count"], 4);
    ASSERT_EQ(index["frames"].size(), 4u);
    const std::string pvd = fileText(out / "frame.pvd");
    std::size_t dataSets = 0;
    for (std::size_t at = pvd.find("<DataSet"); at != std::string::npos;
         at = pvd.find("<DataSet", at + 1)) {
        ++dataSets;
    }
    EXPECT_EQ(dataSets, 4u) << pvd;

    std::vector<HostParticles> frames;
    for (int k = 0; k <= 3; ++k) {
        SCOPED_TRACE("frame " + std::to_string(k));
        const std::string name = frameName(k, "vtu");
        const double time = k / kTinyFrameRate;
        EXPECT_EQ(index["frames"][k]["index"], k);
        EXPECT_EQ(index["frames"][k]["file"], name);
        EXPECT_NEAR(index["frames"][k]["time"].get<double>(), time, 1e-12);
        EXPECT_TRUE(contains(pvd, "file=\"" + name + "\""));

        double stored = -1;
        frames.push_back(readVtu((out / name).string(), &stored));
        const HostParticles& p = frames.back();
        EXPECT_NEAR(stored, time, 1e-12);
        EXPECT_NEAR(readVtuTime((out / name).string()), time, 1e-12);
        ASSERT_EQ(p.size(), kTinyCount);
        expectInsideTinyBox(p);
        expectPlausibleDensities(p);
    }

    // Frame 0 is the seeded lattice at rest, hydrostatic under the default model (delta-SPH):
    // the deepest layer, d/2 above the floor of the 0.12 m column, reads rho0 (1 + g depth / c^2)
    // with c^2 = 100 x 2 g H, i.e. rho0 (1 + (0.115 / 0.12) / 200).
    const HostParticles& first = frames[0];
    double densest = 0;
    for (std::size_t i = 0; i < first.size(); ++i) {
        ASSERT_EQ(speedOf(first, i), 0.0) << i;
        densest = std::max(densest, double(first.rho[i]));
    }
    EXPECT_NEAR(densest, kRestDensity * (1 + 0.115 / 0.12 / 200), 1e-4 * kRestDensity);

    // By frame 3 (0.1 s) the column is collapsing: it moved, fell, and no faster than a splash.
    const HostParticles& last = frames[3];
    double fastest = 0;
    for (std::size_t i = 0; i < last.size(); ++i) {
        fastest = std::max(fastest, speedOf(last, i));
    }
    EXPECT_GT(fastest, 0.3);
    EXPECT_LT(fastest, 2 * std::sqrt(2 * 9.81 * 0.12));
    EXPECT_LT(meanHeight(last), meanHeight(first) - 0.005);
    EXPECT_NE(first.x, last.x);
}

TEST_F(Cli, PlyAndCsvFramesParse) {
    writeFile("tiny.json", kTinyScene);
    RunResult vtu = weir("run tiny.json" + std::string(kCpu) + " --frames 1 --out vtu");
    ASSERT_EQ(vtu.exitCode, 0) << vtu.output;
    const HostParticles reference = readVtu(path("vtu/" + frameName(1, "vtu")));

    for (const std::string format : {"ply", "csv"}) {
        SCOPED_TRACE(format);
        RunResult run = weir("run tiny.json" + std::string(kCpu) + " --frames 1 --format " +
                             format + " --out " + format);
        ASSERT_EQ(run.exitCode, 0) << run.output;
        const fs::path out = dir_ / format;
        EXPECT_EQ(entries(out), (std::vector<std::string>{frameName(0, format),
                                                          frameName(1, format), "frames.json"}));
        const Json index = Json::parse(fileText(out / "frames.json"));
        EXPECT_EQ(index["format"], format);
        EXPECT_EQ(index["count"], 2);
        for (int k = 0; k <= 1; ++k) {
            const std::string file = (out / frameName(k, format)).string();
            HostParticles p = format == "ply" ? readPly(file) : readCsv(file);
            ASSERT_EQ(p.size(), kTinyCount) << file;
            expectInsideTinyBox(p);
            expectPlausibleDensities(p);
            if (k == 1) {
                // The same run as the vtu one, so the same state, whatever the format.
                double worst = 0;
                for (std::size_t i = 0; i < p.size(); ++i) {
                    worst = std::max({worst, std::abs(double(p.x[i]) - reference.x[i]),
                                      std::abs(double(p.y[i]) - reference.y[i]),
                                      std::abs(double(p.z[i]) - reference.z[i])});
                }
                EXPECT_LT(worst, 1e-6);
            }
        }
    }
}

TEST_F(Cli, BuiltinSceneRunsByName) {
    RunResult run =
        weir("run dam_break --particles 500 --frames 1" + std::string(kCpu) + " --out dam");
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_TRUE(contains(run.output, "scene dam_break (<built-in dam_break>)"));
    const HostParticles first = readVtu(path("dam/" + frameName(0, "vtu")));
    const HostParticles second = readVtu(path("dam/" + frameName(1, "vtu")));
    EXPECT_NEAR(double(first.size()), 500, 0.03 * 500);
    EXPECT_EQ(second.size(), first.size());
    EXPECT_TRUE(contains(run.output, std::to_string(first.size()) + " particles on cpu"));
    EXPECT_FALSE(fs::exists(path("dam/" + frameName(2, "vtu"))));
}

TEST_F(Cli, BadScenesExit1AndWriteNoFrames) {
    writeFile("bad.json", R"({
        "container": {"min": [0, 0, 0], "max": [0.2, 0.2, 0.1]},
        "blocks": [{"min": [0, 0, 0], "max": [0.08, 0.12, 0.1]}],
        "fluid": {"restDensity": -5},
        "particles": {"spacing": 0.01}
    })");
    RunResult bad = weir("run bad.json" + std::string(kCpu) + " --frames 1 --out bad_out");
    EXPECT_EQ(bad.exitCode, 1) << bad.output;
    EXPECT_TRUE(contains(bad.output, "bad.json"));
    EXPECT_TRUE(contains(bad.output, "fluid.restDensity"));
    EXPECT_TRUE(contains(bad.output, "-5"));
    EXPECT_TRUE(contains(bad.output, "> 0"));  // what is allowed
    EXPECT_FALSE(fs::exists(path("bad_out")));

    RunResult missing = weir("run missing.json" + std::string(kCpu) + " --out missing_out");
    EXPECT_EQ(missing.exitCode, 1) << missing.output;
    EXPECT_TRUE(contains(missing.output, "missing.json"));
    EXPECT_TRUE(contains(missing.output, "cannot open"));
    EXPECT_FALSE(fs::exists(path("missing_out")));

    // A scene that parses but cannot run (fluid too small for one particle) is exit 1 too.
    writeFile("thin.json", R"({
        "container": {"min": [0, 0, 0], "max": [0.2, 0.2, 0.1]},
        "blocks": [{"min": [0, 0, 0], "max": [0.005, 0.12, 0.1]}],
        "particles": {"spacing": 0.01}
    })");
    RunResult thin = weir("run thin.json" + std::string(kCpu) + " --out thin_out");
    EXPECT_EQ(thin.exitCode, 1) << thin.output;
    EXPECT_TRUE(contains(thin.output, "thin.json"));
    EXPECT_TRUE(contains(thin.output, "no particle"));
    EXPECT_FALSE(fs::exists(path("thin_out")));

    EXPECT_EQ(entries(dir_), (std::vector<std::string>{"bad.json", "thin.json"}));
}

TEST_F(Cli, BlowUpExits3AndKeepsTheFramesBefore) {
    // Far too stiff for a 5 ms step: the CFL limit is about 25 us.
    writeFile("blow.json", R"({
        "name": "blow",
        "container": {"min": [0, 0, 0], "max": [0.4, 0.3, 0.1]},
        "blocks": [{"min": [0, 0, 0], "max": [0.1, 0.2, 0.1]}],
        "fluid": {"stiffness": 1e5},
        "particles": {"spacing": 0.01},
        "time": {"duration": 1, "frameRate": 30, "timeStep": 0.005}
    })");
    RunResult run = weir("run blow.json" + std::string(kCpu) + " --frames 5 --out blow_out");
    ASSERT_EQ(run.exitCode, 3) << run.output;
    EXPECT_TRUE(contains(run.output, "warning: time step 0.005 s"));
    EXPECT_TRUE(contains(run.output, "blew up"));
    EXPECT_TRUE(contains(run.output, "step"));

    // "frames 0..K in DIR/ are complete and kept": exactly those exist, parse and are listed.
    std::smatch match;
    ASSERT_TRUE(std::regex_search(run.output, match, std::regex(R"(frames 0\.\.(\d+) in )")))
        << run.output;
    const int kept = std::stoi(match[1]);
    ASSERT_LT(kept, 5);
    const fs::path out = dir_ / "blow_out";
    const Json index = Json::parse(fileText(out / "frames.json"));
    EXPECT_EQ(index["count"], kept + 1);
    for (int k = 0; k <= kept; ++k) {
        SCOPED_TRACE("frame " + std::to_string(k));
        HostParticles p = readVtu((out / frameName(k, "vtu")).string());
        ASSERT_EQ(p.size(), 10u * 20u * 10u);
        for (std::size_t i = 0; i < p.size(); ++i) {
            ASSERT_TRUE(std::isfinite(p.x[i]) && std::isfinite(p.y[i]) && std::isfinite(p.z[i]));
            ASSERT_TRUE(std::isfinite(p.rho[i]));
        }
    }
    EXPECT_FALSE(fs::exists(out / frameName(kept + 1, "vtu")));
    EXPECT_EQ(entries(out).size(), std::size_t(kept + 1 + 2));  // frames, .pvd, frames.json
}

TEST_F(Cli, ExplainPrintsTheDerivation) {
    writeFile("tiny.json", kTinyScene);
    RunResult explained =
        weir("run tiny.json" + std::string(kCpu) + " --frames 0 --explain --out explained");
    ASSERT_EQ(explained.exitCode, 0) << explained.output;
    for (const char* line :
         {"fluid model delta-sph", "fluid model delta-SPH: ", "spacing d = 0.01 m (scene)",
          "smoothing radius h = 0.03 m (3 d)", "particle mass m = ", "expected top speed",
          "stiffness k = ", "viscosity: the fluid's own mu = ", "time step ",
          "per frame at the expected speed; CFL", "0.25 h / (c + max|v|)", "blow-up bound",
          "960 particles, grid 7 x 7 x 4 cells"}) {
        EXPECT_TRUE(contains(explained.output, line));
    }
    // The paper's model, one option away, derives its own.
    RunResult paper = weir("run tiny.json" + std::string(kCpu) +
                           " --model paper --frames 0 --explain --out paper");
    ASSERT_EQ(paper.exitCode, 0) << paper.output;
    for (const char* line : {"fluid model paper", "fluid model: the paper's", "viscosity mu = ",
                             "0.4 h / (c + max|v|)", "960 particles, grid 10 x 10 x 5 cells"}) {
        EXPECT_TRUE(contains(paper.output, line));
    }
    // --frames 0 writes the initial frame only.
    EXPECT_TRUE(fs::exists(path("explained/" + frameName(0, "vtu"))));
    EXPECT_FALSE(fs::exists(path("explained/" + frameName(1, "vtu"))));

    RunResult plain = weir("run tiny.json" + std::string(kCpu) + " --frames 0 --out plain");
    ASSERT_EQ(plain.exitCode, 0) << plain.output;
    EXPECT_EQ(plain.output.find("smoothing radius"), std::string::npos) << plain.output;
}

TEST_F(Cli, QuietHidesTheProgressLines) {
    writeFile("tiny.json", kTinyScene);
    RunResult loud = weir("run tiny.json --backend cpu --frames 2 --out loud");
    ASSERT_EQ(loud.exitCode, 0) << loud.output;
    EXPECT_TRUE(contains(loud.output, "frame 2/2"));
    RunResult quiet = weir("run tiny.json --backend cpu --frames 2 --quiet --out quiet");
    ASSERT_EQ(quiet.exitCode, 0) << quiet.output;
    EXPECT_EQ(quiet.output.find("frame 1/2"), std::string::npos) << quiet.output;
    EXPECT_TRUE(contains(quiet.output, "done, 3 frames"));
}

// Particle shifting switches at thresholds (free surface, walls, spray: physics/delta_sph.h), so
// summation-order rounding can flip one particle's shift and the runs part by more than rounding:
// these comparisons of the neighbour searches alone run without it.
std::string withoutShifting(std::string scene) {
    const std::size_t brace = scene.rfind('}');
    return scene.insert(brace, R"(, "fluid": {"shifting": 0})");
}

TEST_F(Cli, EveryNeighbourSearchGivesTheSameFluid) {
    writeFile("tiny.json", withoutShifting(kTinyScene));
    std::vector<HostParticles> states;
    for (const std::string mode : {"brute", "grid", "dense"}) {
        SCOPED_TRACE(mode);
        RunResult run = weir("run tiny.json" + std::string(kCpu) + " --frames 2 --neighbours " +
                             mode + " --out " + mode);
        ASSERT_EQ(run.exitCode, 0) << run.output;
        EXPECT_TRUE(contains(run.output, mode + " neighbours"));
        states.push_back(readVtu(path(mode + "/" + frameName(2, "vtu"))));
        ASSERT_EQ(states.back().size(), kTinyCount);
    }
    // Only the summation order differs, so after 2 frames (142 steps) the states agree to
    // float rounding (particles are written in their initial order in every mode).
    const HostParticles& brute = states[0];
    for (std::size_t s = 1; s < states.size(); ++s) {
        double worst = 0;
        for (std::size_t i = 0; i < brute.size(); ++i) {
            const HostParticles& p = states[s];
            worst = std::max({worst, std::abs(double(p.x[i]) - brute.x[i]),
                              std::abs(double(p.y[i]) - brute.y[i]),
                              std::abs(double(p.z[i]) - brute.z[i])});
        }
        EXPECT_LT(worst, 1e-4 * 0.01) << "state " << s;
    }
    EXPECT_LT(meanHeight(brute), 0.06 - 1e-3);  // and the fluid did fall
}

TEST_F(Cli, LongContainerRunsOnTheGridWithWideCellIds) {
    // 1025 cells of h = 1 cm along x: past the paper's 10-bit cell ids, where the grid used to
    // refuse; it now switches to 64-bit ids and says so.
    writeFile("long.json", withoutShifting(R"({
        "container": {"min": [0, 0, 0], "max": [10.25, 0.1, 0.1]},
        "blocks": [{"min": [0, 0, 0], "max": [0.04, 0.04, 0.04]}],
        "particles": {"spacing": 0.005, "smoothingRatio": 2}
    })"));
    RunResult paper = weir("run long.json" + std::string(kCpu) + " --frames 1 --neighbours grid" +
                           " --out paper");
    ASSERT_EQ(paper.exitCode, 0) << paper.output;
    EXPECT_TRUE(contains(paper.output, "grid neighbours")) << paper.output;
    EXPECT_TRUE(contains(paper.output, "cell ids: 64-bit (21 bits per axis)")) << paper.output;
    const HostParticles onGrid = readVtu(path("paper/" + frameName(1, "vtu")));
    EXPECT_EQ(onGrid.size(), 8u * 8u * 8u);

    // 1024 cells still fit the paper's 32-bit id: no switch, no line.
    writeFile("fits.json", R"({
        "container": {"min": [0, 0, 0], "max": [10.24, 0.1, 0.1]},
        "blocks": [{"min": [0, 0, 0], "max": [0.04, 0.04, 0.04]}],
        "particles": {"spacing": 0.005, "smoothingRatio": 2}
    })");
    RunResult fits =
        weir("run fits.json" + std::string(kCpu) + " --frames 1 --neighbours grid --out fits");
    ASSERT_EQ(fits.exitCode, 0) << fits.output;
    EXPECT_FALSE(contains(fits.output, "64-bit")) << fits.output;

    RunResult automatic = weir("run long.json" + std::string(kCpu) + " --frames 1 --out auto");
    ASSERT_EQ(automatic.exitCode, 0) << automatic.output;
    EXPECT_TRUE(contains(automatic.output, "dense neighbours"));
    EXPECT_FALSE(contains(automatic.output, "cell ids:")) << automatic.output;
    const HostParticles onDense = readVtu(path("auto/" + frameName(1, "vtu")));
    ASSERT_EQ(onDense.size(), 8u * 8u * 8u);
    // The same neighbours, so the same fluid up to summation order; and it fell.
    double worst = 0, fell = 0;
    for (std::size_t i = 0; i < onDense.size(); ++i) {
        worst = std::max({worst, std::abs(double(onGrid.x[i]) - onDense.x[i]),
                          std::abs(double(onGrid.y[i]) - onDense.y[i]),
                          std::abs(double(onGrid.z[i]) - onDense.z[i])});
        fell = std::max(fell, 0.04 - double(onGrid.y[i]));
    }
    EXPECT_LT(worst, 1e-4 * 0.005);
    EXPECT_GT(fell, 0.0);
}

// A DFSPH run's progress line gives each frame's steps, their dt and the fastest particle (the
// CFL condition's speed), and the solves' sweeps.
TEST_F(Cli, DfsphProgressGivesStepsSpeedAndSweeps) {
    RunResult run = weir(
        "run dam_break --solver dfsph --backend cpu --particles 1500 --frames 2 "
        "--format ply -o d");
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_TRUE(contains(run.output, " steps (dt ")) << run.output;
    EXPECT_TRUE(contains(run.output, "m/s), density solve ")) << run.output;
    EXPECT_TRUE(contains(run.output, "sweeps a step")) << run.output;
}

// Each solver's time to solution: wall seconds per simulated second, and DFSPH's own stages (the
// neighbour list and both solves) timed beside the paper's.
TEST_F(Cli, BenchGivesEachSolversTimePerSimulatedSecond) {
    double perSimulated[2] = {0, 0};
    int k = 0;
    for (const char* solver : {"wcsph", "dfsph"}) {
        const std::string out = std::string("b-") + solver;
        RunResult run = weir("bench --model delta-sph --solver " + std::string(solver) +
                             " --sizes 1000 --steps 3 --warmup 1 --settle 0.01 --budget 60 "
                             "--backends cpu-dense --no-plot --no-render --out " +
                             out);
        ASSERT_EQ(run.exitCode, 0) << run.output;
        EXPECT_TRUE(contains(run.output, "Wall s per simulated s")) << run.output;
        std::ifstream in(path(out + "/bench.json"));
        nlohmann::json record = nlohmann::json::parse(in);
        EXPECT_EQ(record["solver"], solver);
        const auto& c = record["runs"][0]["columns"]["cpu-dense"];
        ASSERT_TRUE(c.contains("wallSecondsPerSimulatedSecond")) << c.dump();
        perSimulated[k++] = c["wallSecondsPerSimulatedSecond"].get<double>();
        if (std::string(solver) == "dfsph") {
            for (const char* stage : {"neighbour list", "divergence", "pressure"}) {
                ASSERT_TRUE(c["stages"].contains(stage)) << stage << " " << c.dump();
                EXPECT_GT(c["stages"][stage].get<double>(), 0.0) << stage;
            }
            EXPECT_TRUE(contains(run.output, "Constant-density solve")) << run.output;
            // The sweeps of every timed step: a density solve takes at least 2, at most 100.
            ASSERT_TRUE(c.contains("densitySweepsPerStep")) << c.dump();
            EXPECT_GE(c["densitySweepsPerStep"].get<double>(), 2.0);
            EXPECT_LE(c["densitySweepsMax"].get<int>(), 100);
            EXPECT_GE(c["densitySweepsMax"].get<double>(), c["densitySweepsPerStep"].get<double>());
            EXPECT_GE(c["divergenceSweepsPerStep"].get<double>(), 1.0);
            EXPECT_TRUE(contains(run.output, "sweeps a step (max ")) << run.output;
        } else {
            EXPECT_FALSE(c.contains("densitySweepsPerStep")) << c.dump();
        }
    }
    EXPECT_GT(perSimulated[0], 0.0);
    EXPECT_GT(perSimulated[1], 0.0);
}

TEST_F(Cli, BenchTimesEveryStageOfEveryColumn) {
    // A smoke test of `weir bench` at a tiny size: asserts that every stage was timed and the
    // files were written, not how fast anything is.
    RunResult run = weir(
        "bench --sizes 400,800 --steps 3 --warmup 1 --settle 0.01 --budget 60 "
        "--backends cpu-brute,cpu-grid,cpu-dense --no-plot --out b");
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_TRUE(contains(run.output, "Pressure computation")) << run.output;
    std::ifstream in(path("b/bench.json"));
    ASSERT_TRUE(in.good());
    nlohmann::json record = nlohmann::json::parse(in);
    ASSERT_EQ(record["runs"].size(), 2u);
    for (const auto& r : record["runs"]) {
        EXPECT_GT(r["neighboursPerParticle"].get<double>(), 5.0);
#if defined(WEIR_HAS_RENDER)
        // The paper's point-sprite row, drawn offscreen (Mesa's software renderer in CI).
        ASSERT_TRUE(r.contains("pointSpriteMs")) << run.output;
        EXPECT_GT(r["pointSpriteMs"].get<double>(), 0.0);
#endif
        for (const char* column : {"cpu-brute", "cpu-grid", "cpu-dense"}) {
            const auto& c = r["columns"][column];
            ASSERT_FALSE(c.contains("skipped")) << column;
            for (const char* stage : {"density", "force"}) {
                EXPECT_GT(c["stages"][stage].get<double>(), 0.0) << column << " " << stage;
            }
            // The dense path fuses displacement into the force stage.
            if (std::string(column) != "cpu-dense") {
                EXPECT_GT(c["stages"]["integrate"].get<double>(), 0.0) << column;
            } else {
                EXPECT_EQ(c["stages"]["integrate"].get<double>(), 0.0) << column;
            }
            if (std::string(column) != "cpu-brute") {
                EXPECT_GT(c["stages"]["grid"].get<double>(), 0.0) << column;
                EXPECT_GT(c["stepMs"].get<double>(), 0.0) << column;
            }
            EXPECT_GT(c["totalMs"].get<double>(), 0.0) << column;
            EXPECT_GT(c["particleStepsPerSecond"].get<double>(), 0.0) << column;
            EXPECT_EQ(c["threads"].get<int>(), omp_get_max_threads()) << column;
        }
    }
    EXPECT_TRUE(fs::exists(path("b/bench.csv")));
}

TEST_F(Cli, BenchRejectsUnknownColumns) {
    RunResult run = weir("bench --sizes 400 --backends cpu-fast --no-plot --out b");
    EXPECT_EQ(run.exitCode, 2) << run.output;
    EXPECT_TRUE(contains(run.output, "cpu-fast")) << run.output;
}

}  // namespace
}  // namespace weir
