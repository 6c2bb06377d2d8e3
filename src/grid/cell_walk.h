// The one walk over a dense cell table, shared by every neighbour query in weir: the solver's
// neighbour search (grid/dense_grid.h), the boundary particles (physics/boundary.h) and the
// surface field (surface/surface_field.h). A table of cells numbered X fastest, then Z, then Y
// (the order of the paper's cell ids, grid/cell_id.h) holds for each cell c the first element of
// c in cell order, cellBound[c], and the next cell's first as its end; the cells of one X row are
// then one run of elements, two table loads per row. A query visits the rows of cells within
// `reach` cells of its own whose (Y, Z) slab lies within the radius, so the corner rows of the
// square (and more near slab edges) are skipped.
#pragma once

#include <cmath>

#include "core/config.h"
#include "core/vec3.h"
#include "grid/cell_id.h"

namespace weir {

// Linear index of a cell, X fastest, then Z, then Y.
WEIR_HD inline CellKey denseCellIndex(int x, int y, int z, int nx, int nz) {
    return (CellKey(y) * CellKey(nz) + CellKey(z)) * CellKey(nx) + CellKey(x);
}

// floor() as an int without a library call.
WEIR_HD inline int floorToInt(Real v) {
    const int t = int(v);
    return t - (v < Real(t) ? 1 : 0);
}

struct CellTableView {
    const Index* cellBound;  // at least cells + 1 entries: cell c holds [cellBound[c], [c + 1])
    GridSpec spec;           // the cells

    // Calls run(first, end) for each X run of cells around the cell of p (clamped into the grid)
    // within `reach` cells along each axis, whose (Y, Z) slab lies within sqrt(radius2) of p.
    // Runs span the whole [x - reach, x + reach] by default: cutting each run to the sphere's
    // chord visits fewer candidates but measured slower in the solver's loops (bench/NOTES.md:
    // the branchy bounds cost more than the candidates they save). CutToChord cuts them, for
    // queries with a wide reach (the surface field). Plain nested loops: the same walk written as
    // a row iterator measured 16% slower on the GPU.
    template <bool CutToChord = false, class Run>
    WEIR_HD void forEachRun(const Vec3& p, int reach, Real radius2, Run&& run) const {
        const CellCoord c = spec.cellOf(p.x, p.y, p.z);
        const int nx = spec.dims[0], ny = spec.dims[1], nz = spec.dims[2];
        const int yLo = c.y >= reach ? c.y - reach : 0;
        const int yHi = c.y + reach < ny ? c.y + reach : ny - 1;
        const int zLo = c.z >= reach ? c.z - reach : 0;
        const int zHi = c.z + reach < nz ? c.z + reach : nz - 1;
        int xLo = c.x >= reach ? c.x - reach : 0;
        int xHi = c.x + reach < nx ? c.x + reach : nx - 1;
        for (int y = yLo; y <= yHi; ++y) {
            const Real dy = slabDistance(p.y, spec.origin.y + Real(y) * spec.cellSize);
            const Real remY = radius2 - dy * dy;
            if (remY <= Real(0)) {
                continue;
            }
            for (int z = zLo; z <= zHi; ++z) {
                const Real dz = slabDistance(p.z, spec.origin.z + Real(z) * spec.cellSize);
                const Real rem = remY - dz * dz;
                if (rem <= Real(0)) {
                    continue;
                }
                if constexpr (CutToChord) {
                    const Real halfChord = std::sqrt(rem);
                    xLo = floorToInt((p.x - halfChord - spec.origin.x) * spec.inverseCellSize);
                    xHi = floorToInt((p.x + halfChord - spec.origin.x) * spec.inverseCellSize);
                    xLo = xLo < 0 ? 0 : xLo;
                    xHi = xHi > nx - 1 ? nx - 1 : xHi;
                    if (xLo > xHi) {
                        continue;
                    }
                }
                const CellKey rowStart = denseCellIndex(0, y, z, nx, nz);
                run(cellBound[rowStart + CellKey(xLo)], cellBound[rowStart + CellKey(xHi) + 1]);
            }
        }
    }

    // Distance from coordinate v to the slab [lo, lo + cellSize] (0 inside).
    WEIR_HD Real slabDistance(Real v, Real lo) const {
        const Real hi = lo + spec.cellSize;
        return v < lo ? lo - v : (v > hi ? v - hi : Real(0));
    }
};

}  // namespace weir
