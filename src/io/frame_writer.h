// FrameWriter: writes numbered particle frames in one format, with a .pvd series and frames.json.
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "io/frame_formats.h"
#include "io/io_error.h"
#include "io/pvd_writer.h"
#include "solver/particles.h"

namespace weir {

// Writes frame files <dir>/<baseName>_00000.<ext> (five digits, more when needed), each
// atomically. After every frame it also rewrites, atomically, <dir>/frames.json:
//   {"format": "vtu", "count": 2, "frames": [{"index": 0, "time": 0.0, "file": "frame_00000.vtu"},
//    ...]}
// and, for a scene with rigid bodies, each frame's "bodies": [{"position": [x, y, z],
// "orientation": [qx, qy, qz, qw], "velocity": [..], "angularVelocity": [..]}, ...] in the
// scene's order (their shapes are in the recorded scene); for a run with emitters or sinks,
// whose particle count changes, each frame's "particles": its count
// (frames sorted by index, file names relative to dir), and for vtu <dir>/<baseName>.pvd.
class FrameWriter {
   public:
    // Creates dir and its parents; throws IoError if that is impossible.
    FrameWriter(std::string dir, FrameFormat format, std::string baseName = "frame");

    // Writes frame frameIndex (>= 0, else std::invalid_argument) at simulation time `time`;
    // writing an index again replaces that frame. Throws IoError when a file cannot be written.
    void write(int frameIndex, double time, const HostParticles& particles);

    std::string framePath(int frameIndex) const;
    const std::string& dir() const { return dir_; }
    FrameFormat format() const { return format_; }
    std::string indexPath() const;  // <dir>/frames.json
    // Fields written into frames.json beside format, count and frames, from the next write on:
    // what the run was (its scene, its spacing; io/frame_index.h reads them back).
    void setRecord(nlohmann::json record) { record_ = std::move(record); }
    // The run's particle spacing and the volume formats' voxel (FrameInfo), from the next write
    // on; unset, a format that needs them measures each frame.
    void setScale(double spacing, double voxelSize) {
        spacing_ = spacing;
        voxelSize_ = voxelSize;
    }

   private:
    std::string frameFileName(int frameIndex) const;
    void writeIndex() const;

    std::string dir_;
    FrameFormat format_;
    std::string baseName_;
    std::optional<PvdCollection> pvd_;                      // vtu only
    std::map<int, std::pair<double, std::string>> frames_;  // index -> (time, file name)
    std::map<int, nlohmann::json> bodies_;                  // index -> its bodies' poses
    std::map<int, std::size_t> counts_;  // index -> its particle count, where the count changes
    nlohmann::json record_ = nlohmann::json::object();
    double spacing_ = 0, voxelSize_ = 0;
};

}  // namespace weir
