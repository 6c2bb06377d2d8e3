// The force stage's two ways of walking neighbours give the same sum.
#include <gtest/gtest.h>

#include <vector>

#include "core/exec_cpu.h"
#include "grid/dense_grid.h"
#include "physics/stages.h"
#include "solver/solver_test_support.h"

namespace weir {
namespace {

TEST(ForceStage, CollectedNeighboursGiveTheSameAccelerationAsImmediateOnes) {
    // A dam break a few steps in, so that particles sit off the lattice.
    auto sim = testing::start(testing::smallDamBreak(3000), Backend::Cpu, NeighbourMode::Dense);
    const HostParticles state = testing::stateAfter(*sim, 40);
    const SphParams params = sim->params();
    const SimulationSetup setup = buildSetup(testing::smallDamBreak(3000), {}, nullptr);

    const Index n = Index(state.size());
    const std::size_t count = static_cast<std::size_t>(n);
    std::vector<Real4> unsorted(count), pos(count), vel(count);
    for (Index i = 0; i < n; ++i) {
        unsorted[std::size_t(i)] = {state.x[i], state.y[i], state.z[i], 0};
    }
    CpuExec exec;
    DenseGrid<CpuExec> grid(denseGridSpec(setup.grid, 2), 2);
    grid.build(exec, unsorted.data(), n);
    for (Index k = 0; k < n; ++k) {
        const Index from = grid.permutation()[k];
        pos[std::size_t(k)] = unsorted[std::size_t(from)];
        vel[std::size_t(k)] = {state.vx[from], state.vy[from], state.vz[from], 0};
    }
    const ParticleView pv{pos.data(), vel.data(), nullptr, n, BoundaryView{}};
    const DenseGridNeighbours nb = grid.view(pos.data(), params.kernel.h);
    for (Index i = 0; i < n; ++i) {
        densityPressureAt(i, pv, nb, params);
    }

    int overfull = 0;  // particles with more neighbours than the smallest list holds
    for (Index i = 0; i < n; ++i) {
        const Vec3 immediate = accelerationOf(i, pv, nb, params, 0);
        int neighbours = 0;
        nb.forEachCandidate(i, [&](Index j) {
            const Real r2 = lengthSquared(pv.position(i) - pv.position(j));
            neighbours += r2 < params.kernel.h2 && r2 > 0 ? 1 : 0;
        });
        overfull += neighbours > 5 ? 1 : 0;
        for (int capacity : {5, 32, PendingNeighbours::kHostCapacity}) {
            const Vec3 collected = accelerationOf(i, pv, nb, params, capacity);
            ASSERT_EQ(collected.x, immediate.x) << "particle " << i << ", list of " << capacity;
            ASSERT_EQ(collected.y, immediate.y) << "particle " << i << ", list of " << capacity;
            ASSERT_EQ(collected.z, immediate.z) << "particle " << i << ", list of " << capacity;
        }
    }
    // The small list overflowed and was evaluated part by part for most particles.
    EXPECT_GT(overfull, n / 2);
}

}  // namespace
}  // namespace weir
