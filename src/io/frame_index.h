// The frames a `weir run` wrote, as listed in its frames.json, and reading one of them by its
// extension: the input of `weir render` and `weir mesh`.
#pragma once

#include <string>
#include <vector>

#include "io/io_error.h"
#include "solver/particles.h"

namespace weir {

struct FrameEntry {
    int index = 0;
    double time = 0;
    std::string path;  // the frame file, joined to the directory
};

// The frames listed in <dir>/frames.json, sorted by index. Throws IoError naming the file and the
// field when the index is missing, not JSON or malformed, or lists no frames.
std::vector<FrameEntry> readFrameIndex(const std::string& dir);

// Reads a .vtu, .ply or .csv frame; throws IoError naming the file for any other extension.
HostParticles readFrameFile(const std::string& path);

}  // namespace weir
