// The lattice seeder on the host side and the CPU backend (CUDA: lattice_seeder_cuda.cu).
#include "scene/lattice_seeder.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/exec_cpu.h"
#include "scene/lattice_seeding.h"

namespace weir {

LatticeSeeder::LatticeSeeder(SceneSeeds seeds, Slab share, std::int64_t expected)
    : seeds_(std::move(seeds)), share_(share), expected_(expected) {
    if (!seeds_.seedableOnDevice()) {
        throw std::invalid_argument("mesh obstacles are seeded on the host only");
    }
}

double LatticeSeeder::maxSpeed() const {
    double fastest = 0;
    for (const SeedLattice& lattice : seeds_.lattices) {
        fastest = std::max(fastest, length(lattice.velocity));
    }
    return fastest;
}

std::shared_ptr<const ParticleSeeder> LatticeSeeder::within(const Slab& share,
                                                            std::int64_t expected) const {
    return std::make_shared<LatticeSeeder>(seeds_, share, expected);
}

void LatticeSeeder::sample(int axis, const std::function<void(double, std::int64_t)>& visit) const {
    // Every s-th lattice point along each axis, standing for s^3 points, about a million
    // samples in all.
    const SeedShapes shapes = seeds_.shapes();
    for (const SeedLattice& lattice : seeds_.lattices) {
        const std::int64_t s =
            std::max<std::int64_t>(1, std::int64_t(std::cbrt(double(lattice.points()) / 1e6)));
        for (std::int64_t k = s / 2; k < lattice.nz; k += s) {
            for (std::int64_t j = s / 2; j < lattice.ny; j += s) {
                for (std::int64_t i = s / 2; i < lattice.nx; i += s) {
                    const Vec3d x = lattice.point((k * lattice.ny + j) * lattice.nx + i);
                    if (keepSeed(shapes, lattice, x)) {
                        visit(axis == 0 ? x.x : (axis == 1 ? x.y : x.z), s * s * s);
                    }
                }
            }
        }
    }
}

void LatticeSeeder::seed(CpuExec& exec, ParticleStore<CpuExec>& store) const {
    seedLattices(exec, store, seeds_, share_);
}

#if !defined(WEIR_HAS_CUDA)
void LatticeSeeder::seed(CudaExec&, ParticleStore<CudaExec>&) const {
    throw std::logic_error("this weir was built without CUDA");
}
#endif

}  // namespace weir
