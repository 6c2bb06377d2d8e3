// Seeding on a simulation's own backend (on the GPU for a CUDA run, so a billion particles need
// no host arrays): the rule of scene/seeding.h run for every lattice point in parallel, in the
// same order as on the host, so every particle gets the same id either way.
#pragma once

#include <algorithm>
#include <cstdint>
#include <string>

#include "core/check.h"
#include "core/slab.h"
#include "scene/seeding.h"
#include "solver/particle_store.h"

namespace weir {

// Creates the particles of `seeds` inside `share` in `store`, with their index in the host's
// order as id: per lattice, in chunks, a keep flag per point and a prefix sum of the flags (the
// global order), a second flag and sum for the points in the share (their place here), and each
// kept point written at its place. A first pass counts the share.
template <class Exec>
void seedLattices(Exec& exec, ParticleStore<Exec>& store, const SceneSeeds& seeds,
                  const Slab& share) {
    using IndexBuffer = typename Exec::template Buffer<Index>;
    typename Exec::template Buffer<Box> fluidBoxes, obstacleBoxes;
    typename Exec::template Buffer<SphereShape> fluidSpheres, obstacleSpheres;
    exec.upload(fluidBoxes, seeds.fluidBoxes.data(), seeds.fluidBoxes.size());
    exec.upload(obstacleBoxes, seeds.obstacleBoxes.data(), seeds.obstacleBoxes.size());
    exec.upload(fluidSpheres, seeds.fluidSpheres.data(), seeds.fluidSpheres.size());
    exec.upload(obstacleSpheres, seeds.obstacleSpheres.data(), seeds.obstacleSpheres.size());
    const SeedShapes shapes{
        fluidBoxes.data(),        int(fluidBoxes.size()),      fluidSpheres.data(),
        int(fluidSpheres.size()), obstacleBoxes.data(),        int(obstacleBoxes.size()),
        obstacleSpheres.data(),   int(obstacleSpheres.size()), seeds.clearance};
    const bool whole = share.everything();
    constexpr std::int64_t kChunk = std::int64_t(1) << 26;
    IndexBuffer kept, mine;
    Index placed = 0, counted = 0, n = 0;
    for (int pass = whole ? 1 : 0; pass < 2; ++pass) {
        if (pass == 1) {
            n = whole ? Index(seeds.count) : counted;
            // A share gets ghosts and arrivals every step: room for them from the start, so that
            // the arrays need not grow (and be held twice) later.
            store.allocate(n, whole ? 0 : std::size_t(n) / 8);
        }
        Real4 *pos = store.pos(), *vel = store.vel();
        Index* id = store.id();
        Index global = 0;
        placed = 0;
        for (const SeedLattice& lattice : seeds.lattices) {
            for (std::int64_t start = 0; start < lattice.points(); start += kChunk) {
                const Index count = Index(std::min(kChunk, lattice.points() - start));
                kept.resize(std::size_t(std::min(kChunk, lattice.points())));
                mine.resize(whole ? 0 : kept.size());
                Index* flag = kept.data();
                Index* local = whole ? flag : mine.data();
                exec.forEach(count, [=] WEIR_HD(Index k) {
                    const Vec3d p = lattice.point(start + k);
                    const bool keep = keepSeed(shapes, lattice, p);
                    flag[k] = keep ? 1 : 0;
                    if (!whole) {
                        local[k] = keep && share.contains(share.coordinate(p)) ? 1 : 0;
                    }
                });
                if (pass == 0) {
                    exec.inclusiveScan(local, local, count);
                    counted += exec.readOne(mine, std::size_t(count - 1));
                    continue;
                }
                exec.inclusiveScan(flag, flag, count);
                if (!whole) {
                    exec.inclusiveScan(local, local, count);
                }
                const Index globalBase = global, localBase = placed, limit = n;
                exec.forEach(count, [=] WEIR_HD(Index k) {
                    const Index before = k > 0 ? local[k - 1] : 0;
                    const Index at = localBase + before;
                    if (local[k] > before && at < limit) {
                        const Vec3d p = lattice.point(start + k);
                        pos[at] = {Real(p.x), Real(p.y), Real(p.z), 0};
                        vel[at] = {Real(lattice.velocity.x), Real(lattice.velocity.y),
                                   Real(lattice.velocity.z), Real(lattice.densityAt(p))};
                        id[at] = globalBase + (k > 0 ? flag[k - 1] : 0);
                    }
                });
                global += exec.readOne(kept, std::size_t(count - 1));
                placed += whole ? exec.readOne(kept, std::size_t(count - 1))
                                : exec.readOne(mine, std::size_t(count - 1));
            }
        }
        if (pass == 1 && global != Index(seeds.count)) {
            throw SimulationError("seeding placed " + std::to_string(global) +
                                  " particles where the host counted " +
                                  std::to_string(seeds.count));
        }
    }
    if (placed != n) {
        throw SimulationError("seeding placed " + std::to_string(placed) +
                              " particles where the count pass found " + std::to_string(n));
    }
}

}  // namespace weir
