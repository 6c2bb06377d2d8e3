// Boundary particles for the container walls and the obstacles (physics/boundary.h): sampling,
// Akinci's volumes psi and the static grid, built once on the host at set-up.
#pragma once

#include <array>
#include <vector>

#include "physics/boundary.h"
#include "scene/scene.h"

namespace weir {

// Samples the walls and obstacles at spacing d (only within 2 h and the layers of the container:
// an obstacle that sticks out is sampled where fluid can feel it): the container's faces d/2
// outside its walls and each obstacle's surface d/2 inside it, so that the first fluid layer
// (seeded d/2 from a wall) sits one spacing from the boundary layer, as in the fluid lattice; and
// further layers d apart as far as a fluid particle at the wall can see (boundaryLayers: 1 at h =
// 2d, 2 at h = 3d). Points closer than d/2 to an earlier one are dropped (box edges, shared mesh
// edges).
std::vector<Vec3d> sampleBoundary(const Scene& scene, double d, double h);
// Layers of boundary particles for smoothing radius h and spacing d: as many as the kernel
// reaches past the first (1 at h = 2d, 2 at h = 3d), or with fullSupport every layer a fluid
// particle closer than d/2 to the wall can reach (2 at h = 2d: the delta-SPH model's walls
// stand for the fluid beyond them, Adami et al. 2012, and fill the whole support).
int boundaryLayers(double h, double d, bool fullSupport = false);

// The sampled points with the container face each stands for (0..5 as -x, +x, -y, +y, -z, +z;
// -1: an obstacle).
struct BoundarySamples {
    std::vector<Vec3d> points;
    std::vector<int> faces;
    std::size_t size() const { return points.size(); }
};
BoundarySamples sampleBoundary(const Scene& scene, double d, double h, int layers);
// A rigid body's surface (scene.h's BodySpec), sampled as an obstacle's: `layers` layers from d/2
// inside it, in world coordinates at its starting place; faces all -1.
BoundarySamples sampleBodySurface(const BodySpec& body, double d, int layers);
// An upper bound on the points sampleBoundary visits (before close ones are dropped), in closed
// form per box and sphere and one step per row of each mesh triangle: memory can be checked
// before sampling. Throws SceneError for a mesh triangle too large to sample (naming the mesh).
double boundarySampleBound(const Scene& scene, double d, double h, int layers);

// The kernel whose sums give Akinci's volumes: the paper model's poly6 or delta-SPH's Wendland.
enum class BoundaryKernel { Poly6, Wendland };

// psi_b = rho0 / sum_k W_bk for each point (Akinci et al. 2012, the boundary's own density sum),
// capped at rho0 * fullVolume, the volume of a particle with a full neighbourhood
// (d^3 / lattice sum of poly6, as the fluid's mass). The cap matters at the layer facing the
// fluid: its own sum misses the half-space that the fluid fills, so uncapped it weighs 1.5 to 2
// times a fluid particle and the first fluid layer starts that much overdense; measured, it
// throws a tank at rest off its floor. Deeper layers and dense samplings (curved obstacles,
// meshes) keep Akinci's value. The points are sorted into a grid of h-wide cells covering the
// container and one cell of margin.
BoundaryParticles buildBoundary(const std::vector<Vec3d>& points, const Box& container, double h,
                                double restDensity, double fullVolume);
// The same from samples, by `kernel`; faceVelocity: the velocity
// of each container face's particles (null: every wall at rest).
BoundaryParticles buildBoundary(const BoundarySamples& samples, const Box& container, double h,
                                double restDensity, double fullVolume, BoundaryKernel kernel,
                                const std::array<Vec3d, 6>* faceVelocity = nullptr);

// Whether p lies inside the closed triangle mesh (ray parity along +x); through mesh.index when
// it is built (only the triangles under the ray are tested), else every triangle.
bool insideMesh(const MeshObstacle& mesh, const Vec3d& p);
// Whether p lies closer than `distance` to the mesh's surface (through mesh.index when built).
bool nearMesh(const MeshObstacle& mesh, const Vec3d& p, double distance);
// Builds mesh.index (once per mesh: the scene reader does it, and copies share it).
void buildMeshIndex(MeshObstacle& mesh);

}  // namespace weir
