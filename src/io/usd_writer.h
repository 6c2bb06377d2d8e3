// A run as one USD stage in text form (.usda), written by weir itself (no USD library): the
// particles as UsdGeomPoints, the surface meshes as a UsdGeomMesh, the container and obstacles,
// each frame a time sample whose time code is the frame's number. Blender, Houdini (Solaris or
// a USD Import SOP) and usdview open it; docs/pipeline.md.
#pragma once

#include <string>
#include <vector>

#include "io/io_error.h"
#include "scene/scene.h"
#include "solver/particles.h"

namespace weir {

struct UsdFrame {
    int number = 0;                // the frame's number, its time code
    std::string particlesPath;     // a frame file of any frame format (readFrameFile)
    std::string meshPath;          // its surface mesh (.obj or .ply, readMesh); "" none
    std::vector<BodyPose> bodies;  // the scene's rigid bodies at this frame (frames.json)
};

struct UsdStageOptions {
    double framesPerSecond = 0;    // time codes per second, > 0
    double spacing = 0;            // particle spacing d [m], > 0: the points' width; the surface
                                   // vertices' velocity averages the particles within 2 d
    const Scene* scene = nullptr;  // its container (a guide cube) and obstacles; null: none
    std::string doc;               // the stage's doc string
};

// The prims, under /weir:
// - particles (Points): points, velocities [m/s], ids (int64, the particle ids of
//   field_registry.h), extent, primvars:density and primvars:pressure (vertex), all time-sampled,
//   and widths = d (constant);
// - surface (Mesh), where every frame has a mesh: points, normals, velocities (each vertex's
//   from the particles within 2 d, surface/point_velocity.h), faceVertexCounts,
//   faceVertexIndices and extent, time-sampled; triangles wound counter-clockwise seen from
//   outside (USD's default rightHanded orientation);
// - container (Cube, purpose guide) and obstacles/box_N (Cube), sphere_N (Sphere), mesh_N
//   (Mesh), static;
// - bodies/body_N (Xform), where the scene has rigid bodies and the frames their poses: its
//   xformOp:translate (the centre) and xformOp:orient (quatf, real part first) time-sampled,
//   holding its shape about the centre (a Cube scaled to the box, or a Sphere).
// Metres, Y up, start and end time codes the first and last frame numbers. Writes `path`
// atomically, reading each frame once (an attribute's samples are kept in temporaries beside
// path until the stage is put together). Throws IoError naming the file that cannot be read or
// written, std::invalid_argument for no frames or bad options.
void writeUsdStage(const std::string& path, const std::vector<UsdFrame>& frames,
                   const UsdStageOptions& options);

}  // namespace weir
