// `weir bench`: the paper's Tables 1-3 (per-stage times of CPU, GPU and optimized GPU) on this
// machine, at any particle counts, as terminal tables, CSV, JSON and a plot.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "cli/commands.h"
#include "cli/count_option.h"
#include "core/check.h"
#include "core/exec_cpu.h"
#include "grid/cell_id.h"
#include "grid/dense_grid.h"
#include "io/atomic_file.h"
#include "scene/scene.h"
#include "scene/setup.h"
#include "solver/simulation.h"

namespace weir {

namespace {

struct Column {
    std::string name;   // cpu-brute, cpu-grid, cuda-brute, cuda-grid
    std::string title;  // as in the paper's tables
    Backend backend;
    NeighbourMode mode;
};

const std::vector<Column>& allColumns() {
    static const std::vector<Column> columns = {
        {"cpu-brute", "CPU", Backend::Cpu, NeighbourMode::Brute},
        {"cpu-grid", "CPU grid", Backend::Cpu, NeighbourMode::Grid},
        {"cpu-dense", "CPU dense", Backend::Cpu, NeighbourMode::Dense},
        {"cuda-brute", "GPU", Backend::Cuda, NeighbourMode::Brute},
        {"cuda-grid", "Optimized GPU", Backend::Cuda, NeighbourMode::Grid},
        {"cuda-dense", "weir GPU", Backend::Cuda, NeighbourMode::Dense},
    };
    return columns;
}

// Stages in the paper's row order, with the paper's names.
const std::vector<std::pair<std::string, std::string>> kStageRows = {
    {"grid", "Grid construction"},
    {"density", "Pressure computation"},
    {"force", "Force computation"},
    {"integrate", "Displacement computation"},
};

// The stages some column of a run timed besides the paper's four (a method's own: DFSPH's
// neighbour list and solves, the walls' state), in name order.
std::vector<std::string> extraStages(const nlohmann::json& run) {
    std::set<std::string> names;
    for (const auto& [column, r] : run["columns"].items()) {
        if (!r.contains("stages")) {
            continue;
        }
        for (const auto& [stage, ms] : r["stages"].items()) {
            if (std::none_of(kStageRows.begin(), kStageRows.end(),
                             [&](const auto& row) { return row.first == stage; })) {
                names.insert(stage);
            }
        }
    }
    return {names.begin(), names.end()};
}

// Mean neighbours per particle of a run's record; NaN where not counted.
double neighboursOf(const nlohmann::json& run) {
    const nlohmann::json& v = run["neighboursPerParticle"];
    return v.is_number() ? v.get<double>() : std::nan("");
}

// From this many particles on, bench runs start from the lattice, seeded on each backend.
constexpr std::int64_t kLatticeStartFrom = 20000000;

// Mean number of neighbours within h (the particle itself excluded), on the host.
double neighboursPerParticle(const HostParticles& p, const GridSpec& spec, Real h) {
    const Index n = Index(p.size());
    std::vector<Real4> unsorted(n), pos(n);
    for (Index i = 0; i < n; ++i) {
        unsorted[i] = {p.x[i], p.y[i], p.z[i], 0};
    }
    CpuExec exec;
    DenseGrid<CpuExec> grid(spec, 1);
    grid.build(exec, unsorted.data(), n);
    for (Index i = 0; i < n; ++i) {
        pos[i] = unsorted[grid.permutation()[i]];
    }
    DenseGridNeighbours view = grid.view(pos.data(), h);
    double total = 0;
#pragma omp parallel for reduction(+ : total)
    for (Index i = 0; i < n; ++i) {
        long count = 0;
        view.forEachCandidate(i, [&](Index j) {
            count += (j != i && lengthSquared(pos[i].xyz() - pos[j].xyz()) < h * h) ? 1 : 0;
        });
        total += double(count);
    }
    return n > 0 ? total / n : 0.0;
}

std::string nowUtc() {
    std::time_t t = std::time(nullptr);
    char buf[32];
    std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
    return buf;
}

std::string fixed(double v, int digits) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", digits, v);
    return buf;
}

}  // namespace

// Particle counts as users write them: 10000, 50k, 1M, 1B.
std::vector<std::string> splitList(const std::string& text) {
    std::vector<std::string> items;
    std::stringstream in(text);
    for (std::string item; std::getline(in, item, ',');) {
        if (!item.empty()) {
            items.push_back(item);
        }
    }
    return items;
}

int benchCommand(const BenchOptions& options, SpriteDrawTimer* spriteTimer) {
    if (options.scaling) {
        return scalingBenchCommand(options);
    }
    try {
        // The paper's tables time the paper's system: its model, whatever the scene asks for
        // (--model delta-sph times the default one).
        Scene scene = withFluidModel(resolveScene(options.scene), options.model);
        if (!options.solver.empty()) {
            scene = withSolver(scene, options.solver);
        }
        const std::string solver = scene.solver.empty() ? "wcsph" : scene.solver;
        std::vector<std::int64_t> sizes;
        for (const std::string& s : splitList(options.sizes)) {
            sizes.push_back(parseCount(s, "--sizes", 1, kMaxParticles, kParticleLimitText));
        }
        const bool gpu = cudaDeviceAvailable();
        std::vector<Column> columns;
        std::vector<std::string> wanted = splitList(options.columns);
        for (const Column& c : allColumns()) {
            bool asked = options.columns == "auto"
                             ? (c.backend == Backend::Cpu || gpu)
                             : std::find(wanted.begin(), wanted.end(), c.name) != wanted.end();
            if (asked) {
                columns.push_back(c);
            }
        }
        for (const std::string& w : wanted) {
            if (w != "auto" && std::none_of(allColumns().begin(), allColumns().end(),
                                            [&](const Column& c) { return c.name == w; })) {
                throw std::invalid_argument("--backends: unknown bench column '" + w +
                                            "': allowed are cpu-brute, cpu-grid, cpu-dense, "
                                            "cuda-brute, cuda-grid, cuda-dense, auto");
            }
        }
        if (columns.empty()) {
            throw std::invalid_argument("no benchmark column to run (no GPU for cuda columns?)");
        }

        nlohmann::json record;
        record["tool"] = "weir bench";
        record["version"] = WEIR_VERSION;
        record["commit"] = WEIR_COMMIT;
        record["date"] = nowUtc();
        record["scene"] = scene.name;
        record["model"] = options.model;
        record["solver"] = solver;
        record["cpu"] = describeBackend(Backend::Cpu);
        record["gpu"] = gpu ? describeBackend(Backend::Cuda) : "none";
        record["precision"] = sizeof(Real) == 8 ? "double" : "float";
        record["steps"] = options.steps;
        record["warmupSteps"] = options.warmup;
        record["settleSeconds"] = options.settle;
        record["runs"] = nlohmann::json::array();
        std::map<std::string, std::pair<double, double>> lastBrute;  // column -> (n, ms/step)

        std::cerr << "weir bench: " << scene.name << ", fluid model " << options.model
                  << ", solver " << solver << ", columns";
        for (const Column& c : columns) {
            std::cerr << " " << c.name;
        }
        std::cerr << "; " << options.steps << " timed steps after " << options.warmup
                  << " warm-up steps, from a fluid settled for " << options.settle << " s\n";

        for (std::int64_t size : sizes) {
            // Past kLatticeStartFrom particles, each column seeds its particles itself (on the
            // GPU for CUDA) and starts from the lattice: settling would take too long, and the
            // host would hold gigabytes of particles for nothing.
            const bool fromLattice = size >= kLatticeStartFrom;
            SetupOptions setupOptions;
            setupOptions.particleCount = size;
            setupOptions.seedOnDevice = fromLattice;
            SetupReport report;
            SimulationSetup setup = buildSetup(scene, setupOptions, &report);
            const Index n = Index(setup.particleCount());
            // A fluid in motion: advance on the fastest backend, then start every column there.
            if (!fromLattice) {
                auto mover =
                    makeSimulation(gpu ? Backend::Cuda : Backend::Cpu, NeighbourMode::Auto, setup);
                int settleSteps = int(std::lround(options.settle / setup.params.timeStep));
                mover->advance(settleSteps);
                FaultRecord fault = mover->fault();
                if (fault.code != 0) {
                    throw SimulationError(describeFault(fault, mover->params()));
                }
                mover->download(setup.particles);
            } else {
                std::cerr << "  " << n << " particles: seeded by each column on its backend, "
                          << "timed from the initial lattice (no settling past "
                          << kLatticeStartFrom << " particles)\n";
            }
            const double neighbours =
                fromLattice
                    ? std::nan("")
                    : neighboursPerParticle(setup.particles, setup.grid, setup.params.kernel.h);
            nlohmann::json run;
            run["requested"] = size;
            run["particles"] = n;
            run["spacing"] = report.spacing;
            run["smoothingRadius"] = report.smoothingRadius;
            run["smoothingRatio"] = scene.smoothingRatio;
            run["timeStep"] = setup.params.timeStep;
            run["stiffness"] = setup.params.stiffness;
            run["viscosity"] = setup.params.viscosity;
            run["mass"] = setup.params.mass;
            run["neighboursPerParticle"] =
                std::isnan(neighbours) ? nlohmann::json() : nlohmann::json(neighbours);
            run["settled"] = !fromLattice;
            run["gridCells"] = {setup.grid.dims[0], setup.grid.dims[1], setup.grid.dims[2]};
            // The width of the grid columns' cell ids: 64 past 1024 cells on some axis.
            run["cellIdBits"] = needsWideCellIds(setup.grid) ? 64 : 32;
            run["columns"] = nlohmann::json::object();
            // The paper's fifth row: the fluid drawn as point sprites (the same for every column).
            if (spriteTimer != nullptr && !fromLattice) {
                const double ms =
                    spriteTimer->medianDrawMs(scene, setup.particles, 0.5 * report.spacing);
                run["pointSpriteMs"] = ms;
                std::cerr << "  " << n << " point sprites: " << fixed(ms, 4)
                          << " ms per frame (1280x720, " << spriteTimer->description() << ")\n";
            }

            for (const Column& column : columns) {
                nlohmann::json result;
                result["title"] = column.title;
                auto skip = [&](const std::string& why) {
                    result["skipped"] = why;
                    std::cerr << "  " << n << " " << column.name << ": skipped, " << why << "\n";
                };
                const int totalSteps = options.warmup + options.steps;
                auto it = lastBrute.find(column.name);
                if (column.mode == NeighbourMode::Brute && it != lastBrute.end()) {
                    double scale = double(n) / it->second.first;
                    double estimate = it->second.second * scale * scale * totalSteps / 1000.0;
                    if (estimate > options.budget) {
                        skip("estimated " + fixed(estimate, 0) + " s > budget " +
                             fixed(options.budget, 0) + " s (O(N^2))");
                        run["columns"][column.name] = result;
                        continue;
                    }
                }
                std::unique_ptr<Simulation> sim;
                try {
                    sim = makeSimulation(column.backend, column.mode, setup);
                } catch (const SimulationError& e) {
                    skip(e.what());
                    run["columns"][column.name] = result;
                    continue;
                }
                auto start = std::chrono::steady_clock::now();
                sim->advance(1);
                sim->synchronize();
                double firstMs = std::chrono::duration<double, std::milli>(
                                     std::chrono::steady_clock::now() - start)
                                     .count();
                if (firstMs * totalSteps / 1000.0 > options.budget) {
                    skip("one step took " + fixed(firstMs / 1000, 1) + " s, " +
                         std::to_string(totalSteps) + " steps exceed the budget of " +
                         fixed(options.budget, 0) + " s");
                    if (column.mode == NeighbourMode::Brute) {
                        lastBrute[column.name] = {double(n), firstMs};
                    }
                    run["columns"][column.name] = result;
                    continue;
                }
                sim->advance(options.warmup);
                sim->synchronize();
                sim->setTiming(true);
                sim->clearStageTimes();
                sim->takeSolverReport();  // the timed steps' sweeps alone, from here
                sim->advance(options.steps);
                sim->synchronize();
                const StageTimes& times = sim->stageTimes();
                double total = 0;
                for (const auto& [stage, title] : kStageRows) {
                    double ms = times.median(stage);
                    result["stages"][stage] = ms;
                    total += ms;
                }
                // A method's own stages (DFSPH's neighbour list and solves, the walls' state).
                for (const auto& [stage, samples] : times.samples()) {
                    if (!result["stages"].contains(stage)) {
                        const double ms = times.median(stage);
                        result["stages"][stage] = ms;
                        total += ms;
                    }
                }
                result["totalMs"] = total;
                // The full step as users run it: no per-stage events, and on the GPU a replayed
                // CUDA graph where the cell table allows; median over repeated blocks of steps.
                if (column.mode != NeighbourMode::Brute) {
                    sim->setTiming(false);
                    std::vector<double> perStep;
                    double wallSeconds = 0;
                    const double simulatedFrom = sim->time();
                    for (int rep = 0; rep < 7; ++rep) {
                        sim->synchronize();
                        auto t0 = std::chrono::steady_clock::now();
                        sim->advance(options.steps);
                        sim->synchronize();
                        const double ms = std::chrono::duration<double, std::milli>(
                                              std::chrono::steady_clock::now() - t0)
                                              .count();
                        wallSeconds += ms / 1000;
                        perStep.push_back(ms / options.steps);
                    }
                    std::sort(perStep.begin(), perStep.end());
                    result["stepMs"] = perStep[perStep.size() / 2];
                    // Time to solution: what users wait for, whatever the step (a solver with
                    // fewer, costlier steps compares fairly). Over the timed blocks' steps.
                    const double simulated = sim->time() - simulatedFrom;
                    if (simulated > 0) {
                        result["simulatedSeconds"] = simulated;
                        result["wallSecondsPerSimulatedSecond"] = wallSeconds / simulated;
                    }
                }
                // An iterative solver's sweeps over every timed step (DFSPH): what a step's time
                // is made of, and how hard the flow is for the solves at this size.
                const SolverReport solves = sim->takeSolverReport();
                if (solves.iterative && solves.density.solves > 0) {
                    auto perStep = [](const SolveReport& r) {
                        return r.solves > 0 ? double(r.iterations) / r.solves : 0.0;
                    };
                    result["densitySweepsPerStep"] = perStep(solves.density);
                    result["densitySweepsMax"] = solves.density.maxIterations;
                    result["divergenceSweepsPerStep"] = perStep(solves.divergence);
                    result["divergenceSweepsMax"] = solves.divergence.maxIterations;
                    result["solvesAtSweepLimit"] =
                        solves.density.unconverged + solves.divergence.unconverged;
                }
                // Throughput; on the CPU also per core, to show how the backend scales.
                const double stepMs = result.value("stepMs", total);
                result["particleStepsPerSecond"] = double(n) * 1000.0 / stepMs;
                if (column.backend == Backend::Cpu) {
                    result["threads"] = omp_get_max_threads();
                    result["particleStepsPerSecondPerCore"] =
                        result["particleStepsPerSecond"].get<double>() / omp_get_max_threads();
                }
                result["bytesPerParticle"] = double(sim->bytesHeld()) / double(n);
                result["occupiedCells"] = sim->occupiedCells();
                result["device"] = sim->deviceName();
                if (sim->fault().code != 0) {
                    result["fault"] = describeFault(sim->fault(), sim->params());
                }
                if (column.mode == NeighbourMode::Brute) {
                    lastBrute[column.name] = {double(n), total};
                }
                std::cerr << "  " << n << " " << column.name << ": " << fixed(total, 4)
                          << " ms/step (sum of stage medians)";
                if (result.contains("stepMs")) {
                    std::cerr << ", " << fixed(result["stepMs"].get<double>(), 4)
                              << " ms/step (full step, median)";
                }
                if (result.contains("wallSecondsPerSimulatedSecond")) {
                    std::cerr << ", "
                              << fixed(result["wallSecondsPerSimulatedSecond"].get<double>(), 3)
                              << " s per simulated second";
                }
                std::cerr << ", " << fixed(result["bytesPerParticle"].get<double>(), 1)
                          << " bytes/particle, "
                          << fixed(result["particleStepsPerSecond"].get<double>() / 1e6, 2)
                          << " M particle-steps/s";
                if (result.contains("particleStepsPerSecondPerCore")) {
                    std::cerr << " ("
                              << fixed(result["particleStepsPerSecondPerCore"].get<double>() / 1e6,
                                       3)
                              << " M per core, " << result["threads"].get<int>() << " threads)";
                }
                if (result.contains("densitySweepsPerStep")) {
                    std::cerr << ", density solve "
                              << fixed(result["densitySweepsPerStep"].get<double>(), 2)
                              << " sweeps a step (max " << result["densitySweepsMax"].get<int>()
                              << "), divergence "
                              << fixed(result["divergenceSweepsPerStep"].get<double>(), 2)
                              << " (max " << result["divergenceSweepsMax"].get<int>() << ")";
                }
                std::cerr << "\n";
                run["columns"][column.name] = result;
            }
            record["runs"].push_back(run);
        }

        // Terminal tables in the paper's layout.
        const std::string baseline = "cpu-brute";
        for (const auto& run : record["runs"]) {
            const double neighbours = neighboursOf(run);
            std::printf(
                "\nTable: computation time and speedup for %lld particles (time in ms, %s)\n",
                (long long)run["particles"].get<std::int64_t>(),
                std::isnan(neighbours)
                    ? "from the initial lattice"
                    : (fixed(neighbours, 1) + " neighbours per particle").c_str());
            std::printf("%-26s", "Operations");
            for (const Column& c : columns) {
                std::printf("%16s", c.title.c_str());
            }
            std::printf("\n");
            auto cell = [&](const Column& c, const std::string& stage) -> std::string {
                const auto& r = run["columns"][c.name];
                if (r.contains("skipped")) {
                    return "skipped";
                }
                return fixed(
                    stage.empty() ? r["totalMs"].get<double>() : r["stages"][stage].get<double>(),
                    4);
            };
            for (const auto& [stage, title] : kStageRows) {
                std::printf("%-26s", title.c_str());
                for (const Column& c : columns) {
                    std::printf("%16s", cell(c, stage).c_str());
                }
                std::printf("\n");
            }
            for (const std::string& stage : extraStages(run)) {
                static const std::map<std::string, std::string> kTitles = {
                    {"neighbour list", "Neighbour list"},
                    {"divergence", "Divergence-free solve"},
                    {"pressure", "Constant-density solve"},
                    {"walls", "Wall state"}};
                const auto title = kTitles.find(stage);
                std::printf("%-26s",
                            title != kTitles.end() ? title->second.c_str() : stage.c_str());
                for (const Column& c : columns) {
                    const auto& r = run["columns"][c.name];
                    const bool has = r.contains("stages") && r["stages"].contains(stage);
                    std::printf("%16s",
                                has ? fixed(r["stages"][stage].get<double>(), 4).c_str() : "-");
                }
                std::printf("\n");
            }
            if (run.contains("pointSpriteMs")) {
                std::printf("%-26s", "Point sprite rendering");
                for (std::size_t c = 0; c < columns.size(); ++c) {
                    std::printf("%16s", fixed(run["pointSpriteMs"].get<double>(), 4).c_str());
                }
                std::printf("\n");
            }
            std::printf("%-26s", "Total time (step)");
            for (const Column& c : columns) {
                std::printf("%16s", cell(c, "").c_str());
            }
            std::printf("\n%-26s", "Full step (no events)");
            for (const Column& c : columns) {
                const auto& r = run["columns"][c.name];
                std::printf("%16s", r.contains("stepMs")
                                        ? fixed(r["stepMs"].get<double>(), 4).c_str()
                                        : "-");
            }
            std::printf("\n%-26s", "Wall s per simulated s");
            for (const Column& c : columns) {
                const auto& r = run["columns"][c.name];
                std::printf("%16s",
                            r.contains("wallSecondsPerSimulatedSecond")
                                ? fixed(r["wallSecondsPerSimulatedSecond"].get<double>(), 3).c_str()
                                : "-");
            }
            std::printf("\n%-26s", "Speedup over CPU");
            const auto& base = run["columns"].value(baseline, nlohmann::json::object());
            for (const Column& c : columns) {
                const auto& r = run["columns"][c.name];
                if (base.contains("totalMs") && r.contains("totalMs")) {
                    std::printf("%16s",
                                fixed(base["totalMs"].get<double>() / r["totalMs"].get<double>(), 2)
                                    .c_str());
                } else {
                    std::printf("%16s", "-");
                }
            }
            std::printf("\n");
        }

        std::filesystem::create_directories(options.outDir);
        const std::string jsonPath = options.outDir + "/bench.json";
        const std::string csvPath = options.outDir + "/bench.csv";
        writeFileAtomically(jsonPath, [&](std::ostream& out) { out << record.dump(2) << "\n"; });
        writeFileAtomically(csvPath, [&](std::ostream& out) {
            out << "particles,neighbours_per_particle,column,stage,ms,skipped\n";
            for (const auto& run : record["runs"]) {
                for (const auto& [name, r] : run["columns"].items()) {
                    auto row = [&](const std::string& stage, double ms) {
                        out << run["particles"].get<std::int64_t>() << "," << neighboursOf(run)
                            << "," << name << "," << stage << "," << ms << ","
                            << (r.contains("skipped") ? 1 : 0) << "\n";
                    };
                    if (r.contains("skipped")) {
                        row("total", 0);
                        continue;
                    }
                    for (const auto& [stage, ms] : r["stages"].items()) {
                        row(stage, ms.get<double>());
                    }
                    row("total", r["totalMs"].get<double>());
                }
            }
        });
        std::cerr << "weir bench: wrote " << jsonPath << " and " << csvPath << "\n";
        if (!options.noPlot) {
            const std::string script = std::string(WEIR_SOURCE_DIR_PATH) + "/bench/plot.py";
            const std::string command = "python3 '" + script + "' '" + jsonPath + "' '" +
                                        options.outDir + "/bench.png' 2>&1";
            if (std::filesystem::exists(script) && std::system(command.c_str()) == 0) {
                std::cerr << "weir bench: wrote " << options.outDir << "/bench.png\n";
            } else {
                std::cerr << "weir bench: no plot (needs python3 with matplotlib: "
                             "pip install matplotlib; then python3 bench/plot.py "
                          << jsonPath << " out.png)\n";
            }
        }
        return kExitOk;
    } catch (...) {
        return reportCaughtError();
    }
}

}  // namespace weir
