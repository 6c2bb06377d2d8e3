// weir's fast cell table: the same sort by cell as paper §6.2, but a dense array over every grid
// cell instead of a table of occupied cells and their 26 neighbours. cellBound[c] is the first
// particle (in cell order) whose cell is >= c, built by scattering run ends and a max-scan, so a
// row of three neighbour cells is the run [cellBound[first], cellBound[last + 1]): two loads per
// row, no binary search and no per-cell neighbour table. Its cells are h/2 wide, so a particle
// scans 25 rows of 5 cells, (2.5 h)^3 of space instead of the (3 h)^3 of 27 h-wide cells: 42%
// fewer candidates for the same neighbours. Used when the grid has at most a few cells per
// particle; it also lifts the 1024-cells-per-axis limit of the 32-bit id.
#pragma once

#include <cmath>

#include "core/config.h"
#include "core/vec3.h"
#include "grid/cell_id.h"
#include "grid/cell_sort.h"

namespace weir {

// Linear index of a cell, X fastest, then Z, then Y: the order of the paper's cell ids.
WEIR_HD inline CellKey denseCellIndex(int x, int y, int z, int nx, int nz) {
    return (CellKey(y) * CellKey(nz) + CellKey(z)) * CellKey(nx) + CellKey(x);
}

struct DenseGridNeighbours {
    const Index* cellBound;       // totalCells + 1 entries
    const CellKey* particleCell;  // linear cell of each (sorted) particle
    const Real4* pos;             // positions, in the same (sorted) order
    Vec3 origin;
    Real cellSize;
    Real h2;  // squared smoothing radius
    int nx, ny, nz;
    int reach;  // cells per smoothing radius: rows span +-reach cells

    // Calls f(j) for every particle j that can lie within h of particle i (i included): the
    // X runs of the 5 x 5 rows around i's cell, less the rows whose (Y, Z) slab is farther than
    // h (the 4 corner rows and more near slab edges). Cutting each run further to the sphere's
    // chord visits fewer candidates but measured slower (bench/NOTES.md: the branchy bounds cost
    // more than the candidates they save), so runs stay whole.
    template <class F>
    WEIR_HD void forEachCandidate(Index i, F&& f) const {
        const CellKey cell = particleCell[i];
        const int cx = int(cell % CellKey(nx));
        const CellKey rest = cell / CellKey(nx);
        const int cz = int(rest % CellKey(nz)), cy = int(rest / CellKey(nz));
        const Real4 p = pos[i];
        const int yLo = cy >= reach ? cy - reach : 0, yHi = cy + reach < ny ? cy + reach : ny - 1;
        const int zLo = cz >= reach ? cz - reach : 0, zHi = cz + reach < nz ? cz + reach : nz - 1;
        for (int y = yLo; y <= yHi; ++y) {
            const Real dy = slabDistance(p.y, origin.y + Real(y) * cellSize);
            const Real remY = h2 - dy * dy;
            if (remY <= Real(0)) {
                continue;
            }
            for (int z = zLo; z <= zHi; ++z) {
                const Real dz = slabDistance(p.z, origin.z + Real(z) * cellSize);
                const Real rem = remY - dz * dz;
                if (rem <= Real(0)) {
                    continue;
                }
                const int xLo = cx >= reach ? cx - reach : 0;
                const int xHi = cx + reach < nx ? cx + reach : nx - 1;
                const CellKey row = denseCellIndex(0, y, z, nx, nz);
                const Index end = cellBound[row + CellKey(xHi) + 1];
                for (Index j = cellBound[row + CellKey(xLo)]; j < end; ++j) {
                    f(j);
                }
            }
        }
    }

    // Distance from coordinate v to the slab [lo, lo + cellSize] (0 inside).
    WEIR_HD Real slabDistance(Real v, Real lo) const {
        const Real hi = lo + cellSize;
        return v < lo ? lo - v : (v > hi ? v - hi : Real(0));
    }
};

constexpr int kDenseCellsPerRadius = 2;

// Whether the dense table suits a grid of h-wide cells for n particles: at most 8 of its h/2
// cells per particle (plus a floor for small runs), and linear indices that fit in 31 bits.
inline bool denseGridSuits(const GridSpec& radiusGrid, std::int64_t n) {
    const std::uint64_t cells =
        totalCells(radiusGrid) * kDenseCellsPerRadius * kDenseCellsPerRadius * kDenseCellsPerRadius;
    return cells < (std::uint64_t(1) << 31) && cells <= std::uint64_t(8 * n + (1 << 20));
}

template <class Exec>
class DenseGrid {
   public:
    template <class T>
    using Buffer = typename Exec::template Buffer<T>;

    static constexpr int kCellsPerRadius = kDenseCellsPerRadius;

    // spec: cells of h / cellsPerRadius.
    DenseGrid(const GridSpec& spec, int cellsPerRadius) : spec_(spec), reach_(cellsPerRadius) {}

    void build(Exec& exec, const Real4* pos, Index n) {
        sort_.prepare(n);
        const std::uint64_t cells = totalCells(spec_);
        cellBound_.resize(std::size_t(cells + 1));  // the grid does not change size
        const GridSpec spec = spec_;
        const int nx = spec.dims[0], nz = spec.dims[2];
        CellKey* keys = sort_.keys();
        exec.forEach(n, [=] WEIR_HD(Index i) {
            CellCoord c = spec.cellOf(pos[i].x, pos[i].y, pos[i].z);
            keys[i] = denseCellIndex(c.x, c.y, c.z, nx, nz);
        });
        sort_.sort(exec, bitsFor(cells));
        // cellBound[c + 1] = one past the last particle of cell c, where c is occupied; then a
        // running max fills the empty cells with the bound of the last occupied one before them.
        Index* bound = cellBound_.data();
        const CellKey* sorted = sort_.sortedKeys();
        exec.forEach(Index(cells + 1), [=] WEIR_HD(Index c) { bound[c] = 0; });
        exec.forEach(n, [=] WEIR_HD(Index i) {
            if (i == n - 1 || sorted[i] != sorted[i + 1]) {
                bound[sorted[i] + 1] = i + 1;
            }
        });
        exec.inclusiveMaxScan(bound, Index(cells + 1));
    }

    // The neighbour view for positions `pos` in cell order and smoothing radius h.
    DenseGridNeighbours view(const Real4* pos, Real h) const {
        return {cellBound_.data(),
                sort_.sortedKeys(),
                pos,
                spec_.origin,
                spec_.cellSize,
                h * h,
                spec_.dims[0],
                spec_.dims[1],
                spec_.dims[2],
                reach_};
    }
    const Index* permutation() const { return sort_.permutation(); }
    const GridSpec& spec() const { return spec_; }
    const Buffer<Index>& cellBound() const { return cellBound_; }
    std::size_t bytesHeld() const { return sort_.bytesHeld() + cellBound_.size() * sizeof(Index); }

   private:
    GridSpec spec_;
    int reach_;
    CellSort<Exec> sort_;
    Buffer<Index> cellBound_;
};

}  // namespace weir
