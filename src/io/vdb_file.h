// OpenVDB files (.vdb) of a particle frame, for Houdini, Blender and other volume tools: the
// fluid's surface as a narrow-band level set, a velocity grid and the particles as a point data
// grid. vdb_file.cpp is built only where OpenVDB was found (io/optional_formats.h says whether;
// without it these functions throw IoError saying so); this header has no OpenVDB types.
#pragma once

#include <string>

#include "io/io_error.h"
#include "solver/particles.h"
#include "surface/triangle_mesh.h"

namespace weir {

struct VdbFrameOptions {
    double time = 0;       // simulation time [s], stored as the file's metadata "time"
    double spacing = 0;    // particle spacing d [m]; 0: measured on the particles
    double voxelSize = 0;  // voxel edge of the surface and velocity grids [m]; 0: d / 2
    double halfWidth = 3;  // the level set's narrow band, voxels on each side of the surface
};

// The grids' names, as Houdini's and Blender's tools look for them.
inline constexpr const char* kVdbSurfaceGrid = "surface";
inline constexpr const char* kVdbVelocityGrid = "velocity";
inline constexpr const char* kVdbPointsGrid = "points";

// Writes `path` atomically with three grids:
// - "surface": FloatGrid of class level set, the signed distance [m] to the fluid's surface
//   (negative inside), within halfWidth voxels of it; made from `surface` (weir's marching-cubes
//   mesh of the surface field, surface/surface.h), reconstructed here on the CPU when null;
// - "velocity": Vec3fGrid on the same voxels, the mean velocity of the particles within d of each
//   voxel centre, weighted by (1 - r^2 / d^2)^3 (Cycles and Houdini motion-blur by it);
// - "points": PointDataGrid with attributes P, v (Vec3f), id (int32), density, pressure (float).
// Throws IoError naming the file when it cannot be written, SurfaceError (surface/surface.h)
// when the particles have no surface (none, or non-finite positions).
void writeVdbFrame(const std::string& path, const HostParticles& particles,
                   const VdbFrameOptions& options, const TriangleMesh* surface = nullptr);

// Reads the "points" grid of a .vdb back into particles in id order, and the metadata "time"
// into *time when given (0 if absent). Throws IoError naming the file and what is wrong for
// anything OpenVDB cannot read (not a VDB, truncated, corrupt), a missing grid or attribute, or
// ids that are not 0 .. n - 1 once each.
HostParticles readVdbFrame(const std::string& path, double* time = nullptr);

}  // namespace weir
