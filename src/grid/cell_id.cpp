// Grid sizing, and the choice between the paper's 32-bit cell id and the 64-bit one.
#include "grid/cell_id.h"

#include <algorithm>
#include <cmath>

#include "core/check.h"

namespace weir {

namespace {

const char* limitReason(int maxCellsPerAxis) {
    if (maxCellsPerAxis == kMaxCellsPerAxis) {
        return " that the 32-bit cell id of paper §6.2 holds";
    }
    if (maxCellsPerAxis == kMaxWideCellsPerAxis) {
        return " that the 64-bit cell id holds";
    }
    return " allowed";
}

void checkAxes(const int dims[3], double cellSize, int maxCellsPerAxis) {
    const char* axisName = "xyz";
    for (int a = 0; a < 3; ++a) {
        WEIR_REQUIRE(dims[a] <= maxCellsPerAxis,
                     "the container needs " << dims[a] << " grid cells along " << axisName[a]
                                            << " (cells of " << cellSize << " m), more than the "
                                            << maxCellsPerAxis << limitReason(maxCellsPerAxis)
                                            << "; use fewer particles or a smaller container");
    }
}

}  // namespace

bool needsWideCellIds(const GridSpec& spec) {
    return std::max({spec.dims[0], spec.dims[1], spec.dims[2]}) > kMaxCellsPerAxis;
}

std::string cellIdDescription(const GridSpec& spec) {
    return needsWideCellIds(spec)
               ? "64-bit (" + std::to_string(CellIdLayout<WideCellKey>::bitsPerAxis) +
                     " bits per axis)"
               : "32-bit (" + std::to_string(CellIdLayout<CellKey>::bitsPerAxis) +
                     " bits per axis)";
}

void checkCellIdRange(const GridSpec& spec, int maxCellsPerAxis) {
    checkAxes(spec.dims, double(spec.cellSize), maxCellsPerAxis);
}

GridSpec makeGridSpec(const Vec3d& boxMin, const Vec3d& boxMax, double cellSize,
                      int maxCellsPerAxis) {
    WEIR_REQUIRE(cellSize > 0 && std::isfinite(cellSize),
                 "grid cell size must be a positive number, got " << cellSize);
    GridSpec spec;
    spec.origin = Vec3(boxMin);
    spec.cellSize = Real(cellSize);
    spec.inverseCellSize = Real(1.0 / cellSize);
    for (int a = 0; a < 3; ++a) {
        double cells = std::ceil((boxMax[a] - boxMin[a]) / cellSize - 1e-9);
        spec.dims[a] = int(std::clamp(cells, 1.0, 2147483647.0));
    }
    checkAxes(spec.dims, cellSize, maxCellsPerAxis);
    return spec;
}

GridSpec sliceOf(const GridSpec& spec, int axis, double lo, double hi) {
    const double origin = double(spec.origin[axis]), size = double(spec.cellSize);
    const double cells = double(spec.dims[axis]);
    const double first = std::clamp(std::floor((lo - origin) / size), 0.0, cells - 1);
    const double end = std::clamp(std::ceil((hi - origin) / size), first + 1, cells);
    GridSpec slice = spec;
    slice.origin[axis] = Real(origin + first * size);
    slice.dims[axis] = int(end - first);
    return slice;
}

}  // namespace weir
