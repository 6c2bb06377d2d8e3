// The validation cases of `weir validate`: hydrostatic tank and Martin & Moyce dam break.
#include "validate/validation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

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

std::string num(double v) {
    std::ostringstream s;
    s.precision(10);
    s << v;
    return s.str();
}

double seconds(std::chrono::steady_clock::time_point since) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

// A tank of water depth H, width H and a slab 6 d deep, walls of boundary particles.
void runTank(const ValidationOptions& o, ValidationReport& r) {
    const double H = 0.3, d = H / o.tankResolution, W = 6 * d;
    const std::string json = R"({"name": "validate_hydrostatic",
        "container": {"min": [0, 0, 0], "max": [)" +
                             num(H) + ", " + num(1.5 * H) + ", " + num(W) +
                             R"(]},
        "blocks": [{"min": [0, 0, 0], "max": [)" +
                             num(H) + ", " + num(H) + ", " + num(W) + R"(]}],
        "fluid": {"preset": "water", "restDensity": 1000},
        "particles": {"spacing": )" +
                             num(d) + R"(},
        "walls": {"model": "particles"},
        "time": {"duration": )" +
                             num(o.settleTime) + R"(, "frameRate": 10}})";
    Scene scene = parseScene(json, "<validate hydrostatic>");
    SetupReport setupReport;
    SimulationSetup setup = buildSetup(scene, {}, &setupReport);
    const double h = setupReport.smoothingRadius;
    auto sim = makeSimulation(o.backend, NeighbourMode::Auto, std::move(setup));
    r.tankParticles = int(sim->particleCount());
    r.tankDepth = H;
    r.rho0gH = 1000.0 * kG * H;
    const auto start = std::chrono::steady_clock::now();

    // Layers d thick; the interior lies h from the walls and the floor (the boundary particles'
    // reach) and 2 h below the surface (its particles lack neighbours and read light).
    const int layers = int(std::floor(H / d));
    std::vector<double> sum(layers, 0.0);
    std::vector<long> count(layers, 0);
    DensityDeviation worst;
    double straySquares = 0, strayMax = 0;
    long strayCount = 0;
    HostParticles p;
    const int averaged = 9;  // frames over the last 40% of the run, every 5%
    for (int k = 0; k < averaged; ++k) {
        sim->advanceTo(o.settleTime * (0.6 + 0.05 * k));
        if (sim->fault().code != 0) {
            throw SimulationError("hydrostatic tank: " +
                                  describeFault(sim->fault(), sim->params()));
        }
        sim->download(p);
        const DensityDeviation dev = densityDeviation(p, 1000.0);
        worst.max = std::max(worst.max, dev.max);
        worst.mean = std::max(worst.mean, dev.mean);
        for (std::size_t i = 0; i < p.size(); ++i) {
            const double v2 =
                double(p.vx[i]) * p.vx[i] + double(p.vy[i]) * p.vy[i] + double(p.vz[i]) * p.vz[i];
            if (k == averaged - 1) {
                straySquares += v2;
                strayMax = std::max(strayMax, std::sqrt(v2));
                ++strayCount;
            }
            const double x = p.x[i], y = p.y[i], z = p.z[i];
            if (x < h || x > H - h || z < h || z > W - h) {
                continue;
            }
            const int layer = int(y / d);
            if (layer >= 0 && layer < layers) {
                sum[layer] += p.p[i];
                ++count[layer];
            }
        }
    }
    r.tankSeconds = seconds(start);
    double squares = 0;
    int used = 0;
    for (int l = 0; l < layers; ++l) {
        const double y = (l + 0.5) * d;
        if (count[l] == 0 || y < h || y > H - 2 * h) {
            continue;
        }
        const double mean = sum[l] / double(count[l]), reference = 1000.0 * kG * (H - y);
        r.layerY.push_back(y);
        r.layerPressure.push_back(mean);
        r.layerReference.push_back(reference);
        squares += (mean - reference) * (mean - reference);
        ++used;
    }
    const double pressureError = used > 0 ? std::sqrt(squares / used) / r.rho0gH : 1e30;
    const double freeFall = std::sqrt(2 * kG * H);
    r.checks.push_back(
        {"hydrostatic: pressure error (RMS of interior layer means vs rho0 g depth, "
         "/ rho0 g H)",
         pressureError, kHydrostaticPressureTolerance, ""});
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

// Martin & Moyce's column (width a, height n^2 a) in a slab 4 d deep with free-slip walls.
void runDamBreak(const ValidationOptions& o, ValidationReport& r) {
    const double a = kMartinMoyceWidth, d = a / o.columnResolution;
    const double height = kMartinMoyceHeightRatio * a, depth = 4 * d;
    const double timeScale = std::sqrt(2 * kG / a);  // T = t sqrt(2 g / a)
    const double endTime = o.damEndT / timeScale;
    const double length = a * (1.5 + 1.4 * o.damEndT);  // past the front at the end
    const double frameRate = timeScale / 0.25;          // a frame every 0.25 in T
    const std::string json = R"({"name": "validate_martin_moyce",
        "container": {"min": [0, 0, 0], "max": [)" +
                             num(length) + ", " + num(1.5 * height) + ", " + num(depth) + R"(]},
        "blocks": [{"min": [0, 0, 0], "max": [)" +
                             num(a) + ", " + num(height) + ", " + num(depth) +
                             R"(]}],
        "fluid": {"preset": "water", "restDensity": 1000},
        "particles": {"spacing": )" +
                             num(d) + R"(},
        "walls": {"model": "particles"},
        "time": {"duration": )" +
                             num(endTime) + R"(, "frameRate": )" + num(frameRate) + "}}";
    Scene scene = parseScene(json, "<validate dam break>");
    SetupReport setupReport;
    SimulationSetup setup = buildSetup(scene, {}, &setupReport);
    auto sim = makeSimulation(o.backend, NeighbourMode::Auto, std::move(setup));
    r.columnParticles = int(sim->particleCount());
    const auto start = std::chrono::steady_clock::now();
    HostParticles p;
    DensityDeviation worst;
    for (std::int64_t k = 1; k <= setupReport.frames; ++k) {
        const double t = double(k) / frameRate;
        sim->advanceTo(t);
        if (sim->fault().code != 0) {
            throw SimulationError("dam break: " + describeFault(sim->fault(), sim->params()));
        }
        sim->download(p);
        // The leading edge: the furthest particle, plus half a spacing (its share of the front).
        double front = 0;
        for (std::size_t i = 0; i < p.size(); ++i) {
            front = std::max(front, double(p.x[i]));
        }
        r.simT.push_back(t * timeScale);
        r.simZ.push_back((front + 0.5 * d) / a);
        const DensityDeviation dev = densityDeviation(p, 1000.0);
        worst.max = std::max(worst.max, dev.max);
        worst.mean = std::max(worst.mean, dev.mean);
    }
    r.damSeconds = seconds(start);
    // Simulated Z at the measured T, linearly interpolated; T = 0 is Z = 1.
    double squares = 0;
    int used = 0;
    for (const SurgePoint& ref : kMartinMoyceSurge) {
        if (ref.T > r.simT.back()) {
            break;
        }
        double prevT = 0, prevZ = 1;
        for (std::size_t k = 0; k < r.simT.size(); ++k) {
            if (r.simT[k] >= ref.T) {
                const double w = (ref.T - prevT) / (r.simT[k] - prevT);
                const double z = prevZ + w * (r.simZ[k] - prevZ);
                squares += (z - ref.Z) * (z - ref.Z);
                ++used;
                break;
            }
            prevT = r.simT[k];
            prevZ = r.simZ[k];
        }
    }
    r.frontRms = used > 0 ? std::sqrt(squares / used) : 1e30;
    r.checks.push_back({"dam break: surge front RMS error in Z = z / a vs Martin & Moyce (" +
                            std::to_string(used) + " points)",
                        r.frontRms, kFrontRmsTolerance, ""});
    r.checks.push_back({"dam break: max density deviation during the surge", worst.max,
                        kDensityDeviationTolerance, ""});
}

}  // namespace

ValidationReport runValidation(const ValidationOptions& options) {
    ValidationReport report;
    runTank(options, report);
    runDamBreak(options, report);
    return report;
}

bool writeValidation(const ValidationReport& r, const std::string& dir, bool plots,
                     std::string* message) {
    namespace fs = std::filesystem;
    fs::create_directories(dir);
    {
        std::ofstream f(fs::path(dir) / "hydrostatic.csv");
        f << "y,pressure,reference,tolerance\n";
        for (std::size_t i = 0; i < r.layerY.size(); ++i) {
            f << r.layerY[i] << "," << r.layerPressure[i] << "," << r.layerReference[i] << ","
              << kHydrostaticPressureTolerance * r.rho0gH << "\n";
        }
    }
    {
        std::ofstream f(fs::path(dir) / "dam_break.csv");
        f << "T,Z\n";
        for (std::size_t i = 0; i < r.simT.size(); ++i) {
            f << r.simT[i] << "," << r.simZ[i] << "\n";
        }
    }
    {
        std::ofstream f(fs::path(dir) / "martin_moyce_1952.csv");
        f << "# Martin & Moyce 1952, Phil. Trans. R. Soc. A 244, 312-324, Fig. 3, n^2 = 2, "
             "a = 2.25 in; digitized values as distributed with PySPH (db_exp_data.py)\n";
        f << "T,Z,band_low,band_high\n";
        for (const SurgePoint& s : kMartinMoyceSurge) {
            const double band = kFrontBandRelative * s.Z + kFrontBandAbsolute;
            f << s.T << "," << s.Z << "," << s.Z - band << "," << s.Z + band << "\n";
        }
    }
    {
        std::ofstream f(fs::path(dir) / "validation.json");
        f << "{\n  \"passed\": " << (r.passed() ? "true" : "false")
          << ",\n  \"tankParticles\": " << r.tankParticles
          << ",\n  \"columnParticles\": " << r.columnParticles
          << ",\n  \"tankSeconds\": " << r.tankSeconds << ",\n  \"damSeconds\": " << r.damSeconds
          << ",\n  \"checks\": [\n";
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
