// The frames a `weir run` wrote, as listed in its frames.json, and reading one of them by its
// extension: the input of `weir render` and `weir mesh`.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io/io_error.h"
#include "solver/particles.h"

namespace weir {

struct FrameEntry {
    int index = 0;
    double time = 0;
    std::string path;              // the frame file, joined to the directory
    std::vector<BodyPose> bodies;  // the rigid bodies' poses at this frame (empty: none)
};

// The frames listed in <dir>/frames.json, sorted by index. Throws IoError naming the file and the
// field when the index is missing, not JSON or malformed, or lists no frames.
std::vector<FrameEntry> readFrameIndex(const std::string& dir);

// What frames.json records of the run besides its frames (`weir run` writes them; an index
// written by another tool, or by weir before it recorded them, leaves them empty).
struct RunRecord {
    std::string sceneName;    // "dam_break"
    std::string sceneSource;  // the scene file's path as given, or "<built-in NAME>"
    std::string sceneJson;    // the scene as the run read it (JSON text)
    double spacing = 0;       // the run's particle spacing d [m]; 0: not recorded
    std::int64_t particles = 0;
    std::string format;  // "vtu", ...
    std::size_t frames = 0;
};

// What a run records in frames.json besides its frames (FrameWriter::setRecord), so that
// `weir render DIR` needs no --scene and knows the particle spacing; readRunRecord reads it back.
// A scene file is named by its absolute path, which its mesh obstacles' paths are relative to;
// a built-in scene's source ("<built-in NAME>") as it is.
nlohmann::json makeRunRecord(const std::string& sceneName, const std::string& sceneSource,
                             const std::string& sceneJson, std::int64_t particles, double spacing,
                             const std::string& version);

// The record in <dir>/frames.json; throws IoError as readFrameIndex does.
RunRecord readRunRecord(const std::string& dir);

// Reads a frame by its extension, through the format table (io/frame_formats.h); throws IoError
// naming the file for an extension no format has, and for positions that cannot be drawn or
// meshed (checkFramePositions in io/frame_reader.h: not finite, or absurdly far).
HostParticles readFrameFile(const std::string& path);

}  // namespace weir
