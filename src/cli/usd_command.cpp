// `weir usd` (a run's frames, and its surface meshes where written, as one USD stage) and
// `weir run --usd`.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>

#include "cli/commands.h"
#include "cli/frame_selection.h"
#include "cli/progress.h"
#include "io/frame_index.h"
#include "io/usd_writer.h"
#include "scene/scene.h"
#include "surface/surface.h"

namespace weir {

namespace {

namespace fs = std::filesystem;

// The surface mesh weir mesh (or run --mesh) wrote for frame `index` in meshDir: its PLY, else
// its OBJ; "" when it has neither.
std::string meshFileOf(const std::string& meshDir, int index) {
    for (const char* extension : {"ply", "obj"}) {
        char name[40];
        std::snprintf(name, sizeof name, "surface_%05d.%s", index, extension);
        const fs::path path = fs::path(meshDir) / name;
        if (fs::is_regular_file(path)) {
            return path.string();
        }
    }
    return "";
}

}  // namespace

namespace {

// Writes the stage and says so; returns its path.
std::string writeRunUsd(const UsdOptions& options) {
    const std::vector<FrameEntry> frames = selectFrames(
        readFrameIndex(options.framesDir), options.frame, options.frames, options.framesDir);
    const RunRecord record = readRunRecord(options.framesDir);
    std::optional<Scene> scene;
    if (!options.scene.empty()) {
        scene = resolveScene(options.scene);
    } else if (!record.sceneJson.empty()) {
        try {
            scene = parseScene(record.sceneJson, record.sceneSource);
        } catch (const std::exception& e) {
            std::cerr << "weir: warning: the scene recorded in frames.json does not load ("
                      << e.what() << "); the stage has no container or obstacles\n";
        }
    }
    // Frames per second from the frames' numbers and times (time code = frame number), else the
    // scene's frame rate.
    double fps = scene ? scene->frameRate : 24.0;
    if (frames.size() > 1 && frames.back().time > frames.front().time) {
        fps = double(frames.back().index - frames.front().index) /
              (frames.back().time - frames.front().time);
    }
    double spacing = options.spacing > 0 ? options.spacing : record.spacing;
    if (!(spacing > 0)) {
        spacing = estimateParticleSpacing(readFrameFile(frames.front().path));
        if (!(spacing > 0)) {
            throw SurfaceError("cannot estimate the particle spacing from '" + frames.front().path +
                               "'; give --spacing");
        }
    }
    const std::string meshDir =
        options.meshDir.empty() ? (fs::path(options.framesDir) / "mesh").string() : options.meshDir;
    std::vector<UsdFrame> usdFrames;
    std::size_t withMesh = 0;
    for (const FrameEntry& frame : frames) {
        UsdFrame f{frame.index, frame.path,
                   options.noMeshes ? "" : meshFileOf(meshDir, frame.index), frame.bodies};
        withMesh += f.meshPath.empty() ? 0 : 1;
        usdFrames.push_back(f);
    }
    if (withMesh > 0 && withMesh < frames.size()) {
        std::cerr << "weir: warning: " << meshDir << "/ holds surface meshes of " << withMesh
                  << " of the " << frames.size() << " frames: the stage has no surface (weir mesh "
                  << options.framesDir << " writes them all)\n";
    }
    const std::string out = options.outPath.empty()
                                ? (fs::path(options.framesDir) / "frames.usda").string()
                                : options.outPath;
    UsdStageOptions stage;
    stage.framesPerSecond = fps;
    stage.spacing = spacing;
    stage.scene = scene ? &*scene : nullptr;
    stage.doc = "weir SPH fluid" + (record.sceneName.empty() ? "" : ": scene " + record.sceneName) +
                ", " + std::to_string(frames.size()) + " frames from " + options.framesDir;
    writeUsdStage(out, usdFrames, stage);
    std::cerr << "weir: " << out << ": " << frames.size() << " frames ("
              << (withMesh == frames.size() ? "particles and surface" : "particles")
              << (scene ? ", container and obstacles" : "") << ") as one USD stage, "
              << rounded(fps, 3) << " frames/s\n";
    return out;
}

}  // namespace

int usdCommand(const UsdOptions& options) {
    try {
        writeRunUsd(options);
        return kExitOk;
    } catch (...) {
        return reportCaughtError();
    }
}

namespace {

// `weir run --usd`: after the run's last frame (and its meshes), the stage of all its frames.
class RunUsdWriter : public RunObserver {
   public:
    explicit RunUsdWriter(UsdOptions options) : options_(std::move(options)) {}
    void start(const Scene&, const SetupReport&, const std::string& outDir) override {
        options_.framesDir = outDir;
    }
    void frame(std::int64_t, double, const HostParticles&) override {}
    void finish() override { writeRunUsd(options_); }

   private:
    UsdOptions options_;
};

}  // namespace

std::unique_ptr<RunObserver> makeRunUsdWriter(const UsdOptions& options) {
    return std::make_unique<RunUsdWriter>(options);
}

}  // namespace weir
