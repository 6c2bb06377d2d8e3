// A scene's lattice seeding as a ParticleSeeder (solver/simulation_setup.h): the simulation calls
// it to place its particles on its own backend.
#pragma once

#include <cstdint>
#include <memory>

#include "core/slab.h"
#include "scene/seeding.h"
#include "solver/simulation_setup.h"

namespace weir {

class LatticeSeeder final : public ParticleSeeder {
   public:
    // seeds: without mesh obstacles (seedableOnDevice); share: the slab to seed (all: every one),
    // expected: about how many particles that is.
    LatticeSeeder(SceneSeeds seeds, Slab share = {}, std::int64_t expected = -1);

    std::int64_t count() const override { return seeds_.count; }
    std::int64_t expectedCount() const override { return expected_ >= 0 ? expected_ : count(); }
    double maxSpeed() const override;
    std::shared_ptr<const ParticleSeeder> within(const Slab& share,
                                                 std::int64_t expected) const override;
    void sample(int axis, const std::function<void(double, std::int64_t)>& visit) const override;
    void seed(CpuExec& exec, ParticleStore<CpuExec>& store) const override;
    void seed(CudaExec& exec, ParticleStore<CudaExec>& store) const override;

    const SceneSeeds& seeds() const { return seeds_; }

   private:
    SceneSeeds seeds_;
    Slab share_;
    std::int64_t expected_;
};

}  // namespace weir
