// `weir mesh` (frames directory in, one surface mesh per frame out, OBJ and/or binary PLY) and
// `weir run --mesh`.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>

#include "cli/commands.h"
#include "cli/frame_selection.h"
#include "cli/progress.h"
#include "io/frame_index.h"
#include "io/mesh_writer.h"
#include "io/optional_formats.h"
#include "scene/setup.h"
#include "surface/surface.h"

namespace weir {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// "obj", "ply", "obj,ply": each named once. `option` is the command's own name for the list
// ("--format" for weir mesh, "--mesh-format" for weir run), so that errors name what was typed.
std::vector<MeshFormat> parseMeshFormats(const std::string& list, const std::string& option) {
    const std::string allowed =
        "allowed: one or more of " + meshFormatList() + ", comma-separated (e.g. obj,ply)";
    std::vector<MeshFormat> formats;
    std::stringstream in(list);
    for (std::string item; std::getline(in, item, ',');) {
        std::optional<MeshFormat> format;
        try {
            format = parseMeshFormat(item);
        } catch (const std::invalid_argument&) {
            const std::string missing = missingFormatReason(item);
            throw std::invalid_argument(option + " '" + list + "': '" + item + "' " +
                                        (missing.empty() ? "is not a mesh format; " + allowed
                                                         : "cannot be written: " + missing));
        }
        for (MeshFormat f : formats) {
            if (f == *format) {
                throw std::invalid_argument(option + " '" + list + "' names '" + item + "' twice");
            }
        }
        formats.push_back(*format);
    }
    if (formats.empty()) {
        throw std::invalid_argument(option + " is empty; " + allowed);
    }
    return formats;
}

void checkSurfaceNumbers(const MeshOptions& o) {
    auto check = [](double value, const char* flag) {
        if (!(value >= 0) || !std::isfinite(value)) {
            std::ostringstream text;
            text << flag << " " << value << " must be a length in metres > 0 (0: automatic)";
            throw std::invalid_argument(text.str());
        }
    };
    check(o.spacing, "--spacing");
    check(o.cellSize, "--cell-size");
    if (!std::isfinite(o.iso)) {
        throw std::invalid_argument("--iso must be a finite number of particle spacings");
    }
}

std::string meshName(std::int64_t index, MeshFormat format) {
    char name[40];
    std::snprintf(name, sizeof name, "surface_%05lld.%s", static_cast<long long>(index),
                  meshExtension(format).c_str());
    return name;
}

// Writes each frame's surface in every format asked for, timing reconstruction and writing.
class FrameMesher {
   public:
    FrameMesher(const std::string& outDir, std::vector<MeshFormat> formats, Backend backend,
                SurfaceOptions options)
        : outDir_(outDir), formats_(std::move(formats)), backend_(backend), options_(options) {
        fs::create_directories(outDir_);
    }

    // Returns the triangle count.
    std::size_t mesh(std::int64_t index, double time, const HostParticles& particles) {
        const auto start = Clock::now();
        SurfacePlan plan;
        const TriangleMesh mesh = reconstructSurface(backend_, particles, options_, &plan);
        const auto built = Clock::now();
        const SurfaceFrame frame{mesh, &particles, plan.spacing, plan.cellSize, time};
        for (MeshFormat format : formats_) {
            writeMesh((fs::path(outDir_) / meshName(index, format)).string(), format, frame);
        }
        buildSeconds_ += std::chrono::duration<double>(built - start).count();
        writeSeconds_ += std::chrono::duration<double>(Clock::now() - built).count();
        ++meshes_;
        triangles_ += mesh.triangleCount();
        return mesh.triangleCount();
    }

    std::string summary() const {
        std::ostringstream out;
        out << meshes_ << " meshes in " << outDir_ << "/ (" << backendName(backend_) << ", "
            << std::lround(meshes_ ? double(triangles_) / double(meshes_) : 0.0)
            << " triangles each on average, "
            << std::lround(meshes_ ? 1000 * buildSeconds_ / double(meshes_) : 0.0)
            << " ms per mesh to build, "
            << std::lround(meshes_ ? 1000 * writeSeconds_ / double(meshes_) : 0.0)
            << " ms to write)";
        return out.str();
    }

   private:
    std::string outDir_;
    std::vector<MeshFormat> formats_;
    Backend backend_;
    SurfaceOptions options_;
    int meshes_ = 0;
    std::size_t triangles_ = 0;
    double buildSeconds_ = 0, writeSeconds_ = 0;
};

SurfaceOptions surfaceOptions(const MeshOptions& o, double spacing) {
    SurfaceOptions s;
    s.spacing = spacing;
    s.cellSize = o.cellSize;
    s.iso = o.iso;
    s.field = parseSurfaceField(o.surfaceField);
    return s;
}

// `weir run --mesh`: the run's lattice spacing fixes the surface's scale for every frame.
class RunMesher : public RunObserver {
   public:
    explicit RunMesher(const MeshOptions& options)
        : options_(options),
          formats_(parseMeshFormats(options.formats, "--mesh-format")),
          backend_(parseBackend(options.backend)) {
        checkSurfaceNumbers(options);
    }
    void start(const Scene&, const SetupReport& report, const std::string& outDir) override {
        const std::string dir =
            options_.outDir.empty() ? (fs::path(outDir) / "mesh").string() : options_.outDir;
        const double spacing = options_.spacing > 0 ? options_.spacing : report.spacing;
        mesher_ = std::make_unique<FrameMesher>(dir, formats_, backend_,
                                                surfaceOptions(options_, spacing));
        std::cerr << "weir: writing each frame's surface to " << dir << "/\n";
    }
    void frame(std::int64_t index, double time, const HostParticles& particles) override {
        mesher_->mesh(index, time, particles);
    }
    void finish() override {
        if (mesher_) {
            std::cerr << "weir: " << mesher_->summary() << "\n";
        }
    }

   private:
    MeshOptions options_;
    std::vector<MeshFormat> formats_;
    Backend backend_;
    std::unique_ptr<FrameMesher> mesher_;
};

}  // namespace

std::unique_ptr<RunObserver> makeRunMesher(const MeshOptions& options) {
    return std::make_unique<RunMesher>(options);
}

int meshCommand(const MeshOptions& options) {
    try {
        const std::vector<MeshFormat> formats = parseMeshFormats(options.formats, "--format");
        checkSurfaceNumbers(options);
        const Backend backend = parseBackend(options.backend);
        const std::vector<FrameEntry> all = readFrameIndex(options.framesDir);
        const std::vector<FrameEntry> frames =
            selectFrames(all, options.frame, options.frames, options.framesDir);
        const std::string outDir = options.outDir.empty()
                                       ? (fs::path(options.framesDir) / "mesh").string()
                                       : options.outDir;
        // One spacing for all frames, so that the surface keeps its scale as the fluid
        // compresses and splashes: the run's (frames.json), else measured on the run's first
        // frame (the seeded lattice), whichever frames are meshed.
        double spacing = options.spacing;
        if (spacing == 0) {
            spacing = readRunRecord(options.framesDir).spacing;
        }
        if (spacing == 0) {
            spacing = estimateParticleSpacing(readFrameFile(all.front().path));
            if (!(spacing > 0)) {
                throw SurfaceError("cannot estimate the particle spacing from '" +
                                   all.front().path + "'; give --spacing");
            }
        }
        HostParticles particles = readFrameFile(frames.front().path);
        FrameMesher mesher(outDir, formats, backend, surfaceOptions(options, spacing));
        if (!options.quiet) {
            std::cerr << "weir: meshing " << frames.size() << " frame"
                      << (frames.size() == 1 ? "" : "s") << " of " << options.framesDir << " to "
                      << outDir << "/ (spacing " << rounded(spacing, 3) << " m, cell "
                      << rounded(options.cellSize > 0 ? options.cellSize : spacing / 2, 3) << " m, "
                      << options.surfaceField << " field, " << backendName(backend) << ")\n";
        }
        ItemProgress progress("mesh", frames.size(), options.quiet);
        for (std::size_t i = 0; i < frames.size(); ++i) {
            if (i > 0) {
                particles = readFrameFile(frames[i].path);
            }
            mesher.mesh(frames[i].index, frames[i].time, particles);
            progress.update(i + 1);
        }
        progress.finish();
        std::cerr << "weir: " << mesher.summary() << ", "
                  << formatDuration(progress.elapsedSeconds()) << " in all\n";
        return kExitOk;
    } catch (...) {
        return reportCaughtError();
    }
}

}  // namespace weir
