// Distributed runs under mpirun (ctest runs this at 1, 2 and 3 ranks): the R-rank run gives the
// single-rank fluid, particles cross borders and slabs may be empty, ghosts are exactly the
// particles within the halo. Each rank runs the single-rank reference itself, so the comparison
// needs no second launch.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "cluster/communicator.h"
#include "cluster/distributed_simulation.h"
#include "cluster/mpi_test_support.h"
#include "core/backend.h"
#include "solver/solver_test_support.h"

namespace weir {
namespace {

using testing::world;

// The largest distance between a particle in the distributed run and in the single-rank run
// after `time` seconds, on rank 0 (-1 elsewhere).
double divergenceAfter(Backend backend, NeighbourMode mode, const Scene& scene, double time,
                       long long* steps = nullptr, HaloTransport transport = HaloTransport::Auto) {
    auto plain = testing::start(scene, backend, mode);
    DistributedOptions options;
    options.transport = transport;
    DistributedSimulation distributed(world(), backend, mode, buildSetup(scene, {}, nullptr),
                                      options);
    plain->advanceTo(time);
    distributed.advanceTo(time);
    EXPECT_EQ(distributed.fault().code, 0);
    HostParticles a, b;
    plain->download(a);
    distributed.download(b);
    if (steps != nullptr) {
        *steps = distributed.stepCount();
    }
    EXPECT_EQ(plain->stepCount(), distributed.stepCount());
    if (world().rank() != 0) {
        EXPECT_EQ(b.size(), 0u);
        return -1;
    }
    EXPECT_EQ(a.size(), b.size());
    return testing::maxPositionDifference(a, b);
}

// Over 0.1 s (some 200 steps of a falling, sloshing column), the runs part only by the float
// rounding of sums taken in another order: well under a thousandth of the particle spacing.
TEST(Distributed, MatchesTheSingleRankRunOnTheCpu) {
    const Scene scene = testing::smallDamBreak(4000);
    for (NeighbourMode mode : {NeighbourMode::Dense, NeighbourMode::Grid}) {
        long long steps = 0;
        const double worst = divergenceAfter(Backend::Cpu, mode, scene, 0.1, &steps);
        if (world().rank() == 0) {
            const double spacing = buildSetup(scene, {}, nullptr).params.kernel.h / 2;
            std::printf("%s, %d ranks, %lld steps: largest difference %.3g of the spacing\n",
                        neighbourModeName(mode), world().size(), steps, worst / spacing);
            EXPECT_LT(worst, 1e-3 * spacing) << neighbourModeName(mode) << ", " << world().size()
                                             << " ranks, " << steps << " steps";
        }
    }
}

// On the GPU, fused multiply-adds and a splashing dam break amplify rounding more than on the
// CPU: the yardstick is how far two single-GPU runs drift apart when only the order of their
// sums differs (the dense table against the paper's grid). A lost or wrong ghost moves particles
// by a good part of the spacing (a halo one radius wide instead of two: 1.9 spacings here).
TEST(Distributed, MatchesTheSingleRankRunOnTheGpu) {
    if (!cudaDeviceAvailable()) {
        GTEST_SKIP() << "no CUDA device";
    }
    const Scene scene = testing::smallDamBreak(20000);
    const double time = 0.1;
    const double spacing = buildSetup(scene, {}, nullptr).params.kernel.h / 2;
    HostParticles dense, grid;
    auto denseRun = testing::start(scene, Backend::Cuda, NeighbourMode::Dense);
    auto gridRun = testing::start(scene, Backend::Cuda, NeighbourMode::Grid);
    denseRun->advanceTo(time);
    gridRun->advanceTo(time);
    denseRun->download(dense);
    gridRun->download(grid);
    const double noise = testing::maxPositionDifference(dense, grid);
    // Auto: NCCL where each rank has a GPU of its own and weir has NCCL, else host staging.
    for (HaloTransport transport : {HaloTransport::Host, HaloTransport::Auto}) {
        long long steps = 0;
        const double worst =
            divergenceAfter(Backend::Cuda, NeighbourMode::Dense, scene, time, &steps, transport);
        if (world().rank() == 0) {
            std::printf(
                "cuda %s, %d ranks, %lld steps: largest difference %.3g of the spacing "
                "(dense against grid on one GPU: %.3g)\n",
                transport == HaloTransport::Auto ? "auto" : "host", world().size(), steps,
                worst / spacing, noise / spacing);
            EXPECT_LT(worst, std::max(1e-3 * spacing, 3 * noise)) << world().size() << " ranks";
            EXPECT_LT(worst, 0.05 * spacing);  // the CPU-against-GPU bound (solver_cuda_test)
        }
    }
}

// All particles handed to the last rank at once: those of rank 0 cross every border in one
// exchange, and every other slab is left empty; the run goes on and still matches.
TEST(Distributed, ParticlesCrossSeveralBordersAndSlabsMayBeEmpty) {
    const Scene scene = testing::smallDamBreak(3000);
    const SimulationSetup setup = buildSetup(scene, {}, nullptr);
    DistributedSimulation distributed(world(), Backend::Cpu, NeighbourMode::Dense, setup);
    const int ranks = world().size();
    std::vector<double> inner(std::size_t(ranks - 1), -1e6);  // slabs 0..R-2: [-1e6, -1e6)
    distributed.setDecomposition(Decomposition(distributed.decomposition().axis(), inner));
    distributed.computeDensity();
    ParticleBatch mine;
    distributed.downloadOwned(mine);
    std::vector<std::int64_t> counts{std::int64_t(mine.size())};
    world().sumInPlace(counts);
    EXPECT_EQ(counts[0], std::int64_t(setup.particles.size()));
    if (world().rank() == ranks - 1) {
        EXPECT_EQ(std::int64_t(mine.size()), std::int64_t(setup.particles.size()));
    } else {
        EXPECT_EQ(mine.size(), 0u);
    }
    auto plain = makeSimulation(Backend::Cpu, NeighbourMode::Dense, setup);
    plain->advanceTo(0.03);
    distributed.advanceTo(0.03);
    HostParticles a, b;
    plain->download(a);
    distributed.download(b);
    if (world().rank() == 0) {
        ASSERT_EQ(a.size(), b.size());
        EXPECT_LT(testing::maxPositionDifference(a, b), 1e-3 * setup.params.kernel.h);
    }
}

// After an exchange each rank owns exactly the particles of its slab, and holds as ghosts
// exactly the other ranks' particles within two smoothing radii of it; the density of every
// owned particle is the single-rank density.
TEST(Distributed, OwnsItsSlabAndHoldsTheHalo) {
    // At h = 2 d: at delta-SPH's default 3 d a rank's halos (2 h = 6 d on each side) hold more of
    // this small tank than its share saves, and it held more bytes than one rank (CI at 63f2ae1).
    const Scene scene =
        withOverrides(testing::smallDamBreak(5000), R"({"particles": {"smoothingRatio": 2}})");
    const SimulationSetup setup = buildSetup(scene, {}, nullptr);
    DistributedSimulation distributed(world(), Backend::Cpu, NeighbourMode::Dense, setup);
    distributed.computeDensity();
    auto plain = makeSimulation(Backend::Cpu, NeighbourMode::Dense, setup);
    plain->computeDensity();
    HostParticles reference;
    plain->download(reference);

    const Slab slab = distributed.decomposition().slab(world().rank());
    const double width = 2 * double(setup.params.kernel.h);
    std::int64_t inSlab = 0, inHalo = 0;
    for (std::size_t i = 0; i < reference.size(); ++i) {
        const double c = slab.coordinate(Vec3d(reference.x[i], reference.y[i], reference.z[i]));
        inSlab += slab.contains(c) ? 1 : 0;
        inHalo += !slab.contains(c) && c >= slab.lo - width && c < slab.hi + width ? 1 : 0;
    }
    ParticleBatch mine;
    distributed.downloadOwned(mine);
    EXPECT_EQ(std::int64_t(mine.size()), inSlab);
    EXPECT_EQ(distributed.exchangeStats().ghosts, inHalo);
    if (world().size() > 1) {
        EXPECT_GT(inHalo, 0);
        // Its share of the particles and a neighbour table over its slab only.
        EXPECT_LT(distributed.bytesHeld(), plain->bytesHeld());
    }
    for (std::size_t k = 0; k < mine.size(); ++k) {
        const std::size_t i = std::size_t(mine.id[k]);
        ASSERT_TRUE(slab.contains(slab.coordinate(mine.pos[k]))) << "particle " << i;
        ASSERT_NEAR(mine.vel[k].w, reference.rho[i], 1e-4 * reference.rho[i]) << "particle " << i;
    }
}

// Each rank seeds only its slab on its backend (as a billion-particle run must), with the ids of
// the host's seeding order: the gathered particles are the host's, exactly.
TEST(Distributed, SeedsItsShareOnItsBackend) {
    for (Backend backend : {Backend::Cpu, Backend::Cuda}) {
        if (backend == Backend::Cuda && !cudaDeviceAvailable()) {
            continue;
        }
        const Scene scene = testing::seedingScene();
        SetupOptions onBackend;
        onBackend.seedOnDevice = true;
        DistributedSimulation distributed(world(), backend, NeighbourMode::Auto,
                                          buildSetup(scene, onBackend, nullptr));
        HostParticles got;
        distributed.download(got);
        if (world().rank() != 0) {
            continue;
        }
        const HostParticles want = buildSetup(scene, {}, nullptr).particles;
        ASSERT_EQ(got.size(), want.size());
        EXPECT_EQ(testing::maxPositionDifference(got, want), 0.0) << backendName(backend);
        EXPECT_EQ(got.vx, want.vx);
    }
}

// Borders move to follow the fluid: a dam break's column spreads along the tank, and the
// counts per rank stay within the rebalancing threshold plus one check interval's drift.
TEST(Distributed, BordersFollowTheFluid) {
    if (world().size() < 2) {
        GTEST_SKIP() << "one rank has no borders";
    }
    const Scene scene = testing::smallDamBreak(3000);
    DistributedOptions options;
    options.rebalanceEvery = 5;
    DistributedSimulation distributed(world(), Backend::Cpu, NeighbourMode::Dense,
                                      buildSetup(scene, {}, nullptr), options);
    const std::vector<double> before = distributed.decomposition().innerBorders();
    distributed.advanceTo(0.25);
    EXPECT_GT(distributed.exchangeStats().rebalances, 0);
    EXPECT_GT(distributed.decomposition().innerBorders()[0], before[0]);  // the front moved on
    ParticleBatch mine;
    distributed.downloadOwned(mine);
    std::vector<std::int64_t> counts(std::size_t(world().size()), 0);
    counts[std::size_t(world().rank())] = std::int64_t(mine.size());
    world().sumInPlace(counts);
    EXPECT_LT(imbalance(counts), 1.15);
}

// Periodic boundaries (container.periodic) along x and z: the slabs split y, the one axis with
// walls, and each rank makes the periodic ghost copies of its own particles and of the halo it
// received; the run gives the single-rank fluid. All three axes periodic leaves no axis to
// split: refused.
TEST(Distributed, PeriodicAxesMatchTheSingleRankRun) {
    const std::string blocks = R"(
        "blocks": [{"min": [0, 0, 0], "max": [0.16, 0.06, 0.08], "velocity": [0.5, 0, 0.2]},
                   {"min": [0, 0.06, 0], "max": [0.08, 0.1, 0.08], "velocity": [-0.3, 0, 0]}],
        "particles": {"spacing": 0.01}, "walls": {"model": "particles"}})";
    const Scene scene = parseScene(R"({"container": {"min": [0, 0, 0], "max": [0.16, 0.12, 0.08],
        "periodic": [true, false, true]},)" +
                                       blocks,
                                   "<test periodic channel>");
    for (NeighbourMode mode : {NeighbourMode::Dense, NeighbourMode::Grid}) {
        const SimulationSetup setup = buildSetup(scene, {}, nullptr);
        auto plain = makeSimulation(Backend::Cpu, mode, setup);
        DistributedSimulation distributed(world(), Backend::Cpu, mode, setup);
        EXPECT_EQ(distributed.decomposition().axis(), 1);
        plain->advanceTo(0.03);
        distributed.advanceTo(0.03);
        EXPECT_EQ(distributed.fault().code, 0);
        HostParticles a, b;
        plain->download(a);
        distributed.download(b);
        if (world().rank() == 0) {
            ASSERT_EQ(a.size(), b.size());
            double worst = 0;  // by the minimum image: a particle on a face is on both
            for (std::size_t i = 0; i < a.size(); ++i) {
                double d[3] = {a.x[i] - b.x[i], a.y[i] - b.y[i], a.z[i] - b.z[i]};
                double r2 = 0;
                for (int k = 0; k < 3; ++k) {
                    const double length = scene.container.max[k] - scene.container.min[k];
                    d[k] -= scene.periodic[std::size_t(k)] ? length * std::round(d[k] / length) : 0;
                    r2 += d[k] * d[k];
                }
                worst = std::max(worst, std::sqrt(r2));
            }
            EXPECT_LT(worst, 1e-3 * setup.params.kernel.h) << neighbourModeName(mode);
        }
    }
    const Scene allPeriodic = parseScene(R"({"container": {"min": [0, 0, 0],
        "max": [0.16, 0.12, 0.08], "periodic": [true, true, true]},)" +
                                             blocks,
                                         "<test periodic box>");
    EXPECT_THROW(DistributedSimulation(world(), Backend::Cpu, NeighbourMode::Dense,
                                       buildSetup(allPeriodic, {}, nullptr)),
                 SimulationError);
}

}  // namespace
}  // namespace weir
