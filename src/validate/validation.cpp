// The validation cases of `weir validate`: hydrostatic tank, Martin & Moyce dam break over a
// resolution ladder, and the viscous dam break.
#include "validate/validation.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <sstream>
#include <utility>

#include "core/check.h"
#include "scene/scene.h"
#include "scene/setup.h"
#include "solver/density_deviation.h"
#include "solver/simulation.h"
#include "validate/martin_moyce.h"
#include "validate/plot_script.h"

namespace weir {
namespace {

constexpr double kG = 9.81;
constexpr double kPiD = 3.14159265358979323846;

std::string num(double v) {
    std::ostringstream s;
    s.precision(10);
    s << v;
    return s.str();
}

double seconds(std::chrono::steady_clock::time_point since) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

std::string box(double x, double y, double z) {
    return "[" + num(x) + ", " + num(y) + ", " + num(z) + "]";
}

// The fluid section of a validation scene: a preset, `fields` (more "name": value pairs, each
// led by a comma), the model asked for (or the default).
std::string fluidJson(const std::string& preset, const ValidationOptions& o,
                      const std::string& fields = "") {
    std::string json = R"({"preset": ")" + preset + "\"";
    if (preset == "water") {
        json += R"(, "restDensity": 1000)";
    }
    json += fields;
    if (!o.model.empty()) {
        json += R"(, "model": ")" + o.model + "\"";
    }
    if (o.shifting) {
        json += R"(, "shifting": )" + num(*o.shifting);
    }
    return json + "}";
}

// The scene of one case: a container from the origin (periodic along `periodic`) holding one
// block of fluid from the origin corner; `extra`: more top-level fields, each led by a comma.
struct CaseScene {
    CaseScene(std::string name_, const Vec3d& container_, const Vec3d& block_,
              std::array<bool, 3> periodic_ = {})
        : name(std::move(name_)), container(container_), block(block_), periodic(periodic_) {}
    std::string name;  // the scene's name, validate_NAME; errors say "<validate NAME>"
    Vec3d container, block;
    std::array<bool, 3> periodic;
    std::string fluid;
    double spacing = 0, duration = 0, frameRate = 0;
    std::string walls = R"({"model": "particles"})";  // "" leaves the scene's default
    std::string extra;
    std::optional<double> smoothingRatio;  // particles.smoothingRatio; unset: the default
};

// A periodic slab's depth in spacings: `atLeast`, or more where the smoothing ratio needs it (a
// periodic axis at least two smoothing radii long: checkPeriodicLengths).
double slabSpacings(const ValidationOptions& o, double atLeast = 4) {
    const double ratio = o.smoothingRatio.value_or(defaultSmoothingRatio(
        o.model == "paper" ? FluidModelName::Paper : FluidModelName::DeltaSph, o.solver));
    return std::max(atLeast, std::ceil(2 * ratio - 1e-9));
}

std::string sceneJson(const CaseScene& c) {
    auto flag = [](bool b) { return std::string(b ? "true" : "false"); };
    return R"({"name": "validate_)" + c.name + R"(", "container": {"min": [0, 0, 0], "max": )" +
           box(c.container.x, c.container.y, c.container.z) + R"(, "periodic": [)" +
           flag(c.periodic[0]) + ", " + flag(c.periodic[1]) + ", " + flag(c.periodic[2]) +
           R"(]}, "blocks": [{"min": [0, 0, 0], "max": )" + box(c.block.x, c.block.y, c.block.z) +
           R"(}], "fluid": )" + c.fluid + R"(, "particles": {"spacing": )" + num(c.spacing) +
           (c.smoothingRatio ? R"(, "smoothingRatio": )" + num(*c.smoothingRatio) : "") + "}" +
           (c.walls.empty() ? "" : R"(, "walls": )" + c.walls) + c.extra +
           R"(, "time": {"duration": )" + num(c.duration) + R"(, "frameRate": )" +
           num(c.frameRate) + "}}";
}

// A case's simulation through the ordinary scene path; `adjust` may change the initial
// particles before they go to the backend. `scene` and `report` receive what was derived.
std::unique_ptr<Simulation> startCase(const ValidationOptions& o, const CaseScene& c, Scene& scene,
                                      SetupReport& report,
                                      const std::function<void(SimulationSetup&)>& adjust = {}) {
    CaseScene asked = c;
    if (o.smoothingRatio) {
        asked.smoothingRatio = o.smoothingRatio;
    }
    scene = parseScene(sceneJson(asked), "<validate " + c.name + ">");
    if (!o.solver.empty()) {
        scene = withSolver(scene, o.solver);
    }
    SimulationSetup setup = buildSetup(scene, {}, &report);
    if (adjust) {
        adjust(setup);
    }
    return makeSimulation(o.backend, NeighbourMode::Auto, std::move(setup));
}

// Advances to time t; a blow-up throws with the case's name and the diagnosis.
void advanceCase(Simulation& sim, double t, const std::string& what) {
    sim.advanceTo(t);
    if (sim.fault().code != 0) {
        throw SimulationError(what + ": " + describeFault(sim.fault(), sim.params()));
    }
}

void say(const ValidationOptions& o, const std::string& line) {
    if (!o.quiet) {
        std::cerr << "weir validate: " << line << "\n";
    }
}

// A tank of water depth H, width H and a slab 6 d deep (more where the smoothing ratio needs it
// for interior layers h from every wall), walls of boundary particles.
void runTank(const ValidationOptions& o, ValidationReport& r) {
    const double H = 0.3, d = H / o.tankResolution, W = std::max(6.0, slabSpacings(o) + 2) * d;
    CaseScene spec{"hydrostatic", {H, 1.5 * H, W}, {H, H, W}};
    spec.fluid = fluidJson("water", o);
    spec.spacing = d;
    spec.duration = o.settleTime;
    spec.frameRate = 10;
    Scene scene;
    SetupReport setupReport;
    auto sim = startCase(o, spec, scene, setupReport);
    const double h = setupReport.smoothingRadius;
    r.tankParticles = int(sim->particleCount());
    r.tankDepth = H;
    r.tankSpacing = d;
    r.rho0gH = 1000.0 * kG * H;
    say(o, "hydrostatic tank, " + std::to_string(r.tankParticles) + " particles");
    const auto start = std::chrono::steady_clock::now();

    // Layers d thick, each at its lattice row; the interior lies h from the side walls (the
    // boundary particles' reach) and 2 h below the surface (its particles lack neighbours and
    // read light). The floor's layer is the wall layer.
    const int layers = int(std::floor(H / d));
    std::vector<double> sum(layers, 0.0);
    std::vector<long> count(layers, 0);
    DensityDeviation worst;
    double straySquares = 0, strayMax = 0, surface = 0;
    long strayCount = 0;
    HostParticles p;
    const int averaged = 9;  // frames over the last 40% of the run, every 5%
    const int columnsX = std::max(1, int(std::floor(H / d))), columnsZ = std::max(1, int(W / d));
    for (int k = 0; k < averaged; ++k) {
        advanceCase(*sim, o.settleTime * (0.6 + 0.05 * k), "hydrostatic tank");
        sim->download(p);
        const DensityDeviation dev = densityDeviation(p, 1000.0);
        worst.max = std::max(worst.max, dev.max);
        worst.mean = std::max(worst.mean, dev.mean);
        std::vector<double> top(std::size_t(columnsX * columnsZ), -1.0);
        for (std::size_t i = 0; i < p.size(); ++i) {
            const double v2 =
                double(p.vx[i]) * p.vx[i] + double(p.vy[i]) * p.vy[i] + double(p.vz[i]) * p.vz[i];
            if (k == averaged - 1) {
                straySquares += v2;
                strayMax = std::max(strayMax, std::sqrt(v2));
                ++strayCount;
            }
            const double x = p.x[i], y = p.y[i], z = p.z[i];
            const int cx = std::clamp(int(x / d), 0, columnsX - 1);
            const int cz = std::clamp(int(z / d), 0, columnsZ - 1);
            double& t = top[std::size_t(cz * columnsX + cx)];
            t = std::max(t, y);
            if (x < h || x > H - h || z < h || z > W - h) {
                continue;
            }
            const int layer = int(y / d);
            if (layer >= 0 && layer < layers) {
                sum[layer] += p.p[i];
                ++count[layer];
            }
        }
        // The surface: the top particle of each column, plus its half spacing.
        double topSum = 0;
        int topCount = 0;
        for (double t : top) {
            if (t >= 0) {
                topSum += t + 0.5 * d;
                ++topCount;
            }
        }
        surface += topCount > 0 ? topSum / topCount / averaged : 0;
    }
    r.tankSeconds = seconds(start);
    double worstLayer = 0, sy = 0, sp = 0, syy = 0, syp = 0;
    int used = 0;
    for (int l = 0; l < layers; ++l) {
        const double y = (l + 0.5) * d;
        if (count[l] == 0) {
            continue;
        }
        const double mean = sum[l] / double(count[l]), reference = 1000.0 * kG * (H - y);
        if (l == 0) {
            r.wallLayerPressure = mean;
            r.wallLayerReference = reference;
        }
        if (y < h || y > H - 2 * h) {
            continue;
        }
        r.layerY.push_back(y);
        r.layerPressure.push_back(mean);
        r.layerReference.push_back(reference);
        worstLayer = std::max(worstLayer, std::abs(mean - reference));
        sy += y;
        sp += mean;
        syy += y * y;
        syp += y * mean;
        ++used;
    }
    const double slope =
        used > 1 ? (used * syp - sy * sp) / (used * syy - sy * sy) : 0;  // least squares dp/dy
    r.pressureGradient = slope;
    r.surfaceDrift = std::abs(surface - H) / d;
    const double freeFall = std::sqrt(2 * kG * H);
    r.checks.push_back(
        {"hydrostatic: interior layer pressure, max |mean - rho0 g depth| / rho0 g H",
         used > 0 ? worstLayer / r.rho0gH : 1e30, kLayerPressureTolerance, ""});
    r.checks.push_back({"hydrostatic: pressure gradient |dp/dy / (-rho0 g) - 1|",
                        used > 1 ? std::abs(slope / (-1000.0 * kG) - 1) : 1e30,
                        kPressureGradientTolerance, ""});
    r.checks.push_back(
        {"hydrostatic: floor layer pressure |mean / rho0 g depth - 1|",
         r.wallLayerReference > 0 ? std::abs(r.wallLayerPressure / r.wallLayerReference - 1) : 1e30,
         kWallLayerPressureTolerance, ""});
    r.checks.push_back(
        {"hydrostatic: surface drift / spacing", r.surfaceDrift, kSurfaceDriftTolerance, ""});
    r.checks.push_back({"hydrostatic: max density deviation at rest (rho - rho0) / rho0", worst.max,
                        kDensityDeviationTolerance, ""});
    r.checks.push_back({"hydrostatic: mean density deviation at rest", worst.mean,
                        kMeanDensityDeviationTolerance, ""});
    r.checks.push_back({"hydrostatic: stray velocity RMS / sqrt(2 g H)",
                        std::sqrt(straySquares / double(std::max(1L, strayCount))) / freeFall,
                        kStraySpeedTolerance, ""});
    r.checks.push_back({"hydrostatic: stray velocity max / sqrt(2 g H)", strayMax / freeFall,
                        4 * kStraySpeedTolerance, ""});
}

// Martin & Moyce's column (width a, height n^2 a) of `preset` fluid in a slab 4 d deep
// (slabSpacings), periodic across it (a plane flow, as the experiment's), with the walls' own slip
// condition.
FrontRun runDamBreak(const ValidationOptions& o, int resolution, const std::string& preset) {
    const double a = kMartinMoyceWidth, d = a / resolution;
    const double height = kMartinMoyceHeightRatio * a, depth = slabSpacings(o) * d;
    const double timeScale = std::sqrt(2 * kG / a);  // T = t sqrt(2 g / a)
    const double endTime = o.damEndT / timeScale;
    const double length = a * (1.5 + 1.4 * o.damEndT);  // past the front at the end
    const double frameRate = timeScale / 0.125;         // a frame every 0.125 in T
    CaseScene spec{
        "martin_moyce", {length, 1.5 * height, depth}, {a, height, depth}, {false, false, true}};
    spec.fluid = fluidJson(preset, o);
    spec.spacing = d;
    spec.duration = endTime;
    spec.frameRate = frameRate;
    Scene scene;
    SetupReport setupReport;
    auto sim = startCase(o, spec, scene, setupReport);
    FrontRun run;
    run.fluid = preset;
    run.resolution = resolution;
    run.particles = int(sim->particleCount());
    say(o, "dam break, " + preset + ", " + std::to_string(resolution) + " across the column, " +
               std::to_string(run.particles) + " particles");
    const double restDensity = scene.restDensity;
    const auto start = std::chrono::steady_clock::now();
    HostParticles p;
    for (std::int64_t k = 1; k <= setupReport.frames; ++k) {
        const double t = double(k) / frameRate;
        advanceCase(*sim, t,
                    "dam break (" + preset + ", " + std::to_string(resolution) + " across)");
        sim->download(p);
        // The leading edge: the furthest particle, plus half a spacing (its share of the front).
        double front = 0;
        for (std::size_t i = 0; i < p.size(); ++i) {
            front = std::max(front, double(p.x[i]));
        }
        run.T.push_back(t * timeScale);
        run.Z.push_back((front + 0.5 * d) / a);
        run.maxDensityDeviation =
            std::max(run.maxDensityDeviation, densityDeviation(p, restDensity).max);
    }
    run.seconds = seconds(start);
    // Simulated Z at the measured T, linearly interpolated; T = 0 is Z = 1. No time shift.
    double squares = 0, relativeSquares = 0;
    for (const SurgePoint& ref : kMartinMoyceSurge) {
        if (run.T.empty() || ref.T > run.T.back()) {
            break;
        }
        double prevT = 0, prevZ = 1;
        for (std::size_t k = 0; k < run.T.size(); ++k) {
            if (run.T[k] >= ref.T) {
                const double w = (ref.T - prevT) / (run.T[k] - prevT);
                const double z = prevZ + w * (run.Z[k] - prevZ);
                squares += (z - ref.Z) * (z - ref.Z);
                const double relative = (z - ref.Z) / ref.Z;
                relativeSquares += relative * relative;
                run.maxRelative = std::max(run.maxRelative, std::abs(relative));
                ++run.points;
                break;
            }
            prevT = run.T[k];
            prevZ = run.Z[k];
        }
    }
    run.rmsAbsolute = run.points > 0 ? std::sqrt(squares / run.points) : 1e30;
    run.rmsRelative = run.points > 0 ? std::sqrt(relativeSquares / run.points) : 1e30;
    if (run.points == 0) {
        run.maxRelative = 1e30;
    }
    say(o, "  front RMS error " + num(std::round(run.rmsRelative * 1000) / 10) + "%, max " +
               num(std::round(run.maxRelative * 1000) / 10) + "% in " +
               num(std::round(run.seconds * 10) / 10) + " s");
    return run;
}

// A ladder's resolutions, coarse to fine, each once.
std::vector<int> sortedRungs(std::vector<int> rungs) {
    std::sort(rungs.begin(), rungs.end());
    rungs.erase(std::unique(rungs.begin(), rungs.end()), rungs.end());
    return rungs;
}

// One check per step up a ladder: a finer rung's error may exceed the coarser's by at most
// kLadderGrowthTolerance. what: the check's name up to "grows from".
void addLadderChecks(ValidationReport& r, const std::string& what,
                     const std::vector<int>& resolutions, const std::vector<double>& errors) {
    for (std::size_t k = 1; k < resolutions.size(); ++k) {
        r.checks.push_back({what + " grows from " + std::to_string(resolutions[k - 1]) + " to " +
                                std::to_string(resolutions[k]) + " across by",
                            errors[k] - errors[k - 1], kLadderGrowthTolerance, ""});
    }
}

void runLadder(const ValidationOptions& o, ValidationReport& r) {
    for (int resolution : sortedRungs(o.columnResolutions)) {
        r.ladder.push_back(runDamBreak(o, resolution, "water"));
    }
    const FrontRun& finest = r.ladder.back();
    const std::string at = " (" + std::to_string(finest.resolution) + " across the column, " +
                           std::to_string(finest.points) + " points)";
    r.checks.push_back({"dam break: front RMS relative error vs Martin & Moyce" + at,
                        finest.rmsRelative, kFrontRmsRelativeTolerance, ""});
    r.checks.push_back({"dam break: front max relative error vs Martin & Moyce" + at,
                        finest.maxRelative, kFrontMaxRelativeTolerance, ""});
    std::vector<int> resolutions;
    std::vector<double> errors;
    for (const FrontRun& run : r.ladder) {
        resolutions.push_back(run.resolution);
        errors.push_back(run.rmsRelative);
    }
    addLadderChecks(r, "dam break ladder: RMS relative error", resolutions, errors);
    double worst = 0;
    for (const FrontRun& run : r.ladder) {
        worst = std::max(worst, run.maxDensityDeviation);
    }
    r.checks.push_back({"dam break: max density deviation during the surge", worst,
                        kDensityDeviationTolerance, ""});
}

// Water, olive oil and honey from the same column: the fluid's own viscosity has to show. The
// front's travel Z - 1 at the end, honey against water.
void runViscous(const ValidationOptions& o, ValidationReport& r) {
    const int resolution =
        *std::min_element(o.columnResolutions.begin(), o.columnResolutions.end());
    for (const char* preset : {"water", "oil", "honey"}) {
        r.viscous.push_back(runDamBreak(o, resolution, preset));
    }
    const double water = r.viscous[0].Z.back() - 1, oil = r.viscous[1].Z.back() - 1,
                 honey = r.viscous[2].Z.back() - 1;
    r.checks.push_back({"viscous dam break: honey's front travel / water's at the end",
                        honey / water, kViscousFrontRatio, ""});
    r.checks.push_back(
        {"viscous dam break: oil's front travel / water's - 1 (oil no faster than water)",
         oil / water - 1, 0.02, ""});
    r.checks.push_back(
        {"viscous dam break: honey's front travel / oil's - 1 (honey slower than oil)",
         honey / oil - 1, 0.0, ""});
}

// Start-up channel flow, Morris et al. 1997's set-up: L = 1 mm, water (nu = 1e-6), walls of
// boundary particles (no-slip) at y = 0 and L, periodic along x and z. Poiseuille: body force
// F = 1e-4 m/s^2 along x (u_max = 1.25e-5 m/s); Couette: the top wall slides at V0 = 1.25e-5 m/s.
// The speed of sound is set to 10 times the flow's speed, as in the paper (stiffness c^2).
ChannelRun runChannel(const ValidationOptions& o, const std::string& flow) {
    const double L = 1e-3, nu = 1e-6, F = 1e-4, scale = F * L * L / (8 * nu);
    const int n = o.channelResolution;
    const double d = L / n, lx = slabSpacings(o, 8) * d, lz = slabSpacings(o, 6) * d,
                 c = 10 * scale;
    const bool poiseuille = flow == "poiseuille";
    CaseScene spec{flow, {lx, L, lz}, {lx, L, lz}, {true, false, true}};
    spec.fluid = fluidJson("water", o, R"(, "viscosity": 0.001, "stiffness": )" + num(c * c));
    spec.spacing = d;
    spec.duration = 0.5;
    spec.frameRate = 40;
    spec.walls =
        R"({"model": "particles", "slip": "no-slip")" +
        (poiseuille ? std::string()
                    : R"(, "moving": [{"face": "+y", "velocity": )" + box(scale, 0, 0) + "}]") +
        "}";
    spec.extra = R"(, "gravity": )" + (poiseuille ? box(F, 0, 0) : box(0, 0, 0)) +
                 R"(, "limits": {"maxSpeed": )" + num(100 * scale) + "}";
    Scene scene;
    SetupReport setupReport;
    auto sim = startCase(o, spec, scene, setupReport);
    ChannelRun run;
    run.flow = flow;
    run.resolution = n;
    run.particles = int(sim->particleCount());
    say(o, flow + " flow, " + std::to_string(n) + " across the channel, " +
               std::to_string(run.particles) + " particles");
    for (int layer = 0; layer < n; ++layer) {
        run.eta.push_back((layer + 0.5) / n);
    }
    const auto start = std::chrono::steady_clock::now();
    HostParticles p;
    for (double theta : {0.0225, 0.045, 0.1125, 0.225, 0.5}) {
        advanceCase(*sim, theta * L * L / nu, flow + " flow");
        sim->download(p);
        std::vector<double> sum(std::size_t(n), 0.0);
        std::vector<int> count(std::size_t(n), 0);
        for (std::size_t i = 0; i < p.size(); ++i) {
            const int layer = std::clamp(int(std::floor(double(p.y[i]) / d)), 0, n - 1);
            sum[std::size_t(layer)] += p.vx[i];
            ++count[std::size_t(layer)];
        }
        std::vector<double> u, ref;
        double error = 0;
        for (int layer = 0; layer < n; ++layer) {
            const double eta = run.eta[std::size_t(layer)];
            u.push_back(count[std::size_t(layer)] > 0
                            ? sum[std::size_t(layer)] / count[std::size_t(layer)] / scale
                            : 0);
            ref.push_back(poiseuille ? poiseuilleVelocity(eta, theta)
                                     : couetteVelocity(eta, theta));
            error = std::max(error, std::abs(u.back() - ref.back()));
        }
        run.theta.push_back(theta);
        run.u.push_back(u);
        run.uRef.push_back(ref);
        run.error.push_back(error);
    }
    run.seconds = seconds(start);
    return run;
}

void runChannels(const ValidationOptions& o, ValidationReport& r) {
    for (const char* flow : {"poiseuille", "couette"}) {
        r.channels.push_back(runChannel(o, flow));
        const ChannelRun& run = r.channels.back();
        double startup = 0;
        for (std::size_t k = 0; k + 1 < run.error.size(); ++k) {
            startup = std::max(startup, run.error[k]);
        }
        const std::string at = " (" + std::to_string(run.resolution) + " across)";
        const std::string scale = std::string(flow) == "poiseuille" ? "u_max" : "V0";
        r.checks.push_back({std::string(flow) + ": start-up profiles, max |u - u_series| / " +
                                scale + " at theta 0.0225-0.225" + at,
                            startup, kChannelStartupTolerance, ""});
        r.checks.push_back(
            {std::string(flow) + ": steady profile (theta 0.5), max |u - u_series| / " + scale + at,
             run.error.back(), kChannelSteadyTolerance, ""});
    }
}

// Lobovsky et al. (2014), H = 300 mm: a column L = 0.6 m long and H = 0.3 m high against the
// back wall of a tank 1.61 m long, released by a gate at x = 0.6 m (its measured opening is the
// experiment's time origin); the impact wall at x = 1.61 m carries pressure sensors 2, 3 and 4 at
// 15, 30 and 80 mm. A plane flow: the slab is 4 d deep (slabSpacings) and periodic across.
// Reference (their ETSIN front and ~100-repetition pressure percentiles, as distributed with
// AQUAgpusph; facts): the front's (x - gate) / H against tau = t sqrt(g / H), and the filtered
// pressure peaks.
struct LobovskyFrontPoint {
    double tau, x;
};
constexpr LobovskyFrontPoint kLobovskyFront[] = {
    {0.2859, 0.1995}, {0.4765, 0.3815}, {0.6671, 0.5529}, {0.8578, 0.7349}, {1.0484, 0.9729},
    {1.2390, 1.2214}, {1.4296, 1.4926}, {1.6202, 1.7656}, {1.8108, 2.0561}, {2.0014, 2.3675},
    {2.1921, 2.6895}, {2.3827, 3.0062}, {2.5733, 3.3658},
};
struct PressureBand {
    double low, median, high;  // peak p / (rho g H): 2.5%, median, 97.5% curves
};
constexpr PressureBand kLobovskyPeaks[] = {{1.7710, 1.8708, 2.0316},   // sensor 2, tau 2.60
                                           {1.3338, 1.4532, 1.6494},   // sensor 3, tau 2.76
                                           {0.7388, 0.8819, 1.1484}};  // sensor 4, tau 6.0
constexpr double kLobovskySensorHeight[] = {0.015, 0.030, 0.080};

void runLobovsky(const ValidationOptions& o, ValidationReport& r) {
    const double H = 0.3, L = 0.6, length = 1.61, d = H / o.lobovskyResolution,
                 depth = slabSpacings(o) * d;
    const double tauScale = std::sqrt(kG / H), travel = (length - L) / H;
    const double endTau = 6.5;
    CaseScene spec{"lobovsky", {length, 0.6, depth}, {L, H, depth}, {false, false, true}};
    spec.fluid = fluidJson("water", o);
    spec.spacing = d;
    spec.duration = endTau / tauScale;
    spec.frameRate = 100;
    Scene scene;
    SetupReport setupReport;
    auto sim = startCase(o, spec, scene, setupReport);
    const double support = setupReport.smoothingRadius, rhogH = scene.restDensity * kG * H;
    LobovskyRun run;
    run.resolution = o.lobovskyResolution;
    run.particles = int(sim->particleCount());
    say(o, "Lobovsky dam break, " + std::to_string(run.resolution) + " over H, " +
               std::to_string(run.particles) + " particles");
    const auto start = std::chrono::steady_clock::now();
    HostParticles p;
    // Every 0.01 in tau: the impacts are short (the first peak rises in ~0.1).
    for (int k = 1; k <= int(std::lround(endTau / 0.01)); ++k) {
        const double tau = 0.01 * k;
        advanceCase(*sim, tau / tauScale, "Lobovsky dam break");
        sim->download(p);
        double front = 0;
        for (std::size_t i = 0; i < p.size(); ++i) {
            front = std::max(front, double(p.x[i]));
        }
        if (k % 5 == 0) {
            run.frontTau.push_back(tau);
            run.frontX.push_back((std::min(front + 0.5 * d, length) - L) / H);
        }
        // Each sensor reads the fluid's pressure interpolated to its centre on the wall, by a
        // Shepard-normalised Wendland weight over the support radius.
        std::array<double, 3> reading{};
        for (int s = 0; s < 3; ++s) {
            double sumW = 0, sumP = 0;
            for (std::size_t i = 0; i < p.size(); ++i) {
                const double dx = length - double(p.x[i]),
                             dy = kLobovskySensorHeight[s] - double(p.y[i]);
                const double q = std::sqrt(dx * dx + dy * dy) / support;
                if (q < 1) {
                    const double w = std::pow(1 - q, 4) * (1 + 4 * q);
                    sumW += w;
                    sumP += w * double(p.p[i]);
                }
            }
            reading[std::size_t(s)] = sumW > 0 ? sumP / sumW / rhogH : 0;
        }
        run.pressureTau.push_back(tau);
        run.pressure.push_back(reading);
    }
    run.seconds = seconds(start);
    // Front: interpolated at the measured times; no time shift.
    double squares = 0;
    int used = 0;
    for (const LobovskyFrontPoint& ref : kLobovskyFront) {
        for (std::size_t k = 1; k < run.frontTau.size(); ++k) {
            if (run.frontTau[k] >= ref.tau) {
                const double w =
                    (ref.tau - run.frontTau[k - 1]) / (run.frontTau[k] - run.frontTau[k - 1]);
                const double x = run.frontX[k - 1] + w * (run.frontX[k] - run.frontX[k - 1]);
                squares += (x - ref.x) * (x - ref.x);
                ++used;
                break;
            }
        }
    }
    run.frontRms = used > 0 ? std::sqrt(squares / used) / travel : 1e30;
    // Peaks of the 3-sample running mean (the experiment's curves are filtered too).
    for (int s = 0; s < 3; ++s) {
        for (std::size_t k = 1; k + 1 < run.pressure.size(); ++k) {
            const double mean =
                (run.pressure[k - 1][std::size_t(s)] + run.pressure[k][std::size_t(s)] +
                 run.pressure[k + 1][std::size_t(s)]) /
                3;
            // Sensor 4's peak is the returning wave's (tau ~ 6); the others, the first impact's.
            const bool inWindow = s == 2 ? run.pressureTau[k] > 4.5 : run.pressureTau[k] < 4.0;
            if (inWindow && mean > run.peak[std::size_t(s)]) {
                run.peak[std::size_t(s)] = mean;
                run.peakTau[std::size_t(s)] = run.pressureTau[k];
            }
        }
    }
    const std::string at = " (" + std::to_string(run.resolution) + " over H)";
    r.checks.push_back({"Lobovsky: front RMS error / travel to the wall, no time shift" + at,
                        run.frontRms, kLobovskyFrontTolerance, ""});
    for (int s = 0; s < 3; ++s) {
        const PressureBand& band = kLobovskyPeaks[s];
        const double peak = run.peak[std::size_t(s)];
        // Distance outside the 2.5-97.5% band of the peak, relative to the median (0 inside).
        const double outside = std::max({0.0, band.low - peak, peak - band.high}) / band.median;
        r.checks.push_back({"Lobovsky: sensor " + std::to_string(s + 2) + " peak p / rho g H = " +
                                num(std::round(peak * 100) / 100) + " at tau " +
                                num(run.peakTau[std::size_t(s)]) + ", outside the band [" +
                                num(band.low) + ", " + num(band.high) + "] by" + at,
                            outside, 0.0, ""});
    }
    say(o, "  front RMS " + num(std::round(run.frontRms * 1000) / 10) + "% of the travel, in " +
               num(std::round(run.seconds * 10) / 10) + " s");
    r.lobovsky.push_back(std::move(run));
}

// The 2-D Taylor-Green vortex at Re = U L / nu = 100 in a periodic box (L = 1 m, U = 1 m/s,
// water's density, nu = 0.01 m^2/s, a slab 4 d deep (slabSpacings), periodic on every axis, no
// gravity, speed of sound 10 U): u = -U cos(2 pi x / L) sin(2 pi y / L), v = U sin(2 pi x / L)
// cos(2 pi y / L), with the analytic pressure's density at t = 0. Its kinetic energy decays as
// exp(2 b t), b = -8 pi^2 nu / L^2; the rate is fitted (least squares of ln E) over t = 0.25 to 2 L
// / U. The vortex runs with particle shifting on (fluid.shifting 1) unless --shifting says
// otherwise: without it the lattice tears at the stagnation points (docs/physics.md).
TaylorGreenRun runTaylorGreenAt(const ValidationOptions& options, int n, double decayReference) {
    ValidationOptions o = options;
    o.shifting = options.shifting.value_or(1.0);
    const double L = 1, U = 1, nu = 0.01, rho0 = 1000, c = 10 * U;
    const double d = L / n, depth = slabSpacings(o) * d;
    CaseScene spec{"taylor_green", {L, L, depth}, {L, L, depth}, {true, true, true}};
    spec.fluid = fluidJson(
        "water", o, R"(, "viscosity": )" + num(rho0 * nu) + R"(, "stiffness": )" + num(c * c));
    spec.spacing = d;
    spec.duration = 2;
    spec.frameRate = 8;
    spec.walls = "";
    spec.extra = R"(, "gravity": [0, 0, 0], "limits": {"maxSpeed": )" + num(20 * U) + "}";
    Scene scene;
    SetupReport setupReport;
    auto sim = startCase(o, spec, scene, setupReport, [&](SimulationSetup& setup) {
        WEIR_REQUIRE(!setup.seeder,
                     "weir validate: the Taylor-Green particles were not on the host");
        HostParticles& init = setup.particles;
        for (std::size_t i = 0; i < init.size(); ++i) {
            const double kx = 2 * kPiD * init.x[i] / L, ky = 2 * kPiD * init.y[i] / L;
            init.vx[i] = Real(-U * std::cos(kx) * std::sin(ky));
            init.vy[i] = Real(U * std::sin(kx) * std::cos(ky));
            const double p = -rho0 * U * U / 4 * (std::cos(2 * kx) + std::cos(2 * ky));
            init.rho[i] = Real(rho0 + p / (c * c));
        }
    });
    TaylorGreenRun run;
    run.resolution = n;
    run.particles = int(sim->particleCount());
    say(o, "Taylor-Green vortex, Re 100, " + std::to_string(n) + " across, " +
               std::to_string(run.particles) + " particles");
    const auto start = std::chrono::steady_clock::now();
    HostParticles p;
    double st = 0, se = 0, stt = 0, ste = 0;
    int used = 0;
    for (int k = 0; k <= 16; ++k) {
        const double t = 0.125 * k;
        if (k > 0) {
            advanceCase(*sim, t, "Taylor-Green vortex");
        }
        sim->download(p);
        double energy = 0;
        for (std::size_t i = 0; i < p.size(); ++i) {
            energy += 0.5 * (double(p.vx[i]) * p.vx[i] + double(p.vy[i]) * p.vy[i] +
                             double(p.vz[i]) * p.vz[i]);
        }
        energy /= double(std::max<std::size_t>(1, p.size()));
        run.t.push_back(t);
        run.energy.push_back(energy);
        if (t >= 0.25 && energy > 0) {
            st += t;
            se += std::log(energy);
            stt += t * t;
            ste += t * std::log(energy);
            ++used;
        }
    }
    run.seconds = seconds(start);
    const double slope = used > 1 ? (used * ste - st * se) / (used * stt - st * st) : 0;
    run.decayRate = slope / 2;
    run.error = std::abs(run.decayRate / decayReference - 1);
    say(o, "  decay rate " + num(run.decayRate) + " against " + num(decayReference) + " (" +
               num(std::round(run.error * 1000) / 10) + "% off) in " +
               num(std::round(run.seconds * 10) / 10) + " s");
    return run;
}

// The vortex over the resolution ladder: the finest rung is held to the tolerance, and the error
// may not grow from one rung to the next.
void runTaylorGreen(const ValidationOptions& o, ValidationReport& r) {
    const double nu = 0.01, L = 1;
    r.tgvDecayReference = -8 * kPiD * kPiD * nu / (L * L);
    for (int n : sortedRungs(o.taylorGreenResolutions)) {
        r.taylorGreen.push_back(runTaylorGreenAt(o, n, r.tgvDecayReference));
    }
    const TaylorGreenRun& finest = r.taylorGreen.back();
    r.checks.push_back({"Taylor-Green vortex, Re 100: |decay rate / -8 pi^2 / Re - 1| (" +
                            std::to_string(finest.resolution) + " across, shifting " +
                            num(o.shifting.value_or(1.0)) + ")",
                        finest.error, kTaylorGreenDecayTolerance, ""});
    std::vector<int> resolutions;
    std::vector<double> errors;
    for (const TaylorGreenRun& run : r.taylorGreen) {
        resolutions.push_back(run.resolution);
        errors.push_back(run.error);
    }
    addLadderChecks(r, "Taylor-Green ladder: decay-rate error", resolutions, errors);
}

std::string modelName(const std::string& model) {
    return model.empty() ? "the scenes' default" : model;
}

}  // namespace

ValidationReport runValidation(const ValidationOptions& options) {
    WEIR_REQUIRE(!options.columnResolutions.empty(),
                 "weir validate: no dam-break resolution given");
    ValidationReport report;
    report.model = modelName(options.model);
    report.solver = options.solver.empty() ? "wcsph" : options.solver;
    // A case whose scene the solver refuses (DFSPH and periodic axes) is reported, and the
    // others still run.
    auto run = [&](bool asked, const char* name,
                   void (*runCase)(const ValidationOptions&, ValidationReport&)) {
        if (!asked) {
            return;
        }
        try {
            runCase(options, report);
        } catch (const SceneError& e) {
            report.notRun.push_back(std::string(name) + ": " + e.what());
        }
    };
    run(options.hydrostatic, "hydrostatic", runTank);
    run(options.damBreak, "dam-break", runLadder);
    run(options.viscous, "viscous", runViscous);
    run(options.channels, "channels", runChannels);
    run(options.lobovsky, "lobovsky", runLobovsky);
    run(options.taylorGreen, "taylor-green", runTaylorGreen);
    return report;
}

double poiseuilleVelocity(double eta, double theta) {
    // u / u_max = 4 eta (1 - eta) - sum_n 32 / (pi^3 (2n+1)^3) sin((2n+1) pi eta) e^{-(2n+1)^2
    // pi^2 theta}
    double u = 4 * eta * (1 - eta);
    for (int k = 0; k < 200; ++k) {
        const double m = 2 * k + 1;
        u -= 32 / (kPiD * kPiD * kPiD * m * m * m) * std::sin(m * kPiD * eta) *
             std::exp(-m * m * kPiD * kPiD * theta);
    }
    return u;
}

double couetteVelocity(double eta, double theta) {
    // u / V0 = eta + sum_n 2 (-1)^n / (n pi) sin(n pi eta) e^{-n^2 pi^2 theta}
    double u = eta;
    for (int k = 1; k <= 2000; ++k) {
        u += 2 * ((k % 2) != 0 ? -1.0 : 1.0) / (k * kPiD) * std::sin(k * kPiD * eta) *
             std::exp(-double(k) * k * kPiD * kPiD * theta);
    }
    return u;
}

namespace {

void writeFronts(const std::filesystem::path& file, const std::vector<FrontRun>& runs) {
    std::ofstream f(file);
    f << "fluid,resolution,particles,T,Z\n";
    for (const FrontRun& run : runs) {
        for (std::size_t i = 0; i < run.T.size(); ++i) {
            f << run.fluid << "," << run.resolution << "," << run.particles << "," << run.T[i]
              << "," << run.Z[i] << "\n";
        }
    }
}

void writeRunsJson(std::ostream& f, const char* name, const std::vector<FrontRun>& runs) {
    f << "  \"" << name << "\": [\n";
    for (std::size_t i = 0; i < runs.size(); ++i) {
        const FrontRun& run = runs[i];
        f << "    {\"fluid\": \"" << run.fluid << "\", \"resolution\": " << run.resolution
          << ", \"particles\": " << run.particles << ", \"seconds\": " << run.seconds
          << ", \"rmsRelative\": " << run.rmsRelative << ", \"maxRelative\": " << run.maxRelative
          << ", \"rmsAbsolute\": " << run.rmsAbsolute
          << ", \"finalZ\": " << (run.Z.empty() ? 0.0 : run.Z.back())
          << ", \"maxDensityDeviation\": " << run.maxDensityDeviation << "}"
          << (i + 1 < runs.size() ? "," : "") << "\n";
    }
    f << "  ],\n";
}

}  // namespace

bool writeValidation(const ValidationReport& r, const std::string& dir, bool plots,
                     std::string* message) {
    namespace fs = std::filesystem;
    fs::create_directories(dir);
    {
        std::ofstream f(fs::path(dir) / "hydrostatic.csv");
        f << "y,pressure,reference,tolerance\n";
        for (std::size_t i = 0; i < r.layerY.size(); ++i) {
            f << r.layerY[i] << "," << r.layerPressure[i] << "," << r.layerReference[i] << ","
              << kLayerPressureTolerance * r.rho0gH << "\n";
        }
    }
    writeFronts(fs::path(dir) / "dam_break.csv", r.ladder);
    writeFronts(fs::path(dir) / "viscous_dam_break.csv", r.viscous);
    {
        std::ofstream f(fs::path(dir) / "lobovsky_front.csv");
        f << "resolution,tau,x_over_H\n";
        for (const LobovskyRun& run : r.lobovsky) {
            for (std::size_t k = 0; k < run.frontTau.size(); ++k) {
                f << run.resolution << "," << run.frontTau[k] << "," << run.frontX[k] << "\n";
            }
        }
        std::ofstream g(fs::path(dir) / "lobovsky_pressure.csv");
        g << "resolution,tau,sensor2,sensor3,sensor4\n";
        for (const LobovskyRun& run : r.lobovsky) {
            for (std::size_t k = 0; k < run.pressureTau.size(); ++k) {
                g << run.resolution << "," << run.pressureTau[k] << "," << run.pressure[k][0] << ","
                  << run.pressure[k][1] << "," << run.pressure[k][2] << "\n";
            }
        }
    }
    {
        std::ofstream f(fs::path(dir) / "taylor_green.csv");
        f << "resolution,t,energy,energy_analytic\n";
        for (const TaylorGreenRun& run : r.taylorGreen) {
            for (std::size_t k = 0; k < run.t.size(); ++k) {
                f << run.resolution << "," << run.t[k] << "," << run.energy[k] << ","
                  << run.energy[0] * std::exp(2 * r.tgvDecayReference * run.t[k]) << "\n";
            }
        }
    }
    {
        std::ofstream f(fs::path(dir) / "channels.csv");
        f << "flow,resolution,theta,eta,u,u_series\n";
        for (const ChannelRun& run : r.channels) {
            for (std::size_t k = 0; k < run.theta.size(); ++k) {
                for (std::size_t l = 0; l < run.eta.size(); ++l) {
                    f << run.flow << "," << run.resolution << "," << run.theta[k] << ","
                      << run.eta[l] << "," << run.u[k][l] << "," << run.uRef[k][l] << "\n";
                }
            }
        }
    }
    {
        std::ofstream f(fs::path(dir) / "martin_moyce_1952.csv");
        f << "# Martin & Moyce 1952, Phil. Trans. R. Soc. A 244, 312-324, Fig. 3, n^2 = 2, "
             "a = 2.25 in; digitized values as distributed with PySPH (db_exp_data.py)\n";
        f << "T,Z,band_low,band_high\n";
        for (const SurgePoint& s : kMartinMoyceSurge) {
            const double band = kFrontMaxRelativeTolerance * s.Z;
            f << s.T << "," << s.Z << "," << s.Z - band << "," << s.Z + band << "\n";
        }
    }
    {
        std::ofstream f(fs::path(dir) / "validation.json");
        f << "{\n  \"passed\": " << (r.passed() ? "true" : "false") << ",\n  \"model\": \""
          << r.model << "\",\n  \"solver\": \"" << r.solver
          << "\",\n  \"tankParticles\": " << r.tankParticles
          << ",\n  \"tankSeconds\": " << r.tankSeconds << ",\n";
        writeRunsJson(f, "damBreakLadder", r.ladder);
        writeRunsJson(f, "viscousDamBreak", r.viscous);
        f << "  \"checks\": [\n";
        for (std::size_t i = 0; i < r.checks.size(); ++i) {
            const ValidationCheck& c = r.checks[i];
            f << "    {\"name\": \"" << c.name << "\", \"value\": " << c.value
              << ", \"tolerance\": " << c.tolerance
              << ", \"passed\": " << (c.passed() ? "true" : "false") << "}"
              << (i + 1 < r.checks.size() ? "," : "") << "\n";
        }
        f << "  ]\n}\n";
    }
    {
        std::ofstream f(fs::path(dir) / "plot.py");
        f << kValidationPlotScript;
    }
    if (!plots) {
        return true;
    }
    const std::string command = "python3 '" + (fs::path(dir) / "plot.py").string() + "' '" + dir +
                                "' > '" + (fs::path(dir) / "plot.log").string() + "' 2>&1";
    if (std::system(command.c_str()) != 0) {
        if (message != nullptr) {
            *message =
                "no plots: python3 with matplotlib is needed (pip install matplotlib; then "
                "python3 " +
                (fs::path(dir) / "plot.py").string() + " " + dir + ")";
        }
        return false;
    }
    return true;
}

}  // namespace weir
