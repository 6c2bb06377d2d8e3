// `weir whitewater` (a run's frames in, whitewater_NNNNN.ply per frame out: spray, foam and
// bubbles, src/whitewater/) and `weir run --whitewater`.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>

#include "cli/commands.h"
#include "cli/frame_selection.h"
#include "cli/progress.h"
#include "io/frame_index.h"
#include "scene/setup.h"
#include "surface/surface.h"
#include "whitewater/whitewater_files.h"

namespace weir {

namespace {

namespace fs = std::filesystem;

WhitewaterSettings settingsOf(const WhitewaterOptions& o) {
    if (o.maxParticles < 0) {
        throw std::invalid_argument("--max-particles " + std::to_string(o.maxParticles) +
                                    " must be >= 0");
    }
    if (!(o.rate >= 0) || !std::isfinite(o.rate)) {
        throw std::invalid_argument(
            "--rate " + std::to_string(o.rate) +
            " must be >= 0 diffuse particles per fluid particle per second");
    }
    WhitewaterSettings s;
    s.trappedAirRate = s.waveCrestRate = o.rate;
    s.foamLifetime = o.lifetime;
    s.maxParticles = std::size_t(o.maxParticles);
    s.substeps = o.substeps;
    s.check();
    return s;
}

// The scale of a run: its spacing and neighbourhood, the scene's gravity and container, the flow
// speed of its first frame (the same for `weir run --whitewater` and `weir whitewater`).
WhitewaterScale scaleOf(const Scene& scene, double spacing, const HostParticles& firstFrame) {
    WhitewaterScale scale;
    scale.spacing = spacing;
    scale.smoothingRatio = scene.smoothingRatio;
    scale.gravity = scene.gravity;
    scale.container = scene.container;
    scale.flowSpeed = flowSpeedOf(firstFrame, scene.gravity, spacing);
    return scale;
}

// The p-th percentile of the positive values (0 where there are none).
double percentile(std::vector<float> values, double p) {
    values.erase(std::remove_if(values.begin(), values.end(), [](float v) { return !(v > 0); }),
                 values.end());
    if (values.empty()) {
        return 0;
    }
    const auto k = std::size_t(std::lround(p / 100.0 * double(values.size() - 1)));
    std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(k), values.end());
    return values[k];
}

// --explain: the scale, the thresholds in physical units, and what the potentials of a frame
// come to, so that a user can see which one limits the whitewater.
void explain(const WhitewaterScale& scale, const WhitewaterSettings& s, const HostParticles& fluid,
             std::int64_t index) {
    const double u = scale.flowSpeed;
    std::cerr << "weir: whitewater scale: spacing " << rounded(scale.spacing, 4) << " m, h "
              << rounded(scale.neighbourRadius(), 4)
              << " m, flow speed U = sqrt(2 g H) + max|v| = " << rounded(u, 3) << " m/s\n"
              << "weir: thresholds: trapped air " << rounded(s.trappedAirMin * u, 3) << ".."
              << rounded(s.trappedAirMax * u, 3) << " m/s, wave crest " << s.waveCrestMin << ".."
              << s.waveCrestMax << ", kinetic energy "
              << rounded(0.5 * std::pow(s.kineticSpeedMin * u, 2), 3) << ".."
              << rounded(0.5 * std::pow(s.kineticSpeedMax * u, 2), 3) << " J/kg\n";
    const WhitewaterPotentials p = computePotentials(fluid, scale, s);
    const auto line = [&](const char* name, const std::vector<float>& raw,
                          const std::vector<float>& clamped) {
        const auto active =
            std::count_if(clamped.begin(), clamped.end(), [](float v) { return v > 0; });
        std::cerr << "weir: frame " << index << " " << name << ": 50/90/99% of the nonzero "
                  << rounded(percentile(raw, 50), 3) << " / " << rounded(percentile(raw, 90), 3)
                  << " / " << rounded(percentile(raw, 99), 3) << ", max "
                  << rounded(percentile(raw, 100), 3) << "; " << active << " of " << fluid.size()
                  << " particles past the lower threshold\n";
    };
    line("trapped air [m/s]", p.rawTrappedAir, p.trappedAir);
    line("wave crest", p.rawWaveCrest, p.waveCrest);
    line("kinetic energy [J/kg]", p.rawKinetic, p.kinetic);
}

void reportFrame(const WhitewaterFrameReport& r, std::int64_t index) {
    std::cerr << "weir: whitewater frame " << index << ": " << r.spray << " spray, " << r.foam
              << " foam, " << r.bubbles << " bubbles (" << r.step.born << " born, " << r.step.left
              << " left the container, " << r.step.dissolved << " dissolved"
              << (r.step.capped > 0 ? ", " + std::to_string(r.step.capped) + " over the cap" : "")
              << "; " << r.step.substeps << " sub-steps, " << std::lround(1000 * r.seconds)
              << " ms)\n";
}

// `weir run --whitewater`: the run's own spacing and scene, the frames as they are written.
class RunWhitewater : public RunObserver {
   public:
    explicit RunWhitewater(const WhitewaterOptions& options)
        : options_(options), settings_(settingsOf(options)) {}
    void start(const Scene& scene, const SetupReport& report, const std::string& outDir) override {
        scene_ = scene;
        spacing_ = report.spacing;
        dir_ = options_.outDir.empty() ? (fs::path(outDir) / kWhitewaterFolder).string()
                                       : options_.outDir;
        std::cerr << "weir: writing each frame's spray, foam and bubbles to " << dir_ << "/\n";
    }
    void frame(std::int64_t index, double time, const HostParticles& particles) override {
        if (!sequence_) {
            sequence_ = std::make_unique<WhitewaterSequence>(
                dir_, scaleOf(scene_, spacing_, particles), settings_);
        }
        sequence_->add(index, time, particles);
    }
    void finish() override {
        if (sequence_) {
            std::cerr << "weir: " << sequence_->summary() << "\n";
        }
    }

   private:
    WhitewaterOptions options_;
    WhitewaterSettings settings_;
    Scene scene_;
    double spacing_ = 0;
    std::string dir_;
    std::unique_ptr<WhitewaterSequence> sequence_;
};

}  // namespace

std::unique_ptr<RunObserver> makeRunWhitewater(const WhitewaterOptions& options) {
    return std::make_unique<RunWhitewater>(options);
}

int whitewaterCommand(const WhitewaterOptions& options) {
    try {
        const WhitewaterSettings settings = settingsOf(options);
        const std::vector<FrameEntry> all = readFrameIndex(options.framesDir);
        const std::vector<FrameEntry> frames =
            selectFrames(all, std::nullopt, options.frames, options.framesDir);
        const RunRecord record = readRunRecord(options.framesDir);
        if (record.sceneJson.empty()) {
            throw IoError("'" + (fs::path(options.framesDir) / "frames.json").string() +
                          "' records no scene: whitewater needs the run's container and gravity "
                          "(frames written by `weir run` record them)");
        }
        const Scene scene = parseScene(record.sceneJson, record.sceneSource);
        // The scale comes from the run's first frame, whichever frames are processed, so that a
        // range gives what the whole run gives there (from an empty start).
        const HostParticles firstFrame = readFrameFile(all.front().path);
        double spacing = record.spacing;
        if (!(spacing > 0)) {
            spacing = estimateParticleSpacing(firstFrame);
        }
        if (!(spacing > 0)) {
            throw IoError("cannot tell the particle spacing of '" + options.framesDir +
                          "': frames.json records none and its first frame has too few particles");
        }
        const WhitewaterScale scale = scaleOf(scene, spacing, firstFrame);
        const std::string outDir = options.outDir.empty()
                                       ? (fs::path(options.framesDir) / kWhitewaterFolder).string()
                                       : options.outDir;
        if (!options.quiet) {
            std::cerr << "weir: spray, foam and bubbles for " << frames.size() << " frame"
                      << (frames.size() == 1 ? "" : "s") << " of " << options.framesDir << " ("
                      << scene.name << ") to " << outDir << "/ (at most " << settings.maxParticles
                      << " diffuse particles, CPU)\n";
        }
        WhitewaterSequence sequence(outDir, scale, settings);
        ItemProgress progress("whitewater", frames.size(), options.quiet || options.explain);
        for (std::size_t i = 0; i < frames.size(); ++i) {
            const HostParticles fluid =
                frames[i].path == all.front().path ? firstFrame : readFrameFile(frames[i].path);
            if (options.explain && i == 0) {
                explain(scale, settings, fluid, frames[i].index);
            }
            const WhitewaterFrameReport report =
                sequence.add(frames[i].index, frames[i].time, fluid);
            if (options.explain) {
                reportFrame(report, frames[i].index);
            }
            progress.update(i + 1);
        }
        progress.finish();
        std::cerr << "weir: " << sequence.summary() << ", "
                  << formatDuration(progress.elapsedSeconds()) << " in all\n";
        return kExitOk;
    } catch (...) {
        return reportCaughtError();
    }
}

}  // namespace weir
