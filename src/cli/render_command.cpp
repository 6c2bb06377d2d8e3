// `weir render` (frames directory in, one PNG per frame and optionally an MP4 out) and
// `weir run --render`.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <future>
#include <iostream>
#include <optional>
#include <sstream>

#include "cli/frame_selection.h"
#include "cli/progress.h"
#include "cli/render_commands.h"
#include "cli/video.h"
#include "core/backend.h"
#include "io/frame_index.h"
#include "raytrace/interactive_water.h"
#include "raytrace/water_renderer.h"
#include "raytrace/water_scene_export.h"
#include "render/egl_context.h"
#include "render/gl.h"
#include "render/renderer.h"
#include "scene/setup.h"
#include "surface/point_velocity.h"
#include "surface/surface.h"
#include "whitewater/whitewater_files.h"
#include "whitewater/whitewater_ply.h"

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

// The looks of `weir render --look`: what draws the images, and what --samples counts there.
enum class Look { Preview, Water };

struct LookInfo {
    Look look;
    const char* name;
    const char* samplesMeaning;
    int defaultSamples, maxSamples;
};
constexpr LookInfo kLooks[] = {
    {Look::Preview, "preview", "multisampling per pixel", 4, 16},
    {Look::Water, "water", "paths traced per pixel", 32, 65536},
};

const LookInfo& lookInfo(const std::string& name) {
    for (const LookInfo& info : kLooks) {
        if (name == info.name) {
            return info;
        }
    }
    throw std::invalid_argument("--look '" + name + "': allowed are preview, water");
}

// --samples as given, or the look's default.
int samplesPerPixel(const RenderOptions& o) {
    return o.samples > 0 ? o.samples : lookInfo(o.look).defaultSamples;
}

// What every drawing command checks before it starts: image size, look, samples, colour field.
void checkRenderOptions(const RenderOptions& o) {
    checkImageSize(o.width, o.height);
    const LookInfo& look = lookInfo(o.look);
    const int samples = samplesPerPixel(o);
    if (samples < 1 || samples > look.maxSamples) {
        throw std::invalid_argument("--samples " + std::to_string(samples) + " must be within 1.." +
                                    std::to_string(look.maxSamples) + " for the " + look.name +
                                    " look" + " (" + look.samplesMeaning + ")");
    }
    parseColourField(o.color);
    parseBackend(o.backend);
    if (!o.exportWater.empty() && look.look != Look::Water) {
        throw std::invalid_argument(
            "--export-water writes what the water look traces: it needs --look water");
    }
    if (!(o.motionBlur >= 0 && o.motionBlur <= 1)) {
        throw std::invalid_argument("--motion-blur " + std::to_string(o.motionBlur) +
                                    " must be a share of the time between frames in [0, 1]");
    }
    if (o.motionBlur > 0 && look.look != Look::Water) {
        throw std::invalid_argument(
            "--motion-blur blurs the water look's moving surface: it needs --look water");
    }
    if (o.motionBlur > 0 && !o.exportWater.empty()) {
        throw std::invalid_argument(
            "--export-water writes one surface a frame, --motion-blur traces several: use one "
            "of them");
    }
}

// Encodes and writes each image on a thread of its own while the next one is drawn (a 1280 x 720
// path-traced image takes about 0.26 s to encode here): one write at a time; a write's error is
// thrown by the next write or by finish().
class BackgroundPngWriter {
   public:
    BackgroundPngWriter() = default;
    BackgroundPngWriter(const BackgroundPngWriter&) = delete;
    BackgroundPngWriter& operator=(const BackgroundPngWriter&) = delete;
    ~BackgroundPngWriter() {
        if (pending_.valid()) {
            pending_.wait();  // an error here is already reported by whatever unwinds
        }
    }
    void write(std::string path, Image image) {
        finish();
        pending_ = std::async(
            std::launch::async,
            [path = std::move(path), image = std::move(image)] { writePng(path, image); });
    }
    // Waits for the last write; throws its error.
    void finish() {
        if (pending_.valid()) {
            pending_.get();
        }
    }

   private:
    std::future<void> pending_;
};

// Draws frames of one run to <imagesDir>/frame_NNNNN.png with a fixed camera, in one look.
class Imager {
   public:
    virtual ~Imager() = default;
    // poses: the rigid bodies' at this frame (frames.json), drawn where the scene has them.
    virtual void render(std::int64_t index, const HostParticles& particles,
                        const std::vector<BodyPose>& poses) = 0;
    // What draws the images, for the first line of `weir render`.
    virtual std::string contextDescription() const = 0;
    virtual int images() const = 0;
    virtual std::string timing() const = 0;
    // The particle radius drawn, and the lattice spacing the surface is built at (2 radii).
    void setRadius(double radius) { radius_ = radius; }
    double radius() const { return radius_; }
    // The next frame's spray, foam and bubbles (whitewater/); null: none.
    void setWhitewater(const DiffuseParticles* whitewater) { whitewater_ = whitewater; }
    // Waits until every image is written (throws a write's error).
    void finishWriting() { writer_.finish(); }

   protected:
    double radius_ = 0.01;
    const DiffuseParticles* whitewater_ = nullptr;
    BackgroundPngWriter writer_;
};

// The preview look: an EGL context, the OpenGL renderer; particles, or (surface mode) the
// marching-cubes surface of the particles.
class FrameImager : public Imager {
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
        renderer_.setSamples(samplesPerPixel(options));
        renderer_.setMode(surface_ ? RenderMode::Surface : RenderMode::Particles);
    }
    std::string contextDescription() const override { return context_.description(); }
    void setColourRange(const ValueRange& range) { renderer_.setColourRange(range); }

    void render(std::int64_t index, const HostParticles& particles,
                const std::vector<BodyPose>& poses) override {
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
        renderer_.setWhitewater(whitewater_ ? *whitewater_ : DiffuseParticles{}, 0.8 * radius_);
        writer_.write((fs::path(imagesDir_) / imageName(index)).string(),
                      renderer_.renderImage(camera_, width_, height_));
        seconds_ += secondsSince(start);
        ++images_;
    }
    int images() const override { return images_; }
    std::string timing() const override {
        if (images_ == 0) {
            return "no images";
        }
        std::string text =
            std::to_string(std::lround(1000 * (seconds_ - meshSeconds_) / images_)) +
            " ms per image to draw (each PNG is written while the next image is drawn)";
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
    int images_ = 0;
    double seconds_ = 0, meshSeconds_ = 0;
};

// The water look (raytrace/): the marching-cubes surface of each frame, path traced as water
// with the container's floor and far walls, the obstacles and the bodies, under a sky; on the
// CPU or CUDA, with no OpenGL.
class WaterImager : public Imager {
   public:
    WaterImager(const SceneGeometry& geometry, const std::vector<MeshObstacle>& obstacleMeshes,
                const std::string& imagesDir, const RenderOptions& options,
                const OrbitCamera& camera)
        : geometry_(geometry),
          obstacleMeshes_(obstacleMeshes),
          imagesDir_(imagesDir),
          width_(options.width),
          height_(options.height),
          samples_(samplesPerPixel(options)),
          backend_(parseBackend(options.backend)),
          surfaceField_(parseSurfaceField(options.surfaceField)),
          eye_(camera.eye()),
          exportDir_(options.exportWater) {
        fs::create_directories(imagesDir_);
        // The preview's camera, so that the two looks' images line up.
        camera_.eye = Vec3f(camera.eye());
        camera_.forward = Vec3f(camera.forward());
        camera_.right = Vec3f(camera.right());
        camera_.up = Vec3f(camera.up());
        camera_.tanHalfFovY = float(std::tan(0.5 * camera.fovY * 3.14159265358979323846 / 180));
        camera_.aspect = float(width_) / float(height_);
        look_.checkerSize = float(checkerSquareOf(geometry.container));
        if (!exportDir_.empty()) {
            fs::create_directories(exportDir_);
            writeSkyHdr((fs::path(exportDir_) / "sky.hdr").string(), look_, 1024);
        }
    }
    std::string contextDescription() const override {
        std::string text = "path traced, " + std::to_string(samples_) + " paths per pixel";
        if (shutter_ > 0) {
            text += ", motion blur over " + std::to_string(std::lround(shutter_ * 1e3)) +
                    " ms in " + std::to_string(motionSlices()) + " time slices";
        }
        return text + ", on " + describeBackend(backend_);
    }
    // Motion blur: the shutter is open this long (s), centred on each frame's time; 0: none.
    void setShutter(double seconds) { shutter_ = seconds; }
    // Up to 8 time slices, each a share of the paths (the paths of slice k follow slice k-1's,
    // so a fluid at rest gives the image without blur).
    int motionSlices() const { return std::min(samples_, 8); }

    void render(std::int64_t index, const HostParticles& particles,
                const std::vector<BodyPose>& poses) override {
        const auto start = Clock::now();
        SurfaceOptions options;
        options.spacing = 2 * radius_;
        options.field = surfaceField_;
        const TriangleMesh mesh = reconstructSurface(backend_, particles, options);
        meshSeconds_ += secondsSince(start);
        const auto traceStart = Clock::now();
        TracingSceneDescription description;
        description.water = &mesh;
        description.container = geometry_.container;
        description.obstacleBoxes = geometry_.obstacleBoxes;
        description.obstacleSpheres = geometry_.obstacleSpheres;
        description.obstacleMeshes = obstacleMeshes_;
        description.bodies = geometry_.bodies;
        description.bodyPoses = poses;
        description.whitewater = whitewater_;
        description.whitewaterSize = 0.8 * radius_;
        description.cameraEye = eye_;
        // Where the fluid touches the floor and walls its surface lies within about a particle
        // radius of them: a spacing takes those faces and no others.
        description.contactDistance = 2 * radius_;
        Image image(width_, height_);
        std::vector<Vec3f> radiance;
        std::optional<TracingScene> scene;  // without motion blur: the one scene traced
        if (shutter_ > 0) {
            radiance = traceMotionBlurred(mesh, particles, description);
        } else {
            scene.emplace(description);
            radiance = traceWaterImage(backend_, *scene, look_, camera_, width_, height_, samples_);
        }
        image.rgb = toneMapToSrgb8(radiance, look_.exposure);
        traceSeconds_ += secondsSince(traceStart);
        if (scene && !exportDir_.empty()) {  // (checkRenderOptions: not with motion blur)
            // What was traced, for another renderer (docs/rendering.md, "Checked against
            // Blender Cycles").
            const fs::path stem = fs::path(exportDir_) / fs::path(imageName(index)).stem();
            writeTracedWaterObj(stem.string() + "_water.obj", *scene);
            writeWaterSceneJson(stem.string() + ".json", *scene, look_, camera_, width_, height_,
                                samples_);
            writeRadiancePfm(stem.string() + ".pfm", radiance, width_, height_);
        }
        writer_.write((fs::path(imagesDir_) / imageName(index)).string(), std::move(image));
        seconds_ += secondsSince(start);
        ++images_;
    }
    int images() const override { return images_; }

    // The image as a shutter open for shutter_ seconds sees it: the surface moved by its vertices'
    // velocities (the particles' within 2 d) to the middle of each time slice, each slice traced
    // with its share of the paths, the slices weighted by their paths. The floor, walls,
    // obstacles, bodies and whitewater stay at the frame's time.
    std::vector<Vec3f> traceMotionBlurred(const TriangleMesh& mesh, const HostParticles& particles,
                                          TracingSceneDescription description) const {
        const std::vector<Vec3f> velocity =
            particleVelocityAt(particles, mesh.positions, 4 * radius_);
        const int slices = motionSlices();
        std::vector<Vec3f> sum(std::size_t(width_) * std::size_t(height_));
        TriangleMesh moved = mesh;
        description.water = &moved;
        int first = 0;
        for (int k = 0; k < slices; ++k) {
            const int paths = samples_ / slices + (k < samples_ % slices ? 1 : 0);
            const float t = float(shutter_ * ((k + 0.5) / slices - 0.5));
            for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
                moved.positions[v] = mesh.positions[v] + velocity[v] * t;
            }
            const std::vector<Vec3f> slice = traceWaterImage(
                backend_, TracingScene(description), look_, camera_, width_, height_, paths, first);
            for (std::size_t i = 0; i < sum.size(); ++i) {
                sum[i] += slice[i] * float(paths);
            }
            first += paths;
        }
        for (Vec3f& pixel : sum) {
            pixel = pixel * (1.0f / float(samples_));
        }
        return sum;
    }

    std::string timing() const override {
        if (images_ == 0) {
            return "no images";
        }
        const double writing = seconds_ - traceSeconds_ - meshSeconds_;
        return std::to_string(std::lround(1000 * traceSeconds_ / images_)) +
               " ms per image to trace (" + std::to_string(samples_) + " paths per pixel on " +
               backendName(backend_) + ") + " +
               std::to_string(std::lround(1000 * meshSeconds_ / images_)) + " ms per surface + " +
               std::to_string(std::lround(1000 * writing / images_)) +
               " ms waiting to write (each PNG is encoded while the next image is traced)";
    }

   private:
    SceneGeometry geometry_;
    std::vector<MeshObstacle> obstacleMeshes_;
    std::string imagesDir_;
    int width_, height_, samples_;
    Backend backend_;
    SurfaceField surfaceField_;
    Vec3d eye_;
    std::string exportDir_;  // --export-water; empty: none
    double shutter_ = 0;     // --motion-blur: seconds the shutter is open; 0: none
    PinholeCamera camera_;
    WaterLook look_;
    int images_ = 0;
    double seconds_ = 0, meshSeconds_ = 0, traceSeconds_ = 0;
};

// The simulated time between a run's frames: from its frame index, else the scene's frame rate.
double timeBetweenFrames(const std::vector<FrameEntry>& all, const std::optional<Scene>& scene,
                         const std::string& framesDir) {
    if (all.size() >= 2 && all.back().index > all.front().index) {
        const double interval =
            (all.back().time - all.front().time) / double(all.back().index - all.front().index);
        if (interval > 0 && std::isfinite(interval)) {
            return interval;
        }
    }
    if (scene) {
        return 1.0 / scene->frameRate;
    }
    throw std::invalid_argument("--motion-blur needs the time between frames: the frames in '" +
                                framesDir +
                                "' do not give it (one frame, or times that do not increase) "
                                "and there is no scene; name one with --scene");
}

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
        whitewaterDir_ = (fs::path(outDir) / kWhitewaterFolder).string();
        std::cerr << "weir: rendering each frame to " << imagesDir_ << "/ ("
                  << imager_->contextDescription() << ")\n";
    }
    void frame(std::int64_t index, double, const HostParticles& particles) override {
        // With --whitewater, this frame's file is written by then (main.cpp adds that first).
        const std::string whitewaterFile = findWhitewaterFile(whitewaterDir_, index);
        const DiffuseParticles whitewater =
            whitewaterFile.empty() ? DiffuseParticles{} : readWhitewaterPly(whitewaterFile);
        imager_->setWhitewater(whitewaterFile.empty() ? nullptr : &whitewater);
        imager_->render(index, particles, particles.bodies);
        imager_->setWhitewater(nullptr);
    }
    void finish() override {
        if (imager_) {
            imager_->finishWriting();
        }
        if (imager_ && imager_->images() > 0) {
            std::cerr << "weir: " << imager_->images() << " images in " << imagesDir_ << "/ ("
                      << imager_->timing() << ")\n";
        }
    }

   private:
    RenderOptions options_;
    std::unique_ptr<FrameImager> imager_;
    std::string imagesDir_;
    std::string whitewaterDir_;  // <out>/whitewater: `weir run --whitewater` writes there
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
        const std::vector<FrameEntry> allFrames = readFrameIndex(options.framesDir);
        const std::vector<FrameEntry> frames =
            selectFrames(allFrames, options.frame, options.frames, options.framesDir);
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
        // box the camera frames. The water look has no colours: with a scene it needs no pass.
        const Look look = lookInfo(options.look).look;
        const bool everyFrameFirst = look != Look::Water || !scene;
        const auto start = Clock::now();
        const HostParticles first = readFrameFile(frames.front().path);
        const double radius = 0.5 * particleSpacing(options, record, scene, first);
        ValueRange range = robustRange(fieldValues(first, field), field);
        Box bounds{{INFINITY, INFINITY, INFINITY}, {-INFINITY, -INFINITY, -INFINITY}};
        bounds = particleBounds(first, bounds, radius);
        for (std::size_t i = 1; everyFrameFirst && i < frames.size(); ++i) {
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

        std::unique_ptr<Imager> imager;
        if (look == Look::Water) {
            auto water = std::make_unique<WaterImager>(
                geometry, scene ? scene->obstacleMeshes : std::vector<MeshObstacle>{}, imagesDir,
                options, camera);
            if (options.motionBlur > 0) {
                water->setShutter(options.motionBlur *
                                  timeBetweenFrames(allFrames, scene, options.framesDir));
            }
            imager = std::move(water);
        } else {
            auto preview = std::make_unique<FrameImager>(geometry, imagesDir, options, camera);
            preview->setColourRange(range);
            imager = std::move(preview);
        }
        imager->setRadius(radius);
        // Spray, foam and bubbles: from --whitewater, else from the run's own folder if it has one.
        std::string whitewaterDir = options.whitewater;
        if (!options.noWhitewater && whitewaterDir.empty()) {
            const fs::path beside = fs::path(options.framesDir) / kWhitewaterFolder;
            std::error_code error;
            if (fs::is_directory(beside, error)) {
                whitewaterDir = beside.string();
            }
        } else if (!whitewaterDir.empty() && !fs::is_directory(whitewaterDir)) {
            throw IoError("--whitewater '" + whitewaterDir +
                          "' is not a folder (of whitewater_NNNNN.ply files: weir whitewater)");
        }
        if (options.noWhitewater) {
            whitewaterDir.clear();
        }
        if (!options.quiet) {
            std::cerr << "weir: rendering " << frames.size() << " frame"
                      << (frames.size() == 1 ? "" : "s") << " of " << options.framesDir << " to "
                      << imagesDir << "/ (" << options.width << "x" << options.height << ", ";
            if (look == Look::Water) {
                std::cerr << "water look";
            } else if (options.surface) {
                std::cerr << "surface";
            } else {
                std::cerr << colourFieldName(field) << " " << rounded(range.lo, 3) << ".."
                          << rounded(range.hi, 3) << " " << colourFieldUnit(field);
            }
            if (!whitewaterDir.empty()) {
                std::cerr << ", whitewater from " << whitewaterDir;
            }
            std::cerr << ", particle spacing " << rounded(2 * radius, 3) << " m, " << sceneFrom
                      << "; " << imager->contextDescription() << ")\n";
        }
        ItemProgress progress("render", frames.size(), options.quiet);
        for (std::size_t i = 0; i < frames.size(); ++i) {
            const std::string whitewaterFile =
                whitewaterDir.empty() ? "" : findWhitewaterFile(whitewaterDir, frames[i].index);
            const DiffuseParticles whitewater =
                whitewaterFile.empty() ? DiffuseParticles{} : readWhitewaterPly(whitewaterFile);
            imager->setWhitewater(whitewaterFile.empty() ? nullptr : &whitewater);
            imager->render(frames[i].index, i == 0 ? first : readFrameFile(frames[i].path),
                           frames[i].bodies);
            progress.update(i + 1);
        }
        imager->finishWriting();
        progress.finish();
        std::cerr << "weir: " << frames.size() << " image" << (frames.size() == 1 ? "" : "s")
                  << " in " << imagesDir << "/, " << imager->timing() << ", "
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
