// `weir run`: scene in, particle frames out, with progress, logs and blow-up detection.
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli/commands.h"
#include "cli/progress.h"
#include "cli/run_folder.h"
#include "cluster/distributed_simulation.h"
#include "core/check.h"
#include "grid/cell_id.h"
#include "io/frame_index.h"
#include "io/frame_writer.h"
#include "scene/scene.h"
#include "scene/setup.h"
#include "solver/density_deviation.h"

namespace weir {

namespace {

std::ostream& nullStream() {
    static std::ostream sink(nullptr);  // no buffer: writes are dropped
    return sink;
}

// The frame format's hint with its placeholders filled: "out/dam_break/frame.pvd in ParaView ...".
std::string howToOpen(FrameFormat format, const std::string& outDir) {
    std::string hint = format.entry().openHint;
    const std::string base = (std::filesystem::path(outDir) / "frame").string();
    const std::size_t at = hint.find("BASE");
    if (at != std::string::npos) {
        hint.replace(at, 4, base);
    }
    return hint;
}

// The largest particle speed of a frame, m/s.
double maxSpeedOf(const HostParticles& p) {
    double fastest2 = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        fastest2 = std::max(fastest2, double(p.vx[i]) * p.vx[i] + double(p.vy[i]) * p.vy[i] +
                                          double(p.vz[i]) * p.vz[i]);
    }
    return std::sqrt(fastest2);
}

// A frame's iterations of an iterative solver, for the progress line: "; 55 steps (dt 0.61 ms,
// max speed 3.1 m/s), density solve 4.2 sweeps a step (max 9), divergence 1.3"; nothing for
// WCSPH. frameInterval: the frame's simulated time; frame: its particles (for the fastest).
std::string solverNote(const SolverReport& report, double frameInterval,
                       const HostParticles& frame) {
    if (!report.iterative || report.density.solves == 0) {
        return "";
    }
    auto mean = [](const SolveReport& r) {
        return rounded(r.solves > 0 ? double(r.iterations) / r.solves : 0.0, 2);
    };
    std::ostringstream note;
    // Each step runs one density solve: its count is the frame's steps. The time step follows
    // the fastest particle (CFL), so a few fast ones show here first.
    note << "; " << report.density.solves << " steps (dt "
         << rounded(1000 * frameInterval / report.density.solves, 2) << " ms, max speed "
         << rounded(maxSpeedOf(frame), 2) << " m/s)";
    note << ", density solve " << mean(report.density) << " sweeps a step (max "
         << report.density.maxIterations << ")";
    if (report.divergence.solves > 0) {
        note << ", divergence " << mean(report.divergence) << " (max "
             << report.divergence.maxIterations << ")";
    }
    const int unconverged = report.density.unconverged + report.divergence.unconverged;
    if (unconverged > 0) {
        note << ", " << unconverged << " solves at the sweep limit";
    }
    return note.str();
}

}  // namespace

int runCommand(const RunOptions& options, RunObserver* observer) {
    std::unique_ptr<Communicator> comm = worldCommunicator();
    const bool root = comm->rank() == 0;
    // Only rank 0 talks (and writes); the others' errors still name them.
    std::ostream& log = root ? std::cerr : nullStream();
    try {
        Scene scene = resolveScene(options.scene);
        if (!options.model.empty()) {
            scene = withFluidModel(scene, options.model);
        }
        if (!options.solver.empty()) {
            scene = withSolver(scene, options.solver);
        }
        SetupOptions setupOptions;
        setupOptions.particleCount = options.particles;
        // Distributed: each rank seeds only its slab, on its backend (no rank holds them all).
        setupOptions.seedOnDevice = launchedByMpi();
        const Backend backend = parseBackend(options.backend);
        setupOptions.backend = backend;  // a CPU run's particles must fit host memory twice over
        if (backend == Backend::Cuda && !setupOptions.seedOnDevice && cudaDeviceAvailable()) {
            setupOptions.deviceFreeBytes = cudaFreeMemoryBytes();  // checked before seeding
        }
        SetupReport report;
        SimulationSetup setup = buildSetup(scene, setupOptions, &report);
        const NeighbourMode mode = resolveNeighbourMode(parseNeighbourMode(options.neighbours),
                                                        setup.grid, setup.particleCount());
        const FrameFormat format = parseFrameFormat(options.format);
        const std::string outDir = options.outDir.empty() ? "out/" + scene.name : options.outDir;
        const std::int64_t frames =
            options.frames ? std::min(*options.frames, report.frames) : report.frames;

        log << "weir: scene " << scene.name << " (" << scene.sourcePath << "), fluid model "
            << (scene.model == FluidModelName::DeltaSph ? "delta-sph" : "paper") << "\n";
        if (root) {
            prepareRunFolder(outDir, options.overwrite, log);
        }
        if (options.explain) {
            for (const std::string& line : report.lines) {
                log << "  " << line << "\n";
            }
        }
        for (const std::string& warning : report.warnings) {
            log << "weir: warning: " << warning << "\n";
        }
        if (!root) {
            observer = nullptr;
        }
        if (observer != nullptr) {
            observer->start(scene, report, outDir);
        }
        const bool wideCellIds = mode == NeighbourMode::Grid && needsWideCellIds(setup.grid);
        const std::string cellIds = cellIdDescription(setup.grid);
        std::unique_ptr<Simulation> sim;
        DistributedSimulation* cluster = nullptr;
        if (launchedByMpi()) {
            auto distributed =
                std::make_unique<DistributedSimulation>(*comm, backend, mode, std::move(setup));
            cluster = distributed.get();
            sim = std::move(distributed);
        } else {
            sim = makeSimulation(backend, mode, std::move(setup));
        }
        log << "weir: " << sim->particleCount() << " particles on " << backendName(backend) << " ("
            << sim->deviceName() << "), " << neighbourModeName(mode) << " neighbours, dt "
            << rounded(1000 * double(sim->params().timeStep), 3) << " ms"
            << (sim->params().adaptiveTimeStep ? " (adaptive)" : "") << ", about "
            << report.stepsPerFrame << " steps per frame, " << frames << " frames to " << outDir
            << "/\n";
        if (wideCellIds) {
            log << "weir: cell ids: " << cellIds
                << ", as the grid has more than the 1024 cells on an axis that the paper's "
                   "32-bit id holds\n";
        }
        if (cluster != nullptr) {
            const Decomposition& d = cluster->decomposition();
            log << "weir: " << d.ranks() << " ranks, slabs along "
                << "xyz"[d.axis()] << ", one per rank, balanced by particle count\n";
        }

        // Frame k of the run (0: the initial state) is numbered first + k in files and frames.json.
        const auto number = [&](std::int64_t frame) {
            return int(options.firstFrameNumber + frame);
        };
        std::unique_ptr<FrameWriter> writer;
        if (root) {
            writer = std::make_unique<FrameWriter>(outDir, format);
            writer->setScale(report.spacing, options.cellSize);
            writer->setRecord(makeRunRecord(scene.name, scene.sourcePath, scene.json,
                                            sim->particleCount(), report.spacing, WEIR_VERSION));
        }
        HostParticles host;
        sim->computeDensity();
        sim->download(host);
        // Frame 0 counts like every other: with boundary particles (or a scene whose fluid meets
        // an obstacle) the initial state is compressed already, and the report must say so.
        DensityDeviation worst;
        if (root) {
            writer->write(number(0), 0.0, host);
            worst = densityDeviation(host, sim->params().restDensity);
            log << "weir: frame 0 (the initial state): " << worst.text() << "\n";
            if (worst.max > 0.05) {
                log << "weir: warning: the initial fluid is compressed by up to "
                    << rounded(100 * worst.max, 3)
                    << "% (fluid blocks or spheres that overlap or meet closer than the particle "
                       "spacing, or walls of boundary particles); it pushes apart as the run "
                       "starts\n";
            }
        }
        if (observer != nullptr) {
            observer->frame(number(0), 0.0, host);
        }
        Progress progress(frames, options.quiet || !root);
        for (std::int64_t frame = 1; frame <= frames; ++frame) {
            sim->advanceTo(double(frame) * report.frameInterval);
            FaultRecord fault = sim->fault();
            if (fault.code != 0) {
                progress.finish();
                log << "weir: error: " << describeFault(fault, sim->params()) << "\nweir: frames "
                    << number(0) << ".." << number(frame - 1) << " in " << outDir
                    << "/ are complete and kept.\n";
                return kExitBlowUp;
            }
            sim->download(host);
            if (!root) {
                continue;
            }
            const DensityDeviation deviation = densityDeviation(host, sim->params().restDensity);
            worst.max = std::max(worst.max, deviation.max);
            worst.mean = std::max(worst.mean, deviation.mean);
            progress.setNote(deviation.text() +
                             solverNote(sim->takeSolverReport(), report.frameInterval, host));
            writer->write(number(frame), double(frame) * report.frameInterval, host);
            if (observer != nullptr) {
                observer->frame(number(frame), double(frame) * report.frameInterval, host);
            }
            progress.update(frame, sim->time(), sim->stepCount());
        }
        progress.finish();
        if (observer != nullptr) {
            observer->finish();
        }
        double seconds = progress.elapsedSeconds();
        log << "weir: done, " << frames + 1 << " frames, " << sim->stepCount() << " steps in "
            << formatDuration(seconds) << " ("
            << rounded(seconds > 0 ? double(sim->stepCount()) / seconds : 0.0, 3)
            << " steps/s); worst frame: " << worst.text() << "\n";
        if (cluster != nullptr) {
            log << "weir: borders moved " << cluster->exchangeStats().rebalances
                << " times to keep the ranks balanced\n";
        }
        log << "weir: " << frames + 1 << " frames in " << outDir << "/: open "
            << howToOpen(format, outDir) << "; or draw them: weir render " << outDir << "\n";
        return kExitOk;
    } catch (...) {
        return reportCaughtError(*comm);
    }
}

}  // namespace weir
