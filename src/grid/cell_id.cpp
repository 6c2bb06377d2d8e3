// Grid sizing with the paper's 10-bit-per-axis limit.
#include "grid/cell_id.h"

#include <algorithm>
#include <cmath>

#include "core/check.h"

namespace weir {

GridSpec makeGridSpec(const Vec3d& boxMin, const Vec3d& boxMax, double cellSize) {
    WEIR_REQUIRE(cellSize > 0 && std::isfinite(cellSize),
                 "grid cell size must be a positive number, got " << cellSize);
    GridSpec spec;
    spec.origin = Vec3(boxMin);
    spec.cellSize = Real(cellSize);
    spec.inverseCellSize = Real(1.0 / cellSize);
    const char* axisName = "xyz";
    for (int a = 0; a < 3; ++a) {
        double extent = boxMax[a] - boxMin[a];
        double cells = std::ceil(extent / cellSize - 1e-9);
        WEIR_REQUIRE(cells <= kMaxCellsPerAxis,
                     "the container needs " << cells << " grid cells along " << axisName[a]
                                            << " (extent " << extent << " m / cell " << cellSize
                                            << " m), more than the " << kMaxCellsPerAxis
                                            << " that the 32-bit cell id of paper §6.2 holds; "
                                               "use fewer particles or a smaller container");
        spec.dims[a] = std::max(1, int(cells));
    }
    return spec;
}

}  // namespace weir
