// What the water look's rays meet: the fluid's surface (a triangle mesh, smooth-shaded with its
// vertex normals), the obstacles and rigid bodies as matte triangles, all in one hierarchy; and,
// analytically, the floor (an endless checkered plane at the container's bottom) and the
// container's far walls.
#pragma once

#include <cstdint>
#include <vector>

#include "raytrace/bvh.h"
#include "scene/scene.h"
#include "solver/particles.h"
#include "surface/triangle_mesh.h"
#include "whitewater/diffuse_particles.h"

namespace weir {

// Whitewater: the spray, foam and bubbles of whitewater/, a small matte octahedron each.
enum class TriangleKind : std::uint32_t { Water = 0, Obstacle = 1, Body = 2, Whitewater = 3 };

// A triangle's vertex normals (unit; for matte flat triangles all three the face's) and kind.
struct TriangleShading {
    Vec3f n0, n1, n2;
    TriangleKind kind = TriangleKind::Water;
};

// Bits of TracingSceneView::walls: the container's side walls (x and z, low and high). The floor
// is always there, the top never.
constexpr std::uint32_t wallBit(int axis, int side) { return 1U << (2 * axis + side); }

// The side walls the camera sees from inside (TracingSceneView::walls): those whose outside
// faces away from the eye; the others are cut away.
std::uint32_t wallsSeenFrom(const Box& container, const Vec3d& eye);

// The scene in the memory of the backend that traces it: plain pointers, passed by value.
struct TracingSceneView {
    BvhView bvh;
    const TriangleShading* shading = nullptr;  // per triangle, in the hierarchy's order
    Vec3f containerLo, containerHi;
    std::uint32_t walls = 0;   // wallBit(axis, side) for each side wall that is there
    float rayEpsilon = 1e-5f;  // how far a new ray starts off the surface it leaves [m]
};

struct TracingSceneDescription {
    const TriangleMesh* water = nullptr;  // the fluid's surface; null: no fluid
    Box container;
    std::vector<Box> obstacleBoxes;
    std::vector<SphereShape> obstacleSpheres;
    std::vector<MeshObstacle> obstacleMeshes;
    std::vector<BodySpec> bodies;     // drawn where their poses are given
    std::vector<BodyPose> bodyPoses;  // this frame's
    // A side wall is left out where the camera sees its outside (a cut-away: the camera looks
    // into the container through the walls nearest to it).
    Vec3d cameraEye;
    // Faces of the fluid's surface that lie within this distance of the floor or of a wall that
    // is there, and face it, are where the fluid touches the container: left out, so that the
    // water meets the floor and walls directly instead of through a film of air. 0: none left out.
    double contactDistance = 0;
    // This frame's spray, foam and bubbles (null: none), drawn as octahedra reaching
    // whitewaterSize (foam), 0.7x it (spray) and 0.5x it (bubbles) from their centres [m].
    const DiffuseParticles* whitewater = nullptr;
    double whitewaterSize = 0;
};

class TracingScene {
   public:
    explicit TracingScene(const TracingSceneDescription& description);

    TracingSceneView view() const;  // in host memory
    const Bvh& bvh() const { return bvh_; }
    const std::vector<TriangleShading>& shading() const { return shading_; }
    std::size_t waterTriangles() const { return waterTriangles_; }
    std::size_t contactTrianglesLeftOut() const { return contactTrianglesLeftOut_; }

   private:
    Bvh bvh_;
    std::vector<TriangleShading> shading_;
    TracingSceneView view_;
    std::size_t waterTriangles_ = 0;
    std::size_t contactTrianglesLeftOut_ = 0;
};

}  // namespace weir
