// Cell ids of paper §6.2: 32 bits, 2 unused, then Y, Z, X at 10 bits each; grids up to 1024^3.
// Past that, the same layout in 64 bits at 21 bits per axis (1 unused bit).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <type_traits>

#include "core/config.h"
#include "core/vec3.h"

namespace weir {

// The bit layout of a cell id of type Key.
template <class Key>
struct CellIdLayout {
    static_assert(std::is_same_v<Key, std::uint32_t> || std::is_same_v<Key, std::uint64_t>,
                  "cell ids are std::uint32_t (the paper's) or std::uint64_t");
    static constexpr int bitsPerAxis = sizeof(Key) == 4 ? 10 : 21;
    static constexpr int maxCellsPerAxis = 1 << bitsPerAxis;
    static constexpr int keyBits = 3 * bitsPerAxis;  // used bits: 30 or 63
    static constexpr Key axisMask = Key(maxCellsPerAxis - 1);
};

constexpr int kCellBitsPerAxis = CellIdLayout<CellKey>::bitsPerAxis;              // 10
constexpr int kMaxCellsPerAxis = CellIdLayout<CellKey>::maxCellsPerAxis;          // 1024
constexpr int kCellKeyBits = CellIdLayout<CellKey>::keyBits;                      // 30 used bits
constexpr int kMaxWideCellsPerAxis = CellIdLayout<WideCellKey>::maxCellsPerAxis;  // 2^21

struct CellCoord {
    int x = 0, y = 0, z = 0;
};

// Y occupies the top used bits, then Z, then X in the lowest, so cells next to each other along
// X have consecutive ids: a row of three neighbour cells is one run of the sorted particles.
template <class Key = CellKey>
WEIR_HD constexpr Key encodeCell(int x, int y, int z) {
    constexpr int bits = CellIdLayout<Key>::bitsPerAxis;
    return (Key(y) << (2 * bits)) | (Key(z) << bits) | Key(x);
}

template <class Key>
WEIR_HD constexpr CellCoord decodeCell(Key key) {
    constexpr int bits = CellIdLayout<Key>::bitsPerAxis;
    constexpr Key mask = CellIdLayout<Key>::axisMask;
    return {int(key & mask), int((key >> (2 * bits)) & mask), int((key >> bits) & mask)};
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
            // Compared as a Real first: a huge or NaN position (a blow-up) must not reach int.
            const Real c = std::floor((p - o) * inverseCellSize);
            return c >= Real(dim) ? dim - 1 : (c >= Real(0) ? int(c) : 0);
        };
        return {axis(px, origin.x, dims[0]), axis(py, origin.y, dims[1]),
                axis(pz, origin.z, dims[2])};
    }
    template <class Key = CellKey>
    WEIR_HD Key keyOf(Real px, Real py, Real pz) const {
        CellCoord c = cellOf(px, py, pz);
        return encodeCell<Key>(c.x, c.y, c.z);
    }
};

// Builds the grid spec for a box; throws SimulationError if an axis needs more than
// maxCellsPerAxis cells (by default the 2^21 that the 64-bit cell id holds).
GridSpec makeGridSpec(const Vec3d& boxMin, const Vec3d& boxMax, double cellSize,
                      int maxCellsPerAxis = kMaxWideCellsPerAxis);

// The cells of `spec` that cover [lo, hi) along `axis` (at least one; infinite bounds reach the
// grid's ends), in the same places: a distributed run's rank needs only its slab's cells.
GridSpec sliceOf(const GridSpec& spec, int axis, double lo, double hi);

// Whether some axis has more cells than the paper's 32-bit id holds (1024): the sparse grid then
// uses 64-bit ids.
bool needsWideCellIds(const GridSpec& spec);

// "32-bit (10 bits per axis)" or "64-bit (21 bits per axis)": the cell id the sparse grid uses.
std::string cellIdDescription(const GridSpec& spec);

// Bytes of one cell id of the sparse grid over `spec`: 4, or 8 past 1024 cells on some axis.
inline std::size_t cellIdBytesFor(const GridSpec& spec) {
    return needsWideCellIds(spec) ? sizeof(WideCellKey) : sizeof(CellKey);
}

// Throws SimulationError if the grid does not fit cell ids of maxCellsPerAxis cells per axis.
void checkCellIdRange(const GridSpec& spec, int maxCellsPerAxis);

// Cells in the whole grid.
inline std::uint64_t totalCells(const GridSpec& spec) {
    return std::uint64_t(spec.dims[0]) * std::uint64_t(spec.dims[1]) * std::uint64_t(spec.dims[2]);
}

}  // namespace weir
