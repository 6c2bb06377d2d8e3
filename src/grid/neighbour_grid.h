// The uniform neighbour grid of paper §6.2, built by sorting, and the brute-force alternative.
//
// Build, on either backend: (1) a cell id per particle; (2) a stable radix sort of (id, index);
// (3) the cell table (id, first particle, count) by a prefix sum over "new cell starts here"
// flags; (4) the cell-neighbour table, 27 entries per occupied cell (itself and its 26
// neighbours, -1 where empty), by a parallel binary search over the sorted cell ids.
// Cell ids are the paper's 32 bits where every axis has at most 1024 cells, else 64 bits.
#pragma once

#include <algorithm>
#include <variant>

#include "core/config.h"
#include "core/team.h"
#include "core/vec3.h"
#include "grid/cell_id.h"
#include "grid/cell_sort.h"

namespace weir {

constexpr int kNeighbourCells = 27;

// Index of the neighbour offset (dx, dy, dz) in a 27-entry row: dx varies fastest, so the three
// cells (x-1, x, x+1) of one (dy, dz) are adjacent entries, as they are in the sorted cell ids.
WEIR_HD constexpr int neighbourSlot(int dx, int dy, int dz) {
    return ((dy + 1) * 3 + (dz + 1)) * 3 + (dx + 1);
}

// Lower bound of key in sorted keys[0, n).
template <class Key>
WEIR_HD inline Index lowerBound(const Key* keys, Index n, Key key) {
    Index lo = 0, hi = n;
    while (lo < hi) {
        Index mid = lo + (hi - lo) / 2;
        if (keys[mid] < key) {
            lo = mid + 1;
        } else {
            hi = mid;
        }
    }
    return lo;
}

// What the density and force stages need of the grid, passed by value to kernels. The stages
// are the same whichever width the grid's cell ids have; only queries at a point (not at a
// particle) look ids up, in whichever table the grid has.
struct GridNeighbours {
    const Index* particleCell;    // cell-table index of each (sorted) particle
    const Index* neighbourTable;  // kNeighbourCells entries per cell, -1 where empty
    const Index* cellStart;       // first particle of each cell
    const Index* cellCount;       // particles in each cell
    const CellKey* narrowKeys;    // the occupied cells' ids (32-bit grids), or
    const WideCellKey* wideKeys;  // ... (64-bit grids)
    Index cells;                  // occupied cells
    GridSpec spec;

    // Calls f(j) for every particle j in the 27 cells around the cell of the point p (clamped
    // into the grid), each found by a binary search of its id.
    template <class F>
    WEIR_HD void forEachNearPoint(const Vec3& p, F&& f) const {
        const CellCoord c = spec.cellOf(p.x, p.y, p.z);
        for (int dy = -1; dy <= 1; ++dy) {
            for (int dz = -1; dz <= 1; ++dz) {
                for (int dx = -1; dx <= 1; ++dx) {
                    const int x = c.x + dx, y = c.y + dy, z = c.z + dz;
                    if (x < 0 || y < 0 || z < 0 || x >= spec.dims[0] || y >= spec.dims[1] ||
                        z >= spec.dims[2]) {
                        continue;
                    }
                    Index at;
                    bool found;
                    if (narrowKeys != nullptr) {
                        const CellKey key = encodeCell<CellKey>(x, y, z);
                        at = lowerBound(narrowKeys, cells, key);
                        found = at < cells && narrowKeys[at] == key;
                    } else {
                        const WideCellKey key = encodeCell<WideCellKey>(x, y, z);
                        at = lowerBound(wideKeys, cells, key);
                        found = at < cells && wideKeys[at] == key;
                    }
                    if (found) {
                        const Index end = cellStart[at] + cellCount[at];
                        for (Index j = cellStart[at]; j < end; ++j) {
                            f(j);
                        }
                    }
                }
            }
        }
    }

    // Calls f(j) for every particle j in the 27 cells around particle i, i itself included.
    // The cells of one X row are consecutive in the sorted order, so each row is one run.
    // A team of several lanes (core/team.h) splits each run between its lanes.
    template <class F, int TeamSize = 1>
    WEIR_HD void forEachCandidate(Index i, F&& f, Team<TeamSize> team = {}) const {
        const Index* row = neighbourTable + std::size_t(particleCell[i]) * kNeighbourCells;
        for (int r = 0; r < 9; ++r) {
            Index a = row[3 * r], b = row[3 * r + 1], c = row[3 * r + 2];
            Index first = a >= 0 ? a : (b >= 0 ? b : c);
            if (first < 0) {
                continue;
            }
            Index last = c >= 0 ? c : (b >= 0 ? b : a);
            Index end = cellStart[last] + cellCount[last];
            for (Index j = cellStart[first] + team.first(); j < end; j += TeamSize) {
                f(j);
            }
        }
    }
};

// O(N^2) search: every particle is a candidate (the paper's CPU and plain GPU columns).
struct BruteNeighbours {
    Index count;

    template <class F, int TeamSize = 1>
    WEIR_HD void forEachCandidate(Index, F&& f, Team<TeamSize> team = {}) const {
        for (Index j = team.first(); j < count; j += TeamSize) {
            f(j);
        }
    }
    template <class F>
    WEIR_HD void forEachNearPoint(const Vec3&, F&& f) const {
        for (Index j = 0; j < count; ++j) {
            f(j);
        }
    }
};

// The grid with cell ids of type Key: CellKey (paper §6.2) or WideCellKey.
template <class Exec, class Key>
class KeyedNeighbourGrid {
   public:
    template <class T>
    using Buffer = typename Exec::template Buffer<T>;
    using Layout = CellIdLayout<Key>;

    // Throws SimulationError if an axis has more cells than a Key id holds.
    explicit KeyedNeighbourGrid(const GridSpec& spec) : spec_(spec) {
        checkCellIdRange(spec, Layout::maxCellsPerAxis);
    }

    // Sorts particles by cell and builds both tables. Afterwards permutation()[i] is the old index
    // of the particle that is i-th in cell order; the caller reorders its particle data by it.
    void build(Exec& exec, const Real4* pos, Index n) {
        n_ = n;
        sort_.prepare(n);
        particleCell_.resize(std::size_t(n));
        if (n == 0) {
            numCells_ = 0;
            return;
        }
        // Step 1: the cell id of every particle (paper Figure 3 layout).
        GridSpec spec = spec_;
        Key* keys = sort_.keys();
        exec.forEach(
            n, [=] WEIR_HD(Index i) { keys[i] = spec.keyOf<Key>(pos[i].x, pos[i].y, pos[i].z); });
        // Step 2: radix sort by cell id.
        sort_.sort(exec, sortKeyBits());
        buildCellTable(exec);
        buildNeighbourTable(exec);
    }

    // Step 3: head flags, their prefix sum (the cell index of each particle), then per cell its
    // id, first particle and count.
    void buildCellTable(Exec& exec) {
        const Index n = n_;
        const Key* keys = sort_.sortedKeys();
        Index* particleCell = particleCell_.data();
        exec.forEach(n, [=] WEIR_HD(Index i) {
            particleCell[i] = (i == 0 || keys[i] != keys[i - 1]) ? 1 : 0;
        });
        exec.inclusiveScan(particleCell, particleCell, n);
        numCells_ = exec.readOne(particleCell_, std::size_t(n - 1));
        ensureCapacity(cellKeys_, numCells_);
        ensureCapacity(cellStart_, numCells_);
        ensureCapacity(cellCount_, numCells_);
        Key* cellKeys = cellKeys_.data();
        Index* cellStart = cellStart_.data();
        Index* cellCount = cellCount_.data();
        exec.forEach(n, [=] WEIR_HD(Index i) {
            Index cell = particleCell[i] - 1;
            particleCell[i] = cell;
            bool head = i == 0 || keys[i] != keys[i - 1];
            bool tail = i == n - 1 || keys[i] != keys[i + 1];
            if (head) {
                cellKeys[cell] = keys[i];
                cellStart[cell] = i;
            }
            if (tail) {
                // The tail knows its cell's end; its head is found by the run's start.
                cellCount[cell] = i + 1;
            }
        });
        const Index cells = numCells_;
        exec.forEach(cells, [=] WEIR_HD(Index c) { cellCount[c] -= cellStart[c]; });
    }

    // Step 4: for each occupied cell, the cell-table index of itself and its 26 neighbours.
    void buildNeighbourTable(Exec& exec) {
        const Index cells = numCells_;
        ensureCapacity(neighbourTable_, std::size_t(cells) * kNeighbourCells);
        const Key* cellKeys = cellKeys_.data();
        Index* table = neighbourTable_.data();
        const int nx = spec_.dims[0], ny = spec_.dims[1], nz = spec_.dims[2];
        exec.forEach(cells, [=] WEIR_HD(Index c) {
            CellCoord home = decodeCell(cellKeys[c]);
            Index* row = table + std::size_t(c) * kNeighbourCells;
            for (int dy = -1; dy <= 1; ++dy) {
                for (int dz = -1; dz <= 1; ++dz) {
                    for (int dx = -1; dx <= 1; ++dx) {
                        int x = home.x + dx, y = home.y + dy, z = home.z + dz;
                        Index found = -1;
                        if (x >= 0 && y >= 0 && z >= 0 && x < nx && y < ny && z < nz) {
                            Key key = encodeCell<Key>(x, y, z);
                            Index at = lowerBound(cellKeys, cells, key);
                            if (at < cells && cellKeys[at] == key) {
                                found = at;
                            }
                        }
                        row[neighbourSlot(dx, dy, dz)] = found;
                    }
                }
            }
        });
    }

    GridNeighbours view() const {
        GridNeighbours v{particleCell_.data(),
                         neighbourTable_.data(),
                         cellStart_.data(),
                         cellCount_.data(),
                         nullptr,
                         nullptr,
                         numCells_,
                         spec_};
        if constexpr (sizeof(Key) == sizeof(CellKey)) {
            v.narrowKeys = cellKeys_.data();
        } else {
            v.wideKeys = cellKeys_.data();
        }
        return v;
    }
    const Index* permutation() const { return sort_.permutation(); }
    const GridSpec& spec() const { return spec_; }
    Index numCells() const { return numCells_; }
    Index numParticles() const { return n_; }

    // Read access for tests and statistics.
    const Buffer<Key>& cellKeys() const { return cellKeys_; }
    const Buffer<Index>& cellStart() const { return cellStart_; }
    const Buffer<Index>& cellCount() const { return cellCount_; }
    const Buffer<Index>& neighbourTable() const { return neighbourTable_; }
    const Buffer<Index>& particleCell() const { return particleCell_; }

    // Bytes of device (or host) memory held by the grid.
    std::size_t bytesHeld() const {
        return sort_.bytesHeld() +
               (particleCell_.size() + cellStart_.size() + cellCount_.size() +
                neighbourTable_.size()) *
                   sizeof(Index) +
               cellKeys_.size() * sizeof(Key);
    }

    // Bits the radix sort orders by. The paper's id sorts on all 30; the 64-bit one stops above
    // Y's largest value, its top field: up to 64 cells along Y that is 48 bits, 6 passes, not 8.
    int sortKeyBits() const {
        if constexpr (sizeof(Key) == sizeof(CellKey)) {
            return Layout::keyBits;
        } else {
            return 2 * Layout::bitsPerAxis + bitsFor(std::uint64_t(spec_.dims[1]));
        }
    }

   private:
    GridSpec spec_;
    Index n_ = 0;
    Index numCells_ = 0;
    CellSort<Exec, Key> sort_;
    Buffer<Key> cellKeys_;
    Buffer<Index> particleCell_, cellStart_, cellCount_, neighbourTable_;
};

// The sparse grid the solver holds: the paper's 32-bit cell ids where every axis has at most
// 1024 cells, 64-bit ids (21 bits per axis) past that, chosen at construction.
template <class Exec>
class NeighbourGrid {
   public:
    using Narrow = KeyedNeighbourGrid<Exec, CellKey>;
    using Wide = KeyedNeighbourGrid<Exec, WideCellKey>;

    // Throws SimulationError if an axis has more cells than even the 64-bit id holds.
    explicit NeighbourGrid(const GridSpec& spec)
        : grid_(needsWideCellIds(spec) ? Variant(std::in_place_type<Wide>, spec)
                                       : Variant(std::in_place_type<Narrow>, spec)) {}

    // Sorts particles by cell and builds the tables; see KeyedNeighbourGrid::build.
    void build(Exec& exec, const Real4* pos, Index n) {
        std::visit([&](auto& grid) { grid.build(exec, pos, n); }, grid_);
    }

    GridNeighbours view() const {
        return std::visit([](const auto& grid) { return grid.view(); }, grid_);
    }
    const Index* permutation() const {
        return std::visit([](const auto& grid) { return grid.permutation(); }, grid_);
    }
    const GridSpec& spec() const {
        return std::visit([](const auto& grid) -> const GridSpec& { return grid.spec(); }, grid_);
    }
    Index numCells() const {
        return std::visit([](const auto& grid) { return grid.numCells(); }, grid_);
    }
    Index numParticles() const {
        return std::visit([](const auto& grid) { return grid.numParticles(); }, grid_);
    }
    std::size_t bytesHeld() const {
        return std::visit([](const auto& grid) { return grid.bytesHeld(); }, grid_);
    }

    // 32 or 64: the width of this grid's cell ids.
    int cellIdBits() const { return std::holds_alternative<Wide>(grid_) ? 64 : 32; }
    // The grid with its cell ids, for tests and statistics; null if it uses the other width.
    template <class Key>
    const KeyedNeighbourGrid<Exec, Key>* keyed() const {
        return std::get_if<KeyedNeighbourGrid<Exec, Key>>(&grid_);
    }

   private:
    using Variant = std::variant<Narrow, Wide>;
    Variant grid_;
};

}  // namespace weir
