// writePly: a particle frame as a binary little-endian PLY point cloud (Blender, Houdini, MeshLab).
#pragma once

#include <string>

#include "io/io_error.h"
#include "solver/particles.h"

namespace weir {

// Writes the particles atomically as `element vertex N` with one float (double in a WEIR_DOUBLE
// build) property per column: x y z, then the field registry's columns (vx vy vz density
// pressure), then `property int id` (each particle's id, field_registry.h). Throws IoError when
// the file cannot be written.
void writePly(const std::string& path, const HostParticles& particles);

}  // namespace weir
