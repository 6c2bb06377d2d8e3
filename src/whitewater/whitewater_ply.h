// whitewater_NNNNN.ply: one frame's diffuse particles as a binary little-endian PLY (x y z,
// vx vy vz as float, kind as uchar: 0 spray, 1 foam, 2 bubble, lifetime in seconds as float).
#pragma once

#include <string>

#include "io/io_error.h"
#include "whitewater/diffuse_particles.h"

namespace weir {

// Written atomically (io/atomic_file.h): readers only ever see a whole file. Throws IoError
// naming the path and the OS reason.
void writeWhitewaterPly(const std::string& path, const DiffuseParticles& particles);

// Reads a file written by writeWhitewaterPly; throws IoError naming the file and what is wrong
// (cannot open, not a PLY, other columns than these, a kind past 2, truncated).
DiffuseParticles readWhitewaterPly(const std::string& path);

}  // namespace weir
