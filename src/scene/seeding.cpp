// Seeding on the host: the lattices of a scene and how many particles they keep.
#include "scene/seeding.h"

#include <cmath>

#include "scene/boundary.h"

namespace weir {

namespace {

bool boxesOverlap(const Box& a, const Box& b) {
    return a.min.x < b.max.x && b.min.x < a.max.x && a.min.y < b.max.y && b.min.y < a.max.y &&
           a.min.z < b.max.z && b.min.z < a.max.z;
}
Box boundsOf(const SphereShape& s) {
    const Vec3d r(s.radius, s.radius, s.radius);
    return {s.center - r, s.center + r};
}

// Whether every point of a block's lattice is kept: nothing else overlaps the block.
bool blockStandsAlone(const SceneSeeds& seeds, std::size_t block) {
    const Box& box = seeds.fluidBoxes[block];
    for (const Box& b : seeds.obstacleBoxes) {
        if (boxesOverlap(box, b)) {
            return false;
        }
    }
    for (const SphereShape& s : seeds.obstacleSpheres) {
        if (boxesOverlap(box, boundsOf(s))) {
            return false;
        }
    }
    for (std::size_t b = 0; b < block; ++b) {
        if (boxesOverlap(box, seeds.fluidBoxes[b])) {
            return false;
        }
    }
    return true;
}

}  // namespace

bool insideObstacleMesh(const SceneSeeds& seeds, const Vec3d& p) {
    for (const MeshObstacle& mesh : seeds.obstacleMeshes) {
        if (insideMesh(mesh, p)) {
            return true;
        }
    }
    return false;
}

SeedShapes SceneSeeds::shapes() const {
    return {fluidBoxes.data(),        int(fluidBoxes.size()),     fluidSpheres.data(),
            int(fluidSpheres.size()), obstacleBoxes.data(),       int(obstacleBoxes.size()),
            obstacleSpheres.data(),   int(obstacleSpheres.size())};
}

SceneSeeds sceneSeeds(const Scene& scene, double d) {
    SceneSeeds seeds;
    for (const FluidBlock& b : scene.blocks) {
        seeds.fluidBoxes.push_back(b.box);
    }
    for (const FluidSphere& s : scene.spheres) {
        seeds.fluidSpheres.push_back(s.sphere);
    }
    seeds.obstacleBoxes = scene.obstacleBoxes;
    seeds.obstacleSpheres = scene.obstacleSpheres;
    seeds.obstacleMeshes = scene.obstacleMeshes;
    auto lattice = [&](const Box& bounds, const Vec3d& velocity, int shape) {
        SeedLattice l;
        l.lo = bounds.min;
        l.spacing = d;
        l.nx = std::int64_t(std::floor((bounds.max.x - bounds.min.x) / d + 1e-9));
        l.ny = std::int64_t(std::floor((bounds.max.y - bounds.min.y) / d + 1e-9));
        l.nz = std::int64_t(std::floor((bounds.max.z - bounds.min.z) / d + 1e-9));
        l.shape = shape;
        l.velocity = velocity;
        if (l.points() > 0) {
            seeds.lattices.push_back(l);
        }
    };
    for (std::size_t b = 0; b < scene.blocks.size(); ++b) {
        lattice(scene.blocks[b].box, scene.blocks[b].velocity, int(b));
    }
    for (std::size_t s = 0; s < scene.spheres.size(); ++s) {
        lattice(boundsOf(scene.spheres[s].sphere), scene.spheres[s].velocity,
                int(scene.blocks.size() + s));
    }
    const SeedShapes shapes = seeds.shapes();
    for (const SeedLattice& l : seeds.lattices) {
        if (l.shape < shapes.fluidBoxCount && seeds.obstacleMeshes.empty() &&
            blockStandsAlone(seeds, std::size_t(l.shape))) {
            seeds.count += l.points();
            continue;
        }
        std::int64_t kept = 0;
        const std::int64_t points = l.points();
#pragma omp parallel for reduction(+ : kept) schedule(static)
        for (std::int64_t k = 0; k < points; ++k) {
            const Vec3d p = l.point(k);
            kept += keepSeed(shapes, l, p) && !insideObstacleMesh(seeds, p) ? 1 : 0;
        }
        seeds.count += kept;
    }
    return seeds;
}

}  // namespace weir
