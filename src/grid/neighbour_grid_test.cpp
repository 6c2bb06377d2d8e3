// The grid of paper §6.2 on the CPU: cell table invariants, and grid neighbours equal brute force.
#include "grid/neighbour_grid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <set>
#include <string>
#include <utility>

#include "core/exec_cpu.h"
#include "grid/dense_grid.h"
#include "grid/grid_test_support.h"

namespace weir {
namespace {

using testing::Cloud;
using testing::clumpsAlong;
using testing::stableSorted;

TEST(CpuRadixSort, SortsStablyOnTheKeyBits) {
    std::mt19937 rng(3);
    const int n = 50000;
    std::vector<CellKey> keys(n), sortedKeys(n);
    std::vector<Index> values(n), sortedValues(n);
    for (int i = 0; i < n; ++i) {
        keys[i] = rng() & ((1u << kCellKeyBits) - 1) & 0x3ff003ff;  // many equal keys
        values[i] = i;
    }
    CpuExec exec;
    exec.sortPairs(keys.data(), sortedKeys.data(), values.data(), sortedValues.data(), n,
                   kCellKeyBits);
    for (int i = 1; i < n; ++i) {
        ASSERT_LE(sortedKeys[i - 1], sortedKeys[i]);
        if (sortedKeys[i - 1] == sortedKeys[i]) {
            ASSERT_LT(sortedValues[i - 1], sortedValues[i]) << "not stable at " << i;
        }
    }
    for (int i = 0; i < n; ++i) {
        ASSERT_EQ(keys[sortedValues[i]], sortedKeys[i]);
    }
}

TEST(CpuRadixSort, WideKeysSortLikeStableSort) {
    std::mt19937_64 rng(5);
    const int n = 40000;
    // All 63 bits used (a 2^21-cell axis in every field), then only the low 45 (what a thin grid
    // sorts on); few distinct keys, so stability shows.
    for (int keyBits : {63, 45}) {
        std::vector<WideCellKey> keys(n), sortedKeys(n);
        std::vector<Index> values(n), sortedValues(n);
        std::vector<WideCellKey> pool(700);
        for (WideCellKey& k : pool) {
            k = rng() >> (64 - keyBits);
        }
        for (int i = 0; i < n; ++i) {
            keys[i] = pool[rng() % pool.size()];
            values[i] = i;
        }
        CpuExec exec;
        exec.sortPairs(keys.data(), sortedKeys.data(), values.data(), sortedValues.data(), n,
                       keyBits);
        const auto expected = stableSorted(keys);
        for (int i = 0; i < n; ++i) {
            ASSERT_EQ(sortedKeys[i], expected[i].first) << keyBits << " bits, at " << i;
            ASSERT_EQ(sortedValues[i], expected[i].second) << keyBits << " bits, at " << i;
        }
    }
}

// The grid's tables against their definitions, and its candidates against brute force: every
// particle's candidates within h are exactly its brute-force neighbours.
template <class Key>
void expectGridMatchesBruteForce(const KeyedNeighbourGrid<CpuExec, Key>& grid, const Cloud& cloud,
                                 Real h) {
    const Index n = Index(cloud.x.size());
    // Cell table: strictly increasing ids, runs that tile [0, n), particles in their own cell.
    const Index cells = grid.numCells();
    const Key* cellKeys = grid.cellKeys().data();
    const Index* start = grid.cellStart().data();
    const Index* count = grid.cellCount().data();
    const Index* order = grid.permutation();
    Index covered = 0;
    for (Index c = 0; c < cells; ++c) {
        ASSERT_EQ(start[c], covered);
        ASSERT_GT(count[c], 0);
        covered += count[c];
        if (c > 0) {
            ASSERT_LT(cellKeys[c - 1], cellKeys[c]);
        }
        for (Index i = start[c]; i < start[c] + count[c]; ++i) {
            Index p = order[i];
            ASSERT_EQ(grid.spec().template keyOf<Key>(cloud.x[p], cloud.y[p], cloud.z[p]),
                      cellKeys[c]);
            ASSERT_EQ(grid.particleCell().data()[i], c);
        }
    }
    ASSERT_EQ(covered, n);

    // Neighbour table: entry for offset (dx, dy, dz) is that cell if occupied, else -1.
    std::set<Key> occupied(cellKeys, cellKeys + cells);
    for (Index c = 0; c < cells; ++c) {
        CellCoord home = decodeCell(cellKeys[c]);
        for (int dy = -1; dy <= 1; ++dy) {
            for (int dz = -1; dz <= 1; ++dz) {
                for (int dx = -1; dx <= 1; ++dx) {
                    Index e = grid.neighbourTable()
                                  .data()[c * kNeighbourCells + neighbourSlot(dx, dy, dz)];
                    int x = home.x + dx, y = home.y + dy, z = home.z + dz;
                    bool inGrid = x >= 0 && y >= 0 && z >= 0 && x < grid.spec().dims[0] &&
                                  y < grid.spec().dims[1] && z < grid.spec().dims[2];
                    bool expected = inGrid && occupied.count(encodeCell<Key>(x, y, z)) > 0;
                    ASSERT_EQ(e >= 0, expected);
                    if (e >= 0) {
                        ASSERT_EQ(cellKeys[e], encodeCell<Key>(x, y, z));
                    }
                }
            }
        }
    }

    // Particle neighbours found through the grid equal the brute-force sets.
    auto brute = testing::bruteNeighbourSets(cloud, h);
    GridNeighbours view = grid.view();
    for (Index i = 0; i < n; ++i) {
        Index pi = order[i];
        std::vector<int> found;
        view.forEachCandidate(i, [&](Index j) {
            Index pj = order[j];
            Real dx = cloud.x[pi] - cloud.x[pj], dy = cloud.y[pi] - cloud.y[pj],
                 dz = cloud.z[pi] - cloud.z[pj];
            if (pj != pi && dx * dx + dy * dy + dz * dz < h * h) {
                found.push_back(pj);
            }
        });
        std::sort(found.begin(), found.end());
        ASSERT_EQ(found, brute[pi]) << "particle " << pi;
    }
}

class GridVersusBrute : public ::testing::TestWithParam<int> {};

TEST_P(GridVersusBrute, SameNeighboursAsBruteForce) {
    const int n = GetParam();
    const Real size = 1, h = Real(0.09);
    Cloud cloud = testing::randomCloud(n, size, unsigned(n));
    CpuExec exec;
    NeighbourGrid<CpuExec> grid(makeGridSpec({0, 0, 0}, {size, size, size}, h));
    // 12 cells per axis fit the paper's 32-bit cell id, so the grid keeps it.
    ASSERT_EQ(grid.cellIdBits(), 32);
    ASSERT_EQ(grid.keyed<WideCellKey>(), nullptr);
    std::vector<Real4> pos = cloud.packed();
    grid.build(exec, pos.data(), n);
    ASSERT_NE(grid.keyed<CellKey>(), nullptr);
    ASSERT_EQ(grid.permutation(), grid.keyed<CellKey>()->permutation());
    expectGridMatchesBruteForce(*grid.keyed<CellKey>(), cloud, h);
}

INSTANTIATE_TEST_SUITE_P(Sizes, GridVersusBrute, ::testing::Values(1, 2, 50, 3000));

class WideGridVersusBrute : public ::testing::TestWithParam<int> {};

TEST_P(WideGridVersusBrute, SameNeighboursAsBruteForcePast1024Cells) {
    const int longAxis = GetParam();
    const Real h = Real(0.002), length = 1250 * h, width = 4 * h;
    Cloud cloud = clumpsAlong(longAxis, length, width, h, 17 + unsigned(longAxis));
    Vec3d boxMax(width, width, width);
    boxMax[longAxis] = length;
    const GridSpec spec = makeGridSpec({0, 0, 0}, boxMax, h);
    ASSERT_EQ(spec.dims[longAxis], 1250);
    ASSERT_TRUE(needsWideCellIds(spec));

    CpuExec exec;
    NeighbourGrid<CpuExec> grid(spec);
    ASSERT_EQ(grid.cellIdBits(), 64);
    ASSERT_EQ(grid.keyed<CellKey>(), nullptr);
    std::vector<Real4> pos = cloud.packed();
    const Index n = Index(pos.size());
    grid.build(exec, pos.data(), n);
    const auto* wide = grid.keyed<WideCellKey>();
    ASSERT_NE(wide, nullptr);
    EXPECT_EQ(grid.numParticles(), n);

    // Particles do sit past cell 1024 (the test reaches where a 32-bit id would fail) ...
    int beyond = 0;
    for (Index i = 0; i < n; ++i) {
        CellCoord c = spec.cellOf(pos[i].x, pos[i].y, pos[i].z);
        beyond += (longAxis == 0 ? c.x : longAxis == 1 ? c.y : c.z) >= 1024 ? 1 : 0;
    }
    ASSERT_GT(beyond, 100);
    // ... the sort covers every key bit in use ...
    for (Index c = 0; c < grid.numCells(); ++c) {
        ASSERT_LT(wide->cellKeys().data()[c], WideCellKey(1) << wide->sortKeyBits());
    }
    // ... and the tables and the neighbours are right.
    expectGridMatchesBruteForce(*wide, cloud, h);
    std::size_t pairs = 0;
    for (const auto& set : testing::bruteNeighbourSets(cloud, h)) {
        pairs += set.size();
    }
    EXPECT_GT(pairs, std::size_t(n));  // neighbours to find: the comparison is not empty
    // The wider ids are counted in the grid's memory.
    EXPECT_GE(grid.bytesHeld(), 2 * std::size_t(n) * sizeof(WideCellKey));
}

INSTANTIATE_TEST_SUITE_P(LongAxis, WideGridVersusBrute, ::testing::Values(0, 1, 2),
                         [](const auto& info) { return std::string(1, "XYZ"[info.param]); });

class DenseGridVersusBrute : public ::testing::TestWithParam<int> {};

TEST_P(DenseGridVersusBrute, SameNeighboursAsBruteForce) {
    const int n = GetParam();
    const Real size = 1, h = Real(0.07);
    Cloud cloud = testing::randomCloud(n, size, unsigned(n) + 11);
    std::vector<Real4> pos = cloud.packed();
    auto brute = testing::bruteNeighbourSets(cloud, h);
    for (int reach : {1, 2, 3}) {
        CpuExec exec;
        // A box taller than wide, so that mixing up axes would show; cells of h / reach.
        DenseGrid<CpuExec> grid(makeGridSpec({0, 0, 0}, {size, 2 * size, size}, h / reach), reach);
        grid.build(exec, pos.data(), n);
        const Index* order = grid.permutation();
        // cellBound is non-decreasing, starts at 0 and ends at n.
        const std::uint64_t cells = totalCells(grid.spec());
        const Index* bound = grid.cellBound().data();
        ASSERT_EQ(bound[0], 0);
        ASSERT_EQ(bound[cells], n);
        for (std::uint64_t c = 0; c < cells; ++c) {
            ASSERT_LE(bound[c], bound[c + 1]);
        }
        // The counting sort gives the order of a stable sort by cell: cells non-decreasing, and
        // within a cell the particles in their old order (the same on every run and backend).
        const GridSpec& spec = grid.spec();
        auto cellOf = [&](Index i) {
            CellCoord c = spec.cellOf(pos[i].x, pos[i].y, pos[i].z);
            return denseCellIndex(c.x, c.y, c.z, spec.dims[0], spec.dims[2]);
        };
        std::vector<Index> stable(n);
        std::iota(stable.begin(), stable.end(), 0);
        std::stable_sort(stable.begin(), stable.end(),
                         [&](Index a, Index b) { return cellOf(a) < cellOf(b); });
        ASSERT_EQ(std::vector<Index>(order, order + n), stable) << "reach " << reach;
        std::vector<Real4> sortedPos(n);
        for (Index i = 0; i < n; ++i) {
            sortedPos[i] = pos[order[i]];
        }
        DenseGridNeighbours view = grid.view(sortedPos.data(), h);
        for (Index i = 0; i < n; ++i) {
            Index pi = order[i];
            std::vector<int> found;
            view.forEachCandidate(i, [&](Index j) {
                Index pj = order[j];
                Real dx = cloud.x[pi] - cloud.x[pj], dy = cloud.y[pi] - cloud.y[pj],
                     dz = cloud.z[pi] - cloud.z[pj];
                if (pj != pi && dx * dx + dy * dy + dz * dz < h * h) {
                    found.push_back(pj);
                }
            });
            std::sort(found.begin(), found.end());
            ASSERT_EQ(found, brute[pi]) << "particle " << pi << ", reach " << reach;
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Sizes, DenseGridVersusBrute, ::testing::Values(1, 2, 50, 3000));

}  // namespace
}  // namespace weir

namespace weir {
namespace {

template <class F>
void forEachTeamSize(F&& f) {
    f(Team<2>{});
    f(Team<4>{});
    f(Team<8>{});
}

// The candidates of a team's lanes (core/team.h), taken together, are the candidates of one
// thread, each exactly once: every neighbour view deals its rows out without loss or overlap.
template <class View>
void expectTeamsDealEveryCandidateOnce(const View& view, Index n) {
    forEachTeamSize([&](auto tag) {
        constexpr int size = decltype(tag)::size;
        for (Index i = 0; i < n; ++i) {
            std::vector<Index> alone, dealt;
            view.forEachCandidate(i, [&](Index j) { alone.push_back(j); });
            std::vector<int> perLane(std::size_t(size), 0);
            for (int rank = 0; rank < size; ++rank) {
                view.forEachCandidate(
                    i,
                    [&](Index j) {
                        dealt.push_back(j);
                        ++perLane[std::size_t(rank)];
                    },
                    Team<size>{rank});
            }
            std::sort(alone.begin(), alone.end());
            std::sort(dealt.begin(), dealt.end());
            ASSERT_EQ(dealt, alone) << "particle " << i << ", team of " << size;
            // The lanes share the work evenly: a run of k candidates gives each lane k / size,
            // rounded down or up, so no lane has more than one extra per run (at most 25 runs).
            const auto [fewest, most] = std::minmax_element(perLane.begin(), perLane.end());
            ASSERT_LE(*most - *fewest, 25) << "particle " << i << ", team of " << size;
        }
    });
}

TEST(Teams, DealEveryCandidateOnceInEveryNeighbourView) {
    const Index n = 2000;
    const Real size = 1, h = Real(0.12);
    testing::Cloud cloud = testing::randomCloud(n, size, 5);
    std::vector<Real4> pos = cloud.packed();
    CpuExec exec;

    DenseGrid<CpuExec> dense(makeGridSpec({0, 0, 0}, {size, size, size}, h / 2), 2);
    dense.build(exec, pos.data(), n);
    std::vector<Real4> sorted(pos.size());
    for (Index i = 0; i < n; ++i) {
        sorted[std::size_t(i)] = pos[std::size_t(dense.permutation()[i])];
    }
    expectTeamsDealEveryCandidateOnce(dense.view(sorted.data(), h), n);

    NeighbourGrid<CpuExec> sparse(makeGridSpec({0, 0, 0}, {size, size, size}, h));
    sparse.build(exec, pos.data(), n);
    expectTeamsDealEveryCandidateOnce(sparse.view(), n);

    expectTeamsDealEveryCandidateOnce(BruteNeighbours{n}, Index(200));
}

}  // namespace
}  // namespace weir
