// weir's fast cell table: particles grouped by cell as in paper §6.2, but with a dense array over
// every grid cell instead of a table of occupied cells and their 26 neighbours. cellBound[c] is
// the first particle (in cell order) whose cell is >= c, so a row of neighbour cells is the run
// [cellBound[first], cellBound[last + 1]): two loads per row, no binary search and no per-cell
// neighbour table. With cells h/2 wide a particle scans 25 rows of 5 cells, (2.5 h)^3 of space
// instead of the (3 h)^3 of 27 h-wide cells: 42% fewer candidates for the same neighbours.
//
// The grouping is a counting sort rather than a radix sort: the cell count is known, so one pass
// counts particles per cell (each particle taking a ticket), a prefix sum over the counts is the
// cell table itself, and each particle's place follows from its cell's start. Tickets come from
// atomics in whatever order threads run, so a second pass ranks the particles of a cell by their
// current index: the order is that of a stable sort, the same on every run and every backend.
// It also lifts the 1024-cells-per-axis limit of the 32-bit id (cells are linear indices).
#pragma once

#include <cmath>

#include "core/atomics.h"
#include "core/config.h"
#include "core/team.h"
#include "core/vec3.h"
#include "grid/cell_id.h"
#include "grid/cell_walk.h"

namespace weir {

struct DenseGridNeighbours {
    CellTableView cells;  // the cells the particles were grouped by (grid/cell_walk.h)
    const Real4* pos;     // positions, in cell order
    Real h2;              // squared smoothing radius
    int reach;            // cells per smoothing radius: rows span +-reach cells

    // Calls f(j) for every particle j that can lie within h of particle i (i included): the
    // X runs of the 5 x 5 rows around i's cell (with h/2 cells), less the rows whose (Y, Z) slab
    // is farther than h. The cell of i is the same function of the same position as in the
    // build: the cell it was grouped in. A team of several lanes (core/team.h) splits each run
    // between its lanes.
    template <class F, int TeamSize = 1>
    WEIR_HD void forEachCandidate(Index i, F&& f, Team<TeamSize> team = {}) const {
        cells.forEachRun(pos[i].xyz(), reach, h2, [&](Index first, Index end) {
            for (Index j = first + team.first(); j < end; j += TeamSize) {
                f(j);
            }
        });
    }

    // Calls f(j) for every particle j that can lie within h of the point p.
    template <class F>
    WEIR_HD void forEachNearPoint(const Vec3& p, F&& f) const {
        cells.forEachRun(p, reach, h2, [&](Index first, Index end) {
            for (Index j = first; j < end; ++j) {
                f(j);
            }
        });
    }
};

// Cells per smoothing radius of the dense table for a grid of h-wide cells and n particles: 2 (h/2
// cells, the fastest) while that means at most 8 cells per particle (plus a floor for small runs),
// else 1 (h cells: 8 times fewer, for huge sparse domains); 0 if even that needs 2^31 cells or
// more, where the paper's sparse cell table must serve.
inline int denseCellsPerRadius(const GridSpec& radiusGrid, std::int64_t n) {
    const std::uint64_t cells = totalCells(radiusGrid);
    const std::uint64_t limit = std::uint64_t(1) << 31;
    if (cells * 8 < limit && cells * 8 <= std::uint64_t(8 * n + (1 << 20))) {
        return 2;
    }
    return cells < limit ? 1 : 0;
}

// Whether the dense table suits a grid of h-wide cells for n particles.
inline bool denseGridSuits(const GridSpec& radiusGrid, std::int64_t n) {
    return denseCellsPerRadius(radiusGrid, n) > 0;
}

// The grid of the dense table: the h-wide grid's box cut into cells of h / cellsPerRadius.
inline GridSpec denseGridSpec(const GridSpec& radiusGrid, int cellsPerRadius) {
    const Vec3d origin(radiusGrid.origin);
    const Vec3d extent = Vec3d(radiusGrid.dims[0], radiusGrid.dims[1], radiusGrid.dims[2]) *
                         double(radiusGrid.cellSize);
    return makeGridSpec(origin, origin + extent, double(radiusGrid.cellSize) / cellsPerRadius,
                        1 << 21);
}

template <class Exec>
class DenseGrid {
   public:
    template <class T>
    using Buffer = typename Exec::template Buffer<T>;

    // spec: cells of h / cellsPerRadius.
    DenseGrid(const GridSpec& spec, int cellsPerRadius) : spec_(spec), reach_(cellsPerRadius) {}

    // Groups the particles at `pos` by cell; permutation() then gives the cell order.
    void build(Exec& exec, const Real4* pos, Index n) {
        permutation_.resize(std::size_t(n));
        Index* permutation = permutation_.data();
        build(exec, pos, n, [=] WEIR_HD(Index from, Index to) { permutation[to] = from; });
    }

    // Groups the particles by cell and calls place(from, to) once per particle, with its index
    // now and its index in cell order: the caller moves its data there in the same pass.
    template <class Place>
    void build(Exec& exec, const Real4* pos, Index n, Place place) {
        build(exec, pos, n, place, [] WEIR_HD(Index) { return false; });
    }

    // The same, leaving out the particles for which discard(i) holds: they go to a cell past the
    // last one and are not placed, so the kept ones fill [0, keptCount()). A distributed run
    // drops last step's ghosts and the particles that left its slab this way, in the pass that
    // moves every particle anyway.
    template <class Place, class Discard>
    void build(Exec& exec, const Real4* pos, Index n, Place place, Discard discard) {
        build(exec, pos, n, place, discard, [] WEIR_HD() {});
    }

    // The same, calling once() from one thread of the build's first pass: a one-thread task that
    // would otherwise be a launch of its own (the solver's start of a step).
    template <class Place, class Discard, class Once>
    void build(Exec& exec, const Real4* pos, Index n, Place place, Discard discard, Once once) {
        // The particle count does not change between steps, nor does the grid.
        keys_.resize(std::size_t(n));
        tickets_.resize(std::size_t(n));
        slotParticle_.resize(std::size_t(n));
        const std::uint64_t cells = totalCells(spec_);
        cellBound_.resize(std::size_t(cells + 2));  // + the discarded particles' cell
        const GridSpec spec = spec_;
        const int nx = spec.dims[0], nz = spec.dims[2];
        const CellKey discarded = CellKey(cells);
        CellKey* keys = keys_.data();
        Index* ticket = tickets_.data();
        Index* bound = cellBound_.data();
        Index* slotParticle = slotParticle_.data();
        // 1. Count: bound[c + 1] = particles in cell c; each particle's ticket is its arrival.
        exec.forEach(Index(cells + 2), [=] WEIR_HD(Index c) {
            bound[c] = 0;
            if (c == 0) {
                once();
            }
        });
        exec.forEach(n, [=] WEIR_HD(Index i) {
            if (discard(i)) {
                keys[i] = discarded;  // not counted: no ticket, no place (and no atomic on one
                return;               // shared counter by every discarded particle)
            }
            const CellCoord c = spec.cellOf(pos[i].x, pos[i].y, pos[i].z);
            const CellKey key = denseCellIndex(c.x, c.y, c.z, nx, nz);
            keys[i] = key;
            ticket[i] = atomicFetchAdd(&bound[key + 1], Index(1));
        });
        // 2. The prefix sum of the counts: bound[c] = first particle of cell c.
        exec.inclusiveScan(bound, bound, Index(cells + 2));
        // 3. Place by ticket, then order each cell by current index (the order of a stable sort).
        // A cell of more than kMaxRankedCell particles (a pile-up in a broken run) keeps its
        // ticket order rather than cost a quadratic ranking.
        exec.forEach(n, [=] WEIR_HD(Index i) {
            if (keys[i] != discarded) {
                slotParticle[bound[keys[i]] + ticket[i]] = i;
            }
        });
        exec.forEach(n, [=] WEIR_HD(Index slot) {
            if (slot >= bound[discarded]) {
                return;  // past the kept particles
            }
            const Index i = slotParticle[slot];
            const CellKey key = keys[i];
            const Index first = bound[key], end = bound[key + 1];
            if (end - first > kMaxRankedCell) {
                place(i, slot);
                return;
            }
            Index rank = 0;
            for (Index s = first; s < end; ++s) {
                rank += slotParticle[s] < i ? 1 : 0;
            }
            place(i, first + rank);
        });
    }

    // After build(): how many particles were kept (read back from the device).
    Index keptCount(Exec& exec) const {
        return exec.readOne(cellBound_, std::size_t(totalCells(spec_)));
    }

    // Another box of cells of the same size (a distributed run's slab moved): buffers are kept.
    void setSpec(const GridSpec& spec) { spec_ = spec; }

    // The cell table alone (grid/cell_walk.h), for queries around any point.
    CellTableView cells() const { return {cellBound_.data(), spec_}; }
    // The neighbour view for positions `pos` in cell order and smoothing radius h.
    DenseGridNeighbours view(const Real4* pos, Real h) const {
        return {{cellBound_.data(), spec_}, pos, h * h, reach_};
    }
    // After build(exec, pos, n): the old index of the particle that is k-th in cell order.
    const Index* permutation() const { return permutation_.data(); }
    const GridSpec& spec() const { return spec_; }
    int cellsPerRadius() const { return reach_; }
    const Buffer<Index>& cellBound() const { return cellBound_; }
    std::size_t bytesHeld() const {
        return keys_.size() * sizeof(CellKey) +
               (tickets_.size() + slotParticle_.size() + permutation_.size() + cellBound_.size()) *
                   sizeof(Index);
    }

   private:
    static constexpr Index kMaxRankedCell = 256;

    GridSpec spec_;
    int reach_;
    Buffer<CellKey> keys_;
    Buffer<Index> tickets_, slotParticle_, permutation_, cellBound_;
};

}  // namespace weir
