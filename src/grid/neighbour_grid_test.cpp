// The grid of paper §6.2 on the CPU: cell table invariants, and grid neighbours equal brute force.
#include "grid/neighbour_grid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <set>

#include "core/exec_cpu.h"
#include "grid/dense_grid.h"
#include "grid/grid_test_support.h"

namespace weir {
namespace {

using testing::Cloud;

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

class GridVersusBrute : public ::testing::TestWithParam<int> {};

TEST_P(GridVersusBrute, SameNeighboursAsBruteForce) {
    const int n = GetParam();
    const Real size = 1, h = Real(0.09);
    Cloud cloud = testing::randomCloud(n, size, unsigned(n));
    CpuExec exec;
    NeighbourGrid<CpuExec> grid(makeGridSpec({0, 0, 0}, {size, size, size}, h));
    std::vector<Real4> pos = cloud.packed();
    grid.build(exec, pos.data(), n);

    // Cell table: strictly increasing ids, runs that tile [0, n), particles in their own cell.
    const Index cells = grid.numCells();
    const CellKey* cellKeys = grid.cellKeys().data();
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
            ASSERT_EQ(grid.spec().keyOf(cloud.x[p], cloud.y[p], cloud.z[p]), cellKeys[c]);
            ASSERT_EQ(grid.particleCell().data()[i], c);
        }
    }
    ASSERT_EQ(covered, n);

    // Neighbour table: entry for offset (dx, dy, dz) is that cell if occupied, else -1.
    std::set<CellKey> occupied(cellKeys, cellKeys + cells);
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
                    bool expected = inGrid && occupied.count(encodeCell(x, y, z)) > 0;
                    ASSERT_EQ(e >= 0, expected);
                    if (e >= 0) {
                        ASSERT_EQ(cellKeys[e], encodeCell(x, y, z));
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

INSTANTIATE_TEST_SUITE_P(Sizes, GridVersusBrute, ::testing::Values(1, 2, 50, 3000));

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
