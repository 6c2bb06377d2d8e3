// Where the initial particles go: each fluid block or sphere filled with a cubic lattice, less the
// points inside obstacles or within half a spacing of one, or inside an earlier shape. The rule is
// written once, for the host and the device, so a run of a billion particles can be seeded on the
// GPU itself, in the same order as on the host.
#pragma once

#include <cstdint>
#include <type_traits>
#include <vector>

#include "core/config.h"
#include "core/vec3.h"
#include "scene/scene.h"

namespace weir {

WEIR_HD inline bool insideBox(const Vec3d& p, const Box& b) {
    return p.x >= b.min.x && p.x < b.max.x && p.y >= b.min.y && p.y < b.max.y && p.z >= b.min.z &&
           p.z < b.max.z;
}
WEIR_HD inline bool insideSphere(const Vec3d& p, const SphereShape& s) {
    return lengthSquared(p - s.center) < s.radius * s.radius;
}

// The scene's shapes as plain arrays (host or device memory). Fluid shapes are numbered blocks
// first, then spheres.
struct SeedShapes {
    const Box* fluidBoxes = nullptr;
    int fluidBoxCount = 0;
    const SphereShape* fluidSpheres = nullptr;
    int fluidSphereCount = 0;
    const Box* obstacleBoxes = nullptr;
    int obstacleBoxCount = 0;
    const SphereShape* obstacleSpheres = nullptr;
    int obstacleSphereCount = 0;
    // How far fluid starts from an obstacle's surface: half a spacing, as from the container's
    // walls (a block seeded against a wall has its first layer d/2 from it), where the boundary
    // particles d/2 inside the obstacle see the lattice continued. Closer, a particle starts
    // overdense against them (0.0008 m from a box's face at d = 0.011: 1106 kg/m^3, 334 kPa,
    // and a 7.9 m/s jet at t = 0).
    double clearance = 0;
};

// The squared distance from p to box b (0 inside).
WEIR_HD inline double distanceSquaredToBox(const Vec3d& p, const Box& b) {
    double sum = 0;
    for (int a = 0; a < 3; ++a) {
        const double out =
            p[a] < b.min[a] ? b.min[a] - p[a] : (p[a] > b.max[a] ? p[a] - b.max[a] : 0);
        sum += out * out;
    }
    return sum;
}

// The lattice over one fluid shape's bounding box: points lo + (i + 1/2, j + 1/2, k + 1/2) d,
// numbered i fastest, then j, then k.
struct SeedLattice {
    Vec3d lo;
    double spacing = 0;
    std::int64_t nx = 0, ny = 0, nz = 0;
    int shape = 0;  // fluid shape number
    Vec3d velocity;
    // The density it starts at: densityAtTop + densityPerDepth (top - x . up) below `top`.
    Vec3d up{0, 1, 0};
    double top = 0, densityAtTop = 0, densityPerDepth = 0;

    WEIR_HD double densityAt(const Vec3d& p) const {
        const double depth = top - dot(p, up);
        return densityAtTop + densityPerDepth * (depth > 0 ? depth : 0);
    }

    WEIR_HD std::int64_t points() const { return nx * ny * nz; }
    WEIR_HD Vec3d point(std::int64_t index) const {
        const std::int64_t i = index % nx, rest = index / nx;
        const std::int64_t j = rest % ny, k = rest / ny;
        return {lo.x + (double(i) + 0.5) * spacing, lo.y + (double(j) + 0.5) * spacing,
                lo.z + (double(k) + 0.5) * spacing};
    }
};

// Whether lattice point p of `lattice` becomes a particle: inside its shape, outside every
// obstacle and at least the clearance from it, and not already taken by an earlier shape.
WEIR_HD inline bool keepSeed(const SeedShapes& shapes, const SeedLattice& lattice, const Vec3d& p) {
    const int sphere = lattice.shape - shapes.fluidBoxCount;  // >= 0 for a fluid sphere
    if (sphere >= 0 && !insideSphere(p, shapes.fluidSpheres[sphere])) {
        return false;
    }
    const double clear2 = shapes.clearance * shapes.clearance;
    for (int b = 0; b < shapes.obstacleBoxCount; ++b) {
        if (insideBox(p, shapes.obstacleBoxes[b]) ||
            distanceSquaredToBox(p, shapes.obstacleBoxes[b]) < clear2) {
            return false;
        }
    }
    for (int s = 0; s < shapes.obstacleSphereCount; ++s) {
        const SphereShape& o = shapes.obstacleSpheres[s];
        if (insideSphere(p, {o.center, o.radius + shapes.clearance})) {
            return false;
        }
    }
    const int earlierBoxes =
        lattice.shape < shapes.fluidBoxCount ? lattice.shape : shapes.fluidBoxCount;
    for (int b = 0; b < earlierBoxes; ++b) {
        if (insideBox(p, shapes.fluidBoxes[b])) {
            return false;
        }
    }
    for (int s = 0; s < sphere; ++s) {
        if (insideSphere(p, shapes.fluidSpheres[s])) {
            return false;
        }
    }
    return true;
}

// A scene's seeding at one spacing, on the host: its shapes and one lattice per fluid shape.
// Triangle-mesh obstacles are tested on the host only: a scene with them is seeded there.
struct SceneSeeds {
    std::vector<Box> fluidBoxes, obstacleBoxes;
    std::vector<SphereShape> fluidSpheres, obstacleSpheres;
    std::vector<MeshObstacle> obstacleMeshes;
    double clearance = 0;  // SeedShapes::clearance
    std::vector<SeedLattice> lattices;
    std::int64_t count = 0;  // particles the lattices keep
    // Counting stopped past the limit sceneSeeds was given: count is then at least the limit
    // (estimated, from a coarser lattice, or counted until past it); lattices may be incomplete.
    bool overLimit = false;
    // With overLimit: the particles estimated, as a double (the lattice points of lone blocks,
    // exact; past 1e18 lattice points, their number, as no integer holds it).
    double estimate = 0;

    bool empty() const { return lattices.empty(); }
    // Whether a backend can seed these without the host (no mesh obstacles).
    bool seedableOnDevice() const { return obstacleMeshes.empty(); }
    // The shapes, in this object's host memory.
    SeedShapes shapes() const;
};

// Particles a scene may have: particle ids and counts are 32-bit.
constexpr std::int64_t kMaxParticles = 2147483647;

// The seeding of `scene` at spacing d, with its particle count (in closed form for a block that
// no obstacle or earlier shape touches, else counted in parallel). Counting stops once past
// `limit` (overLimit): a lattice far larger is estimated from a coarser one first, so that a too
// fine spacing fails in well under a second. Throws SceneError for a lattice too large to count
// that would keep less than the limit (a huge block mostly inside obstacles).
SceneSeeds sceneSeeds(const Scene& scene, double spacing, std::int64_t limit = kMaxParticles);

// Whether p lies inside one of the seeds' mesh obstacles or closer than the clearance to one
// (host only).
bool insideObstacleMesh(const SceneSeeds& seeds, const Vec3d& p);

// Calls visit(position, velocity) or visit(position, velocity, density) for every kept lattice
// point, in order: shape by shape, each lattice in its own order.
template <class F>
void forEachSeed(const SceneSeeds& seeds, F&& visit) {
    const SeedShapes shapes = seeds.shapes();
    for (const SeedLattice& lattice : seeds.lattices) {
        for (std::int64_t k = 0; k < lattice.points(); ++k) {
            const Vec3d p = lattice.point(k);
            if (keepSeed(shapes, lattice, p) && !insideObstacleMesh(seeds, p)) {
                if constexpr (std::is_invocable_v<F, const Vec3d&, const Vec3d&, double>) {
                    visit(p, lattice.velocity, lattice.densityAt(p));
                } else {
                    visit(p, lattice.velocity);
                }
            }
        }
    }
}

}  // namespace weir
