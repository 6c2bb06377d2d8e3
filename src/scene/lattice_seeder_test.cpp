// Seeding: the counts against a visit of every point, and the lattice seeder's slabs and samples
// against the host's seeding.
#include "scene/lattice_seeder.h"

#include <gtest/gtest.h>

#include <cmath>

#include "scene/seeding.h"
#include "solver/solver_test_support.h"

namespace weir {
namespace {

using namespace weir::testing;

TEST(Seeding, CountsAgreeWithTheSeedsVisited) {
    // The closed-form count of a lone block and the parallel count of the rest against a visit
    // of every kept point, at a few spacings.
    for (const Scene& scene : {seedingScene(), builtinScene("dam_break"),
                               builtinScene("double_dam_break"), builtinScene("drop_into_pool")}) {
        for (double d : {0.011, 0.02, 0.037}) {
            SceneSeeds seeds = sceneSeeds(scene, d);
            std::int64_t visited = 0;
            forEachSeed(seeds, [&](const Vec3d&, const Vec3d&) { ++visited; });
            EXPECT_EQ(seeds.count, visited) << scene.name << " at d = " << d;
            EXPECT_GT(visited, 0);
        }
    }
}

TEST(LatticeSeeder, SlabsSplitTheSeedingAndSamplesWeighItsCount) {
    const SceneSeeds seeds = sceneSeeds(builtinScene("dam_break"), 0.02);
    const LatticeSeeder whole(seeds);
    EXPECT_EQ(whole.count(), seeds.count);
    EXPECT_EQ(whole.expectedCount(), seeds.count);
    // The samples stand for the whole count (every s-th point of each axis weighs s^3) and lie
    // where the host seeds: inside the column, x in [0, 0.4].
    double weight = 0;
    double lo = 1e300, hi = -1e300;
    whole.sample(0, [&](double x, std::int64_t w) {
        weight += double(w);
        lo = std::min(lo, x);
        hi = std::max(hi, x);
    });
    EXPECT_NEAR(weight, double(seeds.count), 0.01 * double(seeds.count));
    EXPECT_GE(lo, 0.0);
    EXPECT_LE(hi, 0.4);
    // A slab keeps the whole count (ids are the whole seeding's) and says what it expects.
    const auto half = whole.within(Slab{0, 0.0, 0.2}, 1234);
    EXPECT_EQ(half->count(), seeds.count);
    EXPECT_EQ(half->expectedCount(), 1234);
}

}  // namespace
}  // namespace weir
