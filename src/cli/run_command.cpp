// `weir run`: scene in, particle frames out, with progress, logs and blow-up detection.
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "cli/commands.h"
#include "cli/interrupt.h"
#include "cli/progress.h"
#include "cli/run_folder.h"
#include "cluster/distributed_simulation.h"
#include "core/check.h"
#include "grid/cell_id.h"
#include "io/background_frame_writer.h"
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

// "Ctrl-C (SIGINT)" for the stop message.
std::string signalName(int signal) {
    return signal == SIGINT ? "Ctrl-C (SIGINT)" : signal == SIGTERM ? "SIGTERM" : "a signal";
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
        const FrameOutputMode outputMode = frameOutputModeFromEnvironment();
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
        const bool flows = setup.flow.active();
        const std::string room = flows ? " (room for " + std::to_string(setup.flow.capacity) +
                                             ": emitters and sinks change the count)"
                                       : "";
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
        log << "weir: " << sim->particleCount() << " particles" << room << " on "
            << backendName(backend) << " (" << sim->deviceName() << "), " << neighbourModeName(mode)
            << " neighbours, dt " << rounded(1000 * double(sim->params().timeStep), 3) << " ms"
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
        // Rank 0 writes the frames on a thread of its own (io/background_frame_writer.h) while
        // the simulation steps on; WEIR_FRAME_OUTPUT=foreground writes them in between steps as
        // before, =off not at all (a single-process run then downloads none it need not).
        const bool framesOff = outputMode == FrameOutputMode::Off;
        const bool downloads = !framesOff || observer != nullptr || cluster != nullptr;
        // Declared before the writer: its thread may read them until it is joined.
        std::atomic<bool> stopping{false};  // the stepping thread ends the run
        // "frames 0..7 in out/dam_break/ are": the frames written, all of them complete.
        const auto keptFrames = [&](const BackgroundFrameWriter* written) {
            const int last = written != nullptr ? written->lastWrittenIndex() : -1;
            return last < 0 ? std::string("no frames are")
                            : "frames " + std::to_string(number(0)) + ".." + std::to_string(last) +
                                  " in " + outDir + "/ are";
        };
        std::unique_ptr<BackgroundFrameWriter> output;
        if (root && !framesOff) {
            auto writer = std::make_unique<FrameWriter>(outDir, format);
            writer->setScale(report.spacing, options.cellSize);
            writer->setRecord(makeRunRecord(scene.name, scene.sourcePath, scene.json,
                                            sim->particleCount(), report.spacing, WEIR_VERSION));
            // One frame being filled, one queued, one being written, as host memory allows
            // (less what a GPU run's download keeps on the host: positions, velocities, ids).
            const std::size_t count = std::size_t(sim->particleCount());
            const std::size_t frameBytes = count * 8 * sizeof(Real);
            const std::size_t staging =
                backend == Backend::Cuda ? count * (2 * sizeof(Real4) + sizeof(Index)) : 0;
            const std::size_t available = availableHostBytes();
            const int held =
                outputMode == FrameOutputMode::Background
                    ? framesThatFit(frameBytes, available - std::min(available, staging))
                    : 1;
            output = std::make_unique<BackgroundFrameWriter>(std::move(writer), held, outputMode);
        }
        // Ctrl-C and SIGTERM stop the run between frames, after the frames handed over are
        // written (not in a distributed run: its ranks would have to agree where to stop).
        std::optional<InterruptGuard> interruptGuard;
        if (cluster == nullptr) {
            interruptGuard.emplace();
        }
        if (output != nullptr && outputMode == FrameOutputMode::Background && cluster == nullptr) {
            // A signal while the stepping thread is inside a frame's steps (minutes at 1B
            // particles): once every frame handed over is written, nothing is lost by ending
            // now rather than after that frame.
            output->setIdleCheck(
                [&] {
                    if (stopSignal() != 0 && !stopping.load()) {
                        std::cerr << "\nweir: stopped by " << signalName(stopSignal()) << "; "
                                  << keptFrames(output.get()) << " complete and kept.\n";
                        std::_Exit(128 + stopSignal());
                    }
                },
                std::chrono::milliseconds(200));
        }
        // The frame to fill: one of the writer's (returned to it when written), else this
        // thread's own.
        HostParticles ownFrame;
        const auto frameToFill = [&]() -> std::shared_ptr<HostParticles> {
            if (output != nullptr) {
                return output->acquire();
            }
            return std::shared_ptr<HostParticles>(std::shared_ptr<HostParticles>(), &ownFrame);
        };
        const auto handOver = [&](std::int64_t frame, std::shared_ptr<HostParticles> host) {
            if (output != nullptr) {
                output->submit(number(frame), double(frame) * report.frameInterval,
                               std::move(host));
            }
        };
        // Ends the run early: every frame handed over written first (a write error then wins).
        const auto stopEarly = [&] {
            stopping.store(true);
            if (output != nullptr) {
                output->finish();
            }
        };

        std::shared_ptr<HostParticles> host = frameToFill();
        sim->computeDensity();
        if (downloads) {
            sim->download(*host);
        }
        // Frame 0 counts like every other: with boundary particles (or a scene whose fluid meets
        // an obstacle) the initial state is compressed already, and the report must say so.
        DensityDeviation worst;
        bool warnedRefused = false;
        if (root && downloads) {
            worst = densityDeviation(*host, sim->params().restDensity, false);
            handOver(0, host);
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
            observer->frame(number(0), 0.0, *host);
        }
        host.reset();                // the writer's again once written
        double downloadSeconds = 0;  // the stepping thread's share of frames 1.., with the check
        Progress progress(frames, options.quiet || !root);
        for (std::int64_t frame = 1; frame <= frames; ++frame) {
            if (stopRequested()) {
                stopEarly();
                progress.finish();
                const int signal = stopSignal() != 0 ? stopSignal() : SIGINT;
                log << "weir: stopped by " << signalName(signal)
                    << " at t = " << rounded(sim->time(), 4) << " s; " << keptFrames(output.get())
                    << " complete and kept.\n";
                return 128 + signal;
            }
            sim->advanceTo(double(frame) * report.frameInterval);
            FaultRecord fault = sim->fault();
            if (fault.code != 0) {
                stopEarly();
                progress.finish();
                log << "weir: error: " << describeFault(fault, sim->params()) << "\nweir: frames "
                    << number(0) << ".." << number(frame - 1) << " in " << outDir
                    << "/ are complete and kept.\n";
                return kExitBlowUp;
            }
            if (!downloads) {
                progress.update(frame, sim->time(), sim->stepCount());
                continue;
            }
            host = frameToFill();
            const auto downloadStart = std::chrono::steady_clock::now();
            sim->download(*host);
            if (!root) {
                host.reset();
                continue;
            }
            const double time = double(frame) * report.frameInterval;
            const DensityDeviation deviation =
                densityDeviation(*host, sim->params().restDensity, false);
            downloadSeconds +=
                std::chrono::duration<double>(std::chrono::steady_clock::now() - downloadStart)
                    .count();
            worst.max = std::max(worst.max, deviation.max);
            worst.mean = std::max(worst.mean, deviation.mean);
            std::string flowNote;
            if (flows) {
                const FlowCounters counts = sim->flowCounters();
                flowNote = "  " + std::to_string(host->size()) + " particles (" +
                           std::to_string(counts.emitted) + " in, " +
                           std::to_string(counts.removed) + " out)";
                if (counts.refused > 0 && !warnedRefused) {
                    warnedRefused = true;
                    log << "weir: warning: the emitters found no room for " << counts.refused
                        << " particles: the reservoir (sized for the scene's time.duration) is "
                           "full; from now on only what the sinks free comes in. Raise "
                           "time.duration to make room\n";
                }
            }
            progress.setNote(deviation.text() +
                             solverNote(sim->takeSolverReport(), report.frameInterval, *host) +
                             flowNote);
            handOver(frame, host);
            if (observer != nullptr) {
                observer->frame(number(frame), time, *host);
            }
            host.reset();
            progress.update(frame, sim->time(), sim->stepCount());
        }
        stopping.store(true);
        if (output != nullptr) {
            output->finish();  // the last frames, before the summary and --usd read them
        }
        progress.finish();
        if (observer != nullptr) {
            observer->finish();
        }
        double seconds = progress.elapsedSeconds();
        log << "weir: done, " << frames + 1 << " frames, " << sim->stepCount() << " steps in "
            << formatDuration(seconds) << " ("
            << rounded(seconds > 0 ? double(sim->stepCount()) / seconds : 0.0, 3) << " steps/s)"
            << (downloads ? "; worst frame: " + worst.text() : "") << "\n";
        if (output != nullptr) {
            // Whether output held the run up: the seconds writing took (in between steps in the
            // foreground; beside them in the background, where only the wait for a free frame
            // stalls the simulation).
            const BackgroundFrameWriter::Stats cost = output->stats();
            log << "weir: frames downloaded in " << rounded(downloadSeconds, 3)
                << " s on the simulation's thread, written "
                << (outputMode == FrameOutputMode::Background ? "in the background"
                                                              : "in between steps")
                << ": " << rounded(double(cost.frameBytes) / 1e6, 3) << " MB in "
                << rounded(cost.writeSeconds, 3) << " s ("
                << rounded(cost.writeSeconds > 0 ? double(cost.frameBytes) / 1e6 / cost.writeSeconds
                                                 : 0.0,
                           3)
                << " MB/s)";
            if (outputMode == FrameOutputMode::Background) {
                log << "; the simulation waited " << rounded(cost.waitSeconds, 3) << " s"
                    << " for free frames (" << output->capacity() << " held at most)";
            }
            log << "\n";
        }
        if (cluster != nullptr) {
            log << "weir: borders moved " << cluster->exchangeStats().rebalances
                << " times to keep the ranks balanced\n";
        }
        if (framesOff) {
            log << "weir: frame output off (WEIR_FRAME_OUTPUT=off): no frames written\n";
        } else {
            log << "weir: " << frames + 1 << " frames in " << outDir << "/: open "
                << howToOpen(format, outDir) << "; or draw them: weir render " << outDir << "\n";
        }
        return kExitOk;
    } catch (...) {
        return reportCaughtError(*comm);
    }
}

}  // namespace weir
