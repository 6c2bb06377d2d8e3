// Slab decomposition, particle routing and message packing, without MPI; and a one-rank
// distributed run against the plain solver.
#include "cluster/decomposition.h"

#include <gtest/gtest.h>

#include <cmath>

#include "cluster/distributed_simulation.h"
#include "cluster/particle_routing.h"
#include "solver/solver_test_support.h"

namespace weir {
namespace {

AxisHistogram uniformHistogram(int bins, std::int64_t perBin) {
    AxisHistogram h;
    h.axis = 0;
    h.lo = 0;
    h.binWidth = 0.1;
    h.counts.assign(std::size_t(bins), perBin);
    return h;
}

ParticleBatch particlesAt(const std::vector<double>& xs) {
    ParticleBatch b;
    for (std::size_t k = 0; k < xs.size(); ++k) {
        b.pos.push_back({Real(xs[k]), 0, 0, 0});
        b.vel.push_back({0, 0, 0, 1000});
        b.id.push_back(Index(k));
    }
    return b;
}

TEST(Decomposition, EqualCountsGiveEqualSlabs) {
    const Decomposition d = balancedDecomposition(uniformHistogram(100, 7), 4);
    ASSERT_EQ(d.ranks(), 4);
    EXPECT_NEAR(d.innerBorders()[0], 2.5, 1e-9);
    EXPECT_NEAR(d.innerBorders()[1], 5.0, 1e-9);
    EXPECT_NEAR(d.innerBorders()[2], 7.5, 1e-9);
    EXPECT_EQ(d.slab(0).lo, -INFINITY);
    EXPECT_EQ(d.slab(3).hi, INFINITY);
    EXPECT_EQ(d.slab(1).lo, d.slab(0).hi);
}

TEST(Decomposition, FollowsTheParticles) {
    // All particles in the first fifth (a dam break's column): every border lies inside it.
    AxisHistogram h = uniformHistogram(100, 0);
    for (int b = 0; b < 20; ++b) {
        h.counts[std::size_t(b)] = 50;
    }
    const Decomposition d = balancedDecomposition(h, 2);
    EXPECT_NEAR(d.innerBorders()[0], 1.0, 1e-9);
    EXPECT_NEAR(imbalance(countsPerRank(h, d)), 1.0, 1e-9);
    // Equal-width slabs would leave rank 1 empty: imbalance 2.
    EXPECT_NEAR(imbalance(countsPerRank(h, Decomposition(0, {5.0}))), 2.0, 1e-9);
}

TEST(Decomposition, NoParticlesGivesEqualWidths) {
    const Decomposition d = balancedDecomposition(uniformHistogram(10, 0), 2);
    EXPECT_NEAR(d.innerBorders()[0], 0.5, 1e-9);
    EXPECT_EQ(imbalance({0, 0}), 1.0);
}

TEST(Decomposition, OwnerOfEveryCoordinate) {
    const Decomposition d(2, {1.0, 1.0, 3.0});  // rank 1's slab is empty
    EXPECT_EQ(d.ownerOf(-5.0, 0), 0);
    EXPECT_EQ(d.ownerOf(0.999, 0), 0);
    EXPECT_EQ(d.ownerOf(1.0, 0), 2);  // [1, 1) holds nothing
    EXPECT_EQ(d.ownerOf(2.5, 0), 2);
    EXPECT_EQ(d.ownerOf(3.0, 0), 3);
    EXPECT_EQ(d.ownerOf(NAN, 1), 1);
    EXPECT_THROW(Decomposition(0, {2.0, 1.0}), std::invalid_argument);
    EXPECT_EQ(longestAxis({0, 0, 0}, {1, 3, 2}), 1);
}

TEST(ParticleRouting, LeaversGoStraightToTheirNewSlabAcrossSeveralBorders) {
    const Decomposition d(0, {1.0, 2.0, 3.0});
    // Rank 0's particles: one moved into rank 1, one across two borders into rank 2, one past
    // every border into rank 3.
    const std::vector<ParticleBatch> out = routeLeavers(particlesAt({1.5, 2.5, 9.0}), d, 0);
    ASSERT_EQ(out.size(), 4u);
    EXPECT_EQ(out[0].size(), 0u);
    ASSERT_EQ(out[1].size(), 1u);
    ASSERT_EQ(out[2].size(), 1u);
    ASSERT_EQ(out[3].size(), 1u);
    EXPECT_EQ(out[2].id[0], 1);
    EXPECT_EQ(out[3].id[0], 2);
}

TEST(ParticleRouting, GhostsGoToEveryRankWithinTheHalo) {
    // Rank 1 owns [1, 1.2): thinner than the halo width 0.5, so a particle of rank 0 near its
    // border is a ghost on rank 1 and on rank 2.
    const Decomposition d(0, {1.0, 1.2, 3.0});
    const std::vector<ParticleBatch> out = routeGhosts(particlesAt({0.9, 0.2}), d, 0, 0.5);
    EXPECT_EQ(out[0].size(), 0u);
    ASSERT_EQ(out[1].size(), 1u);
    ASSERT_EQ(out[2].size(), 1u);
    EXPECT_EQ(out[3].size(), 0u);
    EXPECT_EQ(out[1].id[0], 0);
    EXPECT_EQ(out[1].pos[0].w, kArrivingGhostMark);  // marked a ghost
    EXPECT_EQ(out[1].pos[0].x, Real(0.9));
}

TEST(ParticleRouting, MessagesRoundTrip) {
    ParticleBatch b = particlesAt({0.5, 1.5, 2.5});
    b.vel[1].y = 3;
    ParticleBatch back;
    unpackParticles(packParticles(b), back);
    unpackParticles(packParticles(ParticleBatch{}), back);
    unpackParticles(Bytes{}, back);
    ASSERT_EQ(back.size(), 3u);
    EXPECT_EQ(back.pos[2].x, Real(2.5));
    EXPECT_EQ(back.vel[1].y, Real(3));
    EXPECT_EQ(back.id[2], 2);
    Bytes cut = packParticles(b);
    cut.pop_back();
    EXPECT_THROW(unpackParticles(cut, back), std::runtime_error);
}

// One rank through the distributed path is the plain solver, exactly: same particles, same order
// of every sum.
TEST(DistributedSimulation, OneRankIsThePlainSolverExactly) {
    const Scene scene = testing::smallDamBreak(1500);
    auto plain = testing::start(scene, Backend::Cpu, NeighbourMode::Dense);
    auto comm = makeSoloCommunicator();
    DistributedSimulation distributed(*comm, Backend::Cpu, NeighbourMode::Dense,
                                      buildSetup(scene, {}, nullptr));
    plain->advanceTo(0.02);
    distributed.advanceTo(0.02);
    HostParticles a, b;
    plain->download(a);
    distributed.download(b);
    ASSERT_EQ(a.size(), b.size());
    EXPECT_EQ(plain->stepCount(), distributed.stepCount());
    EXPECT_EQ(testing::maxPositionDifference(a, b), 0.0);
    EXPECT_EQ(distributed.exchangeStats().ghosts, 0);
}

TEST(DistributedSimulation, SetupHistogramCountsSeedsAndParticles) {
    const Scene scene = testing::smallDamBreak(3000);
    const SimulationSetup hosted = buildSetup(scene, {}, nullptr);
    SetupOptions onDevice;
    onDevice.seedOnDevice = true;
    const SimulationSetup seeded = buildSetup(scene, onDevice, nullptr);
    const AxisHistogram a = setupHistogram(hosted, 0, 60);
    const AxisHistogram b = setupHistogram(seeded, 0, 60);
    EXPECT_EQ(a.total(), std::int64_t(hosted.particles.size()));
    // Sampled: within a few percent of the count, and all in the column's third of the tank.
    EXPECT_NEAR(double(b.total()), double(seeded.particleCount()), 0.05 * seeded.particleCount());
    for (std::size_t k = 21; k < 60; ++k) {
        EXPECT_EQ(a.counts[k], 0) << k;
        EXPECT_EQ(b.counts[k], 0) << k;
    }
}

}  // namespace
}  // namespace weir
