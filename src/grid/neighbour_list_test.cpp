// The neighbour list gives every particle exactly its neighbours within the radius, listed where
// they fit and by the inner view's walk where they do not (a clump past the capacity).
#include "grid/neighbour_list.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "core/exec_cpu.h"
#include "grid/grid_test_support.h"
#include "grid/neighbour_grid.h"

namespace weir {
namespace {

TEST(NeighbourList, ListsExactlyTheNeighboursWithinTheRadiusAndWalksPastItsCapacity) {
    // A sparse cloud (a few neighbours each) and a dense clump in one corner (more than the
    // capacity each), so that both kinds of particle are present.
    testing::Cloud cloud = testing::randomCloud(1500, Real(1), 7);
    const testing::Cloud clump = testing::randomCloud(400, Real(0.12), 11);
    cloud.x.insert(cloud.x.end(), clump.x.begin(), clump.x.end());
    cloud.y.insert(cloud.y.end(), clump.y.begin(), clump.y.end());
    cloud.z.insert(cloud.z.end(), clump.z.begin(), clump.z.end());
    const Real h = Real(0.1);
    const std::vector<Real4> pos = cloud.packed();
    const Index n = Index(pos.size());
    const auto expected = testing::bruteNeighbourSets(cloud, h);

    CpuExec exec;
    NeighbourList<CpuExec> list;
    for (bool enabled : {true, false}) {
        const auto view = list.build(exec, BruteNeighbours{n}, pos.data(), n, h * h, enabled);
        int listed = 0, walked = 0;
        for (Index i = 0; i < n; ++i) {
            std::vector<int> found;
            view.forEachCandidate(i, [&](Index j) {
                const Vec3 r = pos[i].xyz() - pos[j].xyz();
                if (j != i && lengthSquared(r) < h * h) {
                    found.push_back(j);
                }
            });
            std::sort(found.begin(), found.end());
            ASSERT_EQ(found, expected[std::size_t(i)]) << "particle " << i;
            const bool fits = expected[std::size_t(i)].size() <= NeighbourList<CpuExec>::kCapacity;
            (enabled && fits ? listed : walked) += 1;
        }
        if (enabled) {
            EXPECT_GT(listed, 1000);
            EXPECT_GT(walked, 100);  // the clump
        } else {
            EXPECT_EQ(walked, n);
        }
    }
}

// A listed particle's candidates are its neighbours only: no candidate beyond the radius.
TEST(NeighbourList, ListedParticlesVisitNoFartherCandidates) {
    const testing::Cloud cloud = testing::randomCloud(800, Real(1), 3);
    const std::vector<Real4> pos = cloud.packed();
    const Index n = Index(pos.size());
    const Real h = Real(0.12);
    CpuExec exec;
    NeighbourList<CpuExec> list;
    const auto view = list.build(exec, BruteNeighbours{n}, pos.data(), n, h * h, true);
    for (Index i = 0; i < n; ++i) {
        int candidates = 0;
        view.forEachCandidate(i, [&](Index j) {
            EXPECT_LT(lengthSquared(pos[i].xyz() - pos[j].xyz()), h * h);
            EXPECT_NE(j, i);
            ++candidates;
        });
        EXPECT_LE(candidates, NeighbourList<CpuExec>::kCapacity);
    }
}

}  // namespace
}  // namespace weir
