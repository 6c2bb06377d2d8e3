// Cell ids of paper §6.2: 32 bits, 2 unused, then Y, Z, X at 10 bits each; grids up to 1024^3.
#pragma once

#include <cmath>
#include <cstdint>

#include "core/config.h"
#include "core/vec3.h"

namespace weir {

constexpr int kCellBitsPerAxis = 10;
constexpr int kMaxCellsPerAxis = 1 << kCellBitsPerAxis;  // 1024
constexpr int kCellKeyBits = 3 * kCellBitsPerAxis;       // 30 used bits
constexpr CellKey kCellAxisMask = kMaxCellsPerAxis - 1;

struct CellCoord {
    int x = 0, y = 0, z = 0;
};

// Y occupies bits 20..29, Z bits 10..19 and X bits 0..9, so cells next to each other along X
// have consecutive ids: a row of three neighbour cells is one run of the sorted particles.
WEIR_HD constexpr CellKey encodeCell(int x, int y, int z) {
    return (CellKey(y) << (2 * kCellBitsPerAxis)) | (CellKey(z) << kCellBitsPerAxis) | CellKey(x);
}

WEIR_HD constexpr CellCoord decodeCell(CellKey key) {
    return {int(key & kCellAxisMask), int((key >> (2 * kCellBitsPerAxis)) & kCellAxisMask),
            int((key >> kCellBitsPerAxis) & kCellAxisMask)};
}

// The uniform grid over the container: origin, cell edge (>= smoothing radius) and size.
struct GridSpec {
    Vec3 origin;
    Real cellSize = 1;
    Real inverseCellSize = 1;
    int dims[3] = {1, 1, 1};

    // Cell of a position, clamped into the grid (positions on the far wall land in the last cell).
    WEIR_HD CellCoord cellOf(Real px, Real py, Real pz) const {
        auto axis = [&](Real p, Real o, int dim) {
            int c = int(std::floor((p - o) * inverseCellSize));
            return c < 0 ? 0 : (c >= dim ? dim - 1 : c);
        };
        return {axis(px, origin.x, dims[0]), axis(py, origin.y, dims[1]),
                axis(pz, origin.z, dims[2])};
    }
    WEIR_HD CellKey keyOf(Real px, Real py, Real pz) const {
        CellCoord c = cellOf(px, py, pz);
        return encodeCell(c.x, c.y, c.z);
    }
};

// Builds the grid spec for a box; throws SimulationError if an axis needs more than
// maxCellsPerAxis cells (by default the 1024 of the paper's cell id).
GridSpec makeGridSpec(const Vec3d& boxMin, const Vec3d& boxMax, double cellSize,
                      int maxCellsPerAxis = kMaxCellsPerAxis);

// The cells of `spec` that cover [lo, hi) along `axis` (at least one; infinite bounds reach the
// grid's ends), in the same places: a distributed run's rank needs only its slab's cells.
GridSpec sliceOf(const GridSpec& spec, int axis, double lo, double hi);

// Throws SimulationError if the grid does not fit the paper's 10-bit-per-axis cell ids.
void checkPaperCellIdRange(const GridSpec& spec);

// Cells in the whole grid.
inline std::uint64_t totalCells(const GridSpec& spec) {
    return std::uint64_t(spec.dims[0]) * std::uint64_t(spec.dims[1]) * std::uint64_t(spec.dims[2]);
}

}  // namespace weir
