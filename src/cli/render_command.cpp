// `weir render` (frames directory in, one PNG per frame and optionally an MP4 out) and
// `weir run --render`.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>

#include "cli/frame_selection.h"
#include "cli/progress.h"
#include "cli/render_commands.h"
#include "cli/video.h"
#include "core/backend.h"
#include "io/frame_index.h"
#include "render/egl_context.h"
#include "render/gl.h"
#include "render/renderer.h"
#include "scene/setup.h"
#include "surface/surface.h"

namespace weir {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

std::string imageName(std::int64_t index) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%05lld.png", static_cast<long long>(index));
    return name;
}

// The container of the particles of all frames, padded by a particle radius, where no scene says.
Box particleBounds(const HostParticles& p, Box box, double pad) {
    for (std::size_t i = 0; i < p.size(); ++i) {
        const Vec3d x{double(p.x[i]), double(p.y[i]), double(p.z[i])};
        for (int a = 0; a < 3; ++a) {
            box.min[a] = std::min(box.min[a], x[a] - pad);
            box.max[a] = std::max(box.max[a], x[a] + pad);
        }
    }
    return box;
}

// Validates what every drawing command shares.
void checkImageSize(int width, int height) {
    if (width < 16 || width > 16384 || height < 16 || height > 16384) {
        throw std::invalid_argument("--width " + std::to_string(width) + " --height " +
                                    std::to_string(height) +
                                    ": each must be within 16..16384 pixels");
    }
}

// What every drawing command checks before it starts: image size, samples, colour field.
void checkRenderOptions(const RenderOptions& o) {
    checkImageSize(o.width, o.height);
    if (o.samples < 1 || o.samples > 16) {
        throw std::invalid_argument("--samples " + std::to_string(o.samples) +
                                    " must be within 1..16");
    }
    parseColourField(o.color);
    parseBackend(o.backend);
}

// Draws frames of one run to <imagesDir>/frame_NNNNN.png: an EGL context, the renderer and a
// fixed camera; particles, or (surface mode) the marching-cubes surface of the particles.
class FrameImager {
   public:
    FrameImager(const SceneGeometry& geometry, const std::string& imagesDir,
                const RenderOptions& options, const OrbitCamera& camera)
        : imagesDir_(imagesDir),
          width_(options.width),
          height_(options.height),
          camera_(camera),
          field_(parseColourField(options.color)),
          surface_(options.surface),
          surfaceBackend_(parseBackend(options.backend)),
          surfaceField_(parseSurfaceField(options.surfaceField)) {
        fs::create_directories(imagesDir_);
        renderer_.setGeometry(geometry);
        bodies_ = geometry.bodies;
        renderer_.setSamples(options.samples);
        renderer_.setMode(surface_ ? RenderMode::Surface : RenderMode::Particles);
    }
    const std::string& contextDescription() const { return context_.description(); }
    void setColourRange(const ValueRange& range) { renderer_.setColourRange(range); }
    // The particle radius drawn, and the lattice spacing the surface is built at (2 radii).
    void setRadius(double radius) { radius_ = radius; }
    double radius() const { return radius_; }

    // poses: the rigid bodies' at this frame (frames.json), drawn where the scene has them.
    void render(std::int64_t index, const HostParticles& particles,
                const std::vector<BodyPose>& poses) {
        const auto start = Clock::now();
        renderer_.setBodies(bodies_, poses);
        if (surface_) {
            SurfaceOptions options;
            options.spacing = 2 * radius_;
            options.field = surfaceField_;
            const auto meshStart = Clock::now();
            renderer_.setMesh(reconstructSurface(surfaceBackend_, particles, options));
            meshSeconds_ += secondsSince(meshStart);
        }
        renderer_.setParticles(particles, field_, radius_);
        writePng((fs::path(imagesDir_) / imageName(index)).string(),
                 renderer_.renderImage(camera_, width_, height_));
        seconds_ += secondsSince(start);
        ++images_;
    }
    int images() const { return images_; }
    std::string timing() const {
        if (images_ == 0) {
            return "no images";
        }
        std::string text = std::to_string(std::lround(1000 * (seconds_ - meshSeconds_) / images_)) +
                           " ms per image to draw and write";
        if (surface_) {
            text += " + " + std::to_string(std::lround(1000 * meshSeconds_ / images_)) +
                    " ms per surface on " + backendName(surfaceBackend_);
        }
        return text;
    }

   private:
    OffscreenContext context_;  // made current before the renderer is built
    Renderer renderer_;
    std::vector<BodySpec> bodies_;
    std::string imagesDir_;
    int width_, height_;
    OrbitCamera camera_;
    ColourField field_;
    bool surface_;
    Backend surfaceBackend_;
    SurfaceField surfaceField_;
    double radius_ = 0.01;
    int images_ = 0;
    double seconds_ = 0, meshSeconds_ = 0;
};

// `weir run --render`: the scene's geometry and physics fix the camera and colour range.
class RunRenderer : public RunObserver {
   public:
    explicit RunRenderer(const RenderOptions& options) : options_(options) {
        checkRenderOptions(options_);
    }
    void start(const Scene& scene, const SetupReport& report, const std::string& outDir) override {
        const ColourField field = parseColourField(options_.color);
        imagesDir_ =
            options_.outDir.empty() ? (fs::path(outDir) / "images").string() : options_.outDir;
        const OrbitCamera camera =
            commandLineCamera(scene.container, double(options_.width) / options_.height,
                              options_.camera, options_.target);
        imager_ =
            std::make_unique<FrameImager>(SceneGeometry::of(scene), imagesDir_, options_, camera);
        const double g = length(scene.gravity);
        imager_->setColourRange(physicalRange(field, scene.restDensity, report.expectedSpeed,
                                              scene.restDensity * g * report.fluidHeight));
        imager_->setRadius(0.5 * report.spacing);
        std::cerr << "weir: rendering each frame to " << imagesDir_ << "/ ("
                  << imager_->contextDescription() << ")\n";
    }
    void frame(std::int64_t index, double, const HostParticles& particles) override {
        imager_->render(index, particles, particles.bodies);
    }
    void finish() override {
        if (imager_ && imager_->images() > 0) {
            std::cerr << "weir: " << imager_->images() << " images in " << imagesDir_ << "/ ("
                      << imager_->timing() << ")\n";
        }
    }

   private:
    RenderOptions options_;
    std::unique_ptr<FrameImager> imager_;
    std::string imagesDir_;
};

// The lattice spacing the frames were seeded at: --spacing; else the run's, as frames.json
// records it; else, with a scene, the spacing at
// which the scene seeds exactly the frames' particle count (its own resolution, or the count as
// `weir run --particles` gives it); else the median nearest-neighbour distance in the first frame
// (right for frame 0, a little short for a moving fluid).
double particleSpacing(const RenderOptions& options, const RunRecord& record,
                       const std::optional<Scene>& scene, const HostParticles& first) {
    if (options.spacing > 0) {
        return options.spacing;
    }
    if (record.spacing > 0) {
        return record.spacing;
    }
    if (scene) {
        for (bool byCount : {false, true}) {
            SetupOptions setupOptions;
            if (byCount) {
                setupOptions.particleCount = std::int64_t(first.size());
            }
            SetupReport report;
            try {
                const SimulationSetup setup = buildSetup(*scene, setupOptions, &report);
                if (setup.particles.size() == first.size()) {
                    return report.spacing;
                }
            } catch (const std::exception&) {
                // not this resolution
            }
        }
    }
    return 2 * estimateParticleRadius(first);
}

}  // namespace

std::unique_ptr<RunObserver> makeRunRenderer(const RenderOptions& options) {
    return std::make_unique<RunRenderer>(options);
}

int renderCommand(const RenderOptions& options) {
    try {
        checkRenderOptions(options);
        if (!(options.spacing >= 0) || !std::isfinite(options.spacing)) {
            throw std::invalid_argument("--spacing " + std::to_string(options.spacing) +
                                        " must be a length in metres > 0 (0: automatic)");
        }
        const ColourField field = parseColourField(options.color);
        if (!options.video.empty()) {
            checkVideoOutput("--video", options.video);
        }
        const std::vector<FrameEntry> frames = selectFrames(
            readFrameIndex(options.framesDir), options.frame, options.frames, options.framesDir);
        const RunRecord record = readRunRecord(options.framesDir);
        const std::string imagesDir = options.outDir.empty()
                                          ? (fs::path(options.framesDir) / "images").string()
                                          : options.outDir;
        std::optional<Scene> scene;
        std::string sceneFrom;
        if (!options.scene.empty()) {
            scene = resolveScene(options.scene);
            sceneFrom = "scene " + scene->name + " (--scene)";
        } else if (!record.sceneJson.empty()) {
            try {
                scene = parseScene(record.sceneJson, record.sceneSource);
                sceneFrom = "scene " + scene->name + " (from frames.json)";
            } catch (const std::exception& e) {
                std::cerr << "weir: warning: the scene recorded in frames.json does not load ("
                          << e.what() << "); drawing a box around the particles (--scene SCENE "
                          << "draws a scene's container and obstacles)\n";
            }
        }
        if (!scene) {
            sceneFrom = "no scene: a box around the particles";
        }

        // A first pass over the frames fixes what must not change between images: the colour
        // range (so that a colour means one value in the whole video) and, without a scene, the
        // box the camera frames.
        const auto start = Clock::now();
        const HostParticles first = readFrameFile(frames.front().path);
        const double radius = 0.5 * particleSpacing(options, record, scene, first);
        ValueRange range = robustRange(fieldValues(first, field), field);
        Box bounds{{INFINITY, INFINITY, INFINITY}, {-INFINITY, -INFINITY, -INFINITY}};
        bounds = particleBounds(first, bounds, radius);
        for (std::size_t i = 1; i < frames.size(); ++i) {
            const HostParticles p = readFrameFile(frames[i].path);
            range = unite(range, robustRange(fieldValues(p, field), field));
            if (!scene) {
                bounds = particleBounds(p, bounds, radius);
            }
        }
        SceneGeometry geometry;
        geometry.container = bounds;
        if (scene) {
            geometry = SceneGeometry::of(*scene);
        } else if (!(bounds.max.x >= bounds.min.x)) {
            geometry.container = {{0, 0, 0}, {1, 1, 1}};  // frames without particles
        }
        const OrbitCamera camera =
            commandLineCamera(geometry.container, double(options.width) / options.height,
                              options.camera, options.target);

        FrameImager imager(geometry, imagesDir, options, camera);
        imager.setColourRange(range);
        imager.setRadius(radius);
        if (!options.quiet) {
            std::cerr << "weir: rendering " << frames.size() << " frame"
                      << (frames.size() == 1 ? "" : "s") << " of " << options.framesDir << " to "
                      << imagesDir << "/ (" << options.width << "x" << options.height << ", ";
            if (options.surface) {
                std::cerr << "surface";
            } else {
                std::cerr << colourFieldName(field) << " " << rounded(range.lo, 3) << ".."
                          << rounded(range.hi, 3) << " " << colourFieldUnit(field);
            }
            std::cerr << ", particle spacing " << rounded(2 * radius, 3) << " m, " << sceneFrom
                      << "; " << imager.contextDescription() << ")\n";
        }
        ItemProgress progress("render", frames.size(), options.quiet);
        for (std::size_t i = 0; i < frames.size(); ++i) {
            imager.render(frames[i].index, i == 0 ? first : readFrameFile(frames[i].path),
                          frames[i].bodies);
            progress.update(i + 1);
        }
        progress.finish();
        std::cerr << "weir: " << frames.size() << " image" << (frames.size() == 1 ? "" : "s")
                  << " in " << imagesDir << "/, " << imager.timing() << ", "
                  << formatDuration(secondsSince(start)) << " in all\n";

        if (!options.video.empty()) {
            const bool contiguous =
                frames.back().index - frames.front().index + 1 == int(frames.size());
            if (!contiguous) {
                std::cerr << "weir: warning: frame indices have gaps; the video stops at the "
                             "first gap\n";
            }
            const double interval = frames.size() > 1
                                        ? (frames.back().time - frames.front().time) /
                                              double(frames.back().index - frames.front().index)
                                        : 0;
            const double fps = interval > 0 ? 1.0 / interval : 30.0;
            encodeImages(imagesDir, frames.front().index, int(frames.size()), fps, options.video);
            std::cerr << "weir: video " << options.video << " (H.264, " << rounded(fps, 3)
                      << " frames/s)\n";
        }
        return kExitOk;
    } catch (...) {
        return reportCaughtError();
    }
}

}  // namespace weir
