// `weir run`: scene in, particle frames out, with progress, logs and blow-up detection.
#include <filesystem>
#include <iostream>

#include "cli/commands.h"
#include "cli/progress.h"
#include "core/check.h"
#include "io/frame_writer.h"
#include "scene/scene.h"
#include "scene/setup.h"
#include "solver/density_deviation.h"

namespace weir {

Scene resolveScene(const std::string& spec) {
    if (spec.empty()) {
        return builtinScene("dam_break");
    }
    if (std::filesystem::exists(spec)) {
        return loadScene(spec);
    }
    for (const std::string& name : builtinSceneNames()) {
        if (spec == name) {
            return builtinScene(name);
        }
    }
    return loadScene(spec);  // reports the missing file
}

int runCommand(const RunOptions& options, RunObserver* observer) {
    try {
        Scene scene = resolveScene(options.scene);
        SetupOptions setupOptions;
        setupOptions.particleCount = options.particles;
        SetupReport report;
        SimulationSetup setup = buildSetup(scene, setupOptions, &report);
        const Backend backend = parseBackend(options.backend);
        const NeighbourMode mode = resolveNeighbourMode(parseNeighbourMode(options.neighbours),
                                                        setup.grid, setup.particleCount());
        const FrameFormat format = parseFrameFormat(options.format);
        const std::string outDir = options.outDir.empty() ? "out/" + scene.name : options.outDir;
        const std::int64_t frames =
            options.frames ? std::min(*options.frames, report.frames) : report.frames;

        std::cerr << "weir: scene " << scene.name << " (" << scene.sourcePath << ")\n";
        if (options.explain) {
            for (const std::string& line : report.lines) {
                std::cerr << "  " << line << "\n";
            }
        }
        for (const std::string& warning : report.warnings) {
            std::cerr << "weir: warning: " << warning << "\n";
        }
        if (observer != nullptr) {
            observer->start(scene, report, outDir);
        }
        auto sim = makeSimulation(backend, mode, std::move(setup));
        std::cerr << "weir: " << sim->particleCount() << " particles on " << backendName(backend)
                  << " (" << sim->deviceName() << "), " << neighbourModeName(mode)
                  << " neighbours, dt " << sim->params().timeStep << " s"
                  << (sim->params().adaptiveTimeStep ? " (adaptive)" : "") << ", about "
                  << report.stepsPerFrame << " steps per frame, " << frames << " frames to "
                  << outDir << "/\n";

        FrameWriter writer(outDir, format);
        HostParticles host;
        sim->computeDensity();
        sim->download(host);
        writer.write(0, 0.0, host);
        if (observer != nullptr) {
            observer->frame(0, 0.0, host);
        }
        Progress progress(frames, options.quiet);
        DensityDeviation worst;
        for (std::int64_t frame = 1; frame <= frames; ++frame) {
            sim->advanceTo(double(frame) * report.frameInterval);
            FaultRecord fault = sim->fault();
            if (fault.code != 0) {
                progress.finish();
                std::cerr << "weir: error: " << describeFault(fault, sim->params())
                          << "\nweir: frames 0.." << frame - 1 << " in " << outDir
                          << "/ are complete and kept.\n";
                return kExitBlowUp;
            }
            sim->download(host);
            const DensityDeviation deviation = densityDeviation(host, sim->params().restDensity);
            worst.max = std::max(worst.max, deviation.max);
            worst.mean = std::max(worst.mean, deviation.mean);
            progress.setNote(deviation.text());
            writer.write(int(frame), double(frame) * report.frameInterval, host);
            if (observer != nullptr) {
                observer->frame(frame, double(frame) * report.frameInterval, host);
            }
            progress.update(frame, sim->time(), sim->stepCount());
        }
        progress.finish();
        if (observer != nullptr) {
            observer->finish();
        }
        double seconds = progress.elapsedSeconds();
        std::cerr << "weir: done, " << frames + 1 << " frames, " << sim->stepCount() << " steps in "
                  << formatDuration(seconds) << " ("
                  << (seconds > 0 ? double(sim->stepCount()) / seconds : 0.0)
                  << " steps/s); worst frame: " << worst.text() << "\n";
        return kExitOk;
    } catch (const std::invalid_argument& e) {
        std::cerr << "weir: error: " << e.what() << "\n";
        return kExitUsage;
    } catch (const std::exception& e) {
        std::cerr << "weir: error: " << e.what() << "\n";
        return kExitError;
    }
}

}  // namespace weir
