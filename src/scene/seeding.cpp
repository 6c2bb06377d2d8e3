// Seeding on the host: the lattices of a scene and how many particles they keep.
#include "scene/seeding.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

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
    const Vec3d clear(seeds.clearance, seeds.clearance, seeds.clearance);
    for (const Box& b : seeds.obstacleBoxes) {
        if (boxesOverlap(box, {b.min - clear, b.max + clear})) {
            return false;
        }
    }
    for (const SphereShape& s : seeds.obstacleSpheres) {
        if (boxesOverlap(box, boundsOf({s.center, s.radius + seeds.clearance}))) {
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
        if (insideMesh(mesh, p) || nearMesh(mesh, p, seeds.clearance)) {
            return true;
        }
    }
    return false;
}

SeedShapes SceneSeeds::shapes() const {
    return {fluidBoxes.data(),        int(fluidBoxes.size()),      fluidSpheres.data(),
            int(fluidSpheres.size()), obstacleBoxes.data(),        int(obstacleBoxes.size()),
            obstacleSpheres.data(),   int(obstacleSpheres.size()), clearance};
}

namespace {

// "blocks[1]" or "spheres[0]": a fluid shape by its scene field.
std::string shapeName(const SceneSeeds& seeds, int shape) {
    const int blocks = int(seeds.fluidBoxes.size());
    return shape < blocks ? "blocks[" + std::to_string(shape) + "]"
                          : "spheres[" + std::to_string(shape - blocks) + "]";
}

// Lattice points of a shape tested at most (about a minute on one core); past it, a scene must
// fit its blocks and spheres closer to the fluid.
constexpr double kMaxTestedPoints = 8589934592.0;  // 2^33
// Points tested to estimate a large lattice's count.
constexpr double kEstimatePoints = 4194304.0;  // 2^22

// Points of lattice l kept, tested on every stride-th point along each axis and scaled up.
double estimateKept(const SceneSeeds& seeds, const SeedShapes& shapes, const SeedLattice& l) {
    const std::int64_t stride = std::max<std::int64_t>(
        1, std::int64_t(std::ceil(std::cbrt(double(l.points()) / kEstimatePoints))));
    const std::int64_t sx = (l.nx + stride - 1) / stride, sy = (l.ny + stride - 1) / stride,
                       sz = (l.nz + stride - 1) / stride;
    const std::int64_t samples = sx * sy * sz;
    std::int64_t kept = 0;
#pragma omp parallel for reduction(+ : kept) schedule(static)
    for (std::int64_t k = 0; k < samples; ++k) {
        const std::int64_t i = (k % sx) * stride, j = (k / sx % sy) * stride,
                           m = (k / sx / sy) * stride;
        const Vec3d p = l.point(i + l.nx * (j + l.ny * m));
        kept += keepSeed(shapes, l, p) && !insideObstacleMesh(seeds, p) ? 1 : 0;
    }
    return double(kept) / double(samples) * double(l.points());
}

}  // namespace

SceneSeeds sceneSeeds(const Scene& scene, double d, std::int64_t limit) {
    SceneSeeds seeds;
    for (const FluidBlock& b : scene.blocks) {
        seeds.fluidBoxes.push_back(b.box);
    }
    for (const FluidSphere& s : scene.spheres) {
        seeds.fluidSpheres.push_back(s.sphere);
    }
    seeds.obstacleBoxes = scene.obstacleBoxes;
    seeds.obstacleSpheres = scene.obstacleSpheres;
    // Half a spacing, less round-off: a point d/2 from a face is kept (scene/seeding.h).
    seeds.clearance = d * (0.5 - 1e-6);
    seeds.obstacleMeshes = scene.obstacleMeshes;
    for (const BodySpec& body : scene.bodies) {  // fluid starts clear of the bodies too
        if (body.isMesh) {
            seeds.obstacleMeshes.push_back(body.mesh);
        } else if (body.isSphere) {
            seeds.obstacleSpheres.push_back(body.sphere);
        } else {
            seeds.obstacleBoxes.push_back(body.box);
        }
    }
    for (MeshObstacle& mesh : seeds.obstacleMeshes) {
        if (!mesh.index) {
            buildMeshIndex(mesh);
        }
    }
    double latticePoints = 0;  // all lattices', in a double: it may not fit an integer
    auto lattice = [&](const Box& bounds, const Vec3d& velocity, int shape) {
        double n[3];
        for (int a = 0; a < 3; ++a) {
            n[a] = std::max(0.0, std::floor((bounds.max[a] - bounds.min[a]) / d + 1e-9));
        }
        const double points = n[0] * n[1] * n[2];
        latticePoints += points;
        if (!(points > 0) || !(latticePoints <= 1e18)) {  // 1e18: its integers fit an int64
            return;
        }
        SeedLattice l;
        l.lo = bounds.min;
        l.spacing = d;
        l.nx = std::int64_t(n[0]);
        l.ny = std::int64_t(n[1]);
        l.nz = std::int64_t(n[2]);
        l.shape = shape;
        l.velocity = velocity;
        seeds.lattices.push_back(l);
    };
    for (std::size_t b = 0; b < scene.blocks.size(); ++b) {
        lattice(scene.blocks[b].box, scene.blocks[b].velocity, int(b));
    }
    for (std::size_t s = 0; s < scene.spheres.size(); ++s) {
        lattice(boundsOf(scene.spheres[s].sphere), scene.spheres[s].velocity,
                int(scene.blocks.size() + s));
    }
    if (!(latticePoints <= 1e18)) {
        seeds.overLimit = true;
        seeds.count = std::numeric_limits<std::int64_t>::max();
        seeds.estimate = latticePoints;
        return seeds;
    }
    const SeedShapes shapes = seeds.shapes();
    // Closed form where it is exact, then estimates of the large lattices: past the limit, the
    // scene fails before anything is counted point by point.
    std::vector<bool> counted(seeds.lattices.size(), false);
    double estimate = 0;
    for (std::size_t n = 0; n < seeds.lattices.size(); ++n) {
        const SeedLattice& l = seeds.lattices[n];
        if (l.shape < shapes.fluidBoxCount && seeds.obstacleMeshes.empty() &&
            blockStandsAlone(seeds, std::size_t(l.shape))) {
            seeds.count += l.points();
            estimate += double(l.points());
            counted[n] = true;
        } else if (double(l.points()) > 4 * kEstimatePoints) {  // small ones: counted below
            estimate += estimateKept(seeds, shapes, l);
        }
    }
    if (estimate > 1.05 * double(limit)) {
        seeds.overLimit = true;
        seeds.count = std::int64_t(std::min(estimate, 9e18));
        seeds.estimate = estimate;
        return seeds;
    }
    for (std::size_t n = 0; n < seeds.lattices.size() && seeds.count <= limit; ++n) {
        const SeedLattice& l = seeds.lattices[n];
        if (counted[n]) {
            continue;
        }
        if (double(l.points()) > kMaxTestedPoints) {
            throw SceneError(
                "scene '" + scene.sourcePath + "': " + shapeName(seeds, l.shape) + " spans " +
                std::to_string(l.points()) + " lattice points at spacing " + std::to_string(d) +
                " m, more than the " + std::to_string(std::int64_t(kMaxTestedPoints)) +
                " weir tests one by one, for about " + std::to_string(std::int64_t(estimate)) +
                " particles; make it fit the fluid more closely (obstacles take most "
                "of it) or use a larger particles.spacing");
        }
        // In chunks, so that counting stops soon after the limit.
        constexpr std::int64_t kChunk = std::int64_t(1) << 24;
        for (std::int64_t start = 0; start < l.points() && seeds.count <= limit; start += kChunk) {
            const std::int64_t end = std::min(l.points(), start + kChunk);
            std::int64_t kept = 0;
#pragma omp parallel for reduction(+ : kept) schedule(static)
            for (std::int64_t k = start; k < end; ++k) {
                const Vec3d p = l.point(k);
                kept += keepSeed(shapes, l, p) && !insideObstacleMesh(seeds, p) ? 1 : 0;
            }
            seeds.count += kept;
        }
    }
    seeds.overLimit = seeds.count > limit;
    seeds.estimate = double(seeds.count);
    return seeds;
}

}  // namespace weir
