// FluidGrid's build: the bounding box, the cells, a counting sort.
#include "whitewater/fluid_grid.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace weir {

FluidGrid::FluidGrid(const HostParticles& fluid, double radius)
    : radius_(radius), cellSize_(radius / 2) {
    if (!(radius > 0) || !std::isfinite(radius)) {
        throw std::invalid_argument("FluidGrid: the radius must be > 0");
    }
    const std::size_t n = fluid.size();
    if (n == 0) {
        return;
    }
    if (n >= std::size_t(UINT32_MAX)) {
        throw std::invalid_argument("FluidGrid: too many particles for 32-bit cell tables");
    }
    Vec3d lo(INFINITY, INFINITY, INFINITY), hi(-INFINITY, -INFINITY, -INFINITY);
    for (std::size_t i = 0; i < n; ++i) {
        const Vec3d x(fluid.x[i], fluid.y[i], fluid.z[i]);
        for (int a = 0; a < 3; ++a) {
            lo[a] = std::min(lo[a], x[a]);
            hi[a] = std::max(hi[a], x[a]);
        }
    }
    // Cells of half the radius, searched two on each side: 125 cells of (h / 2)^3 hold 42% fewer
    // candidates than 27 of h^3. Unless a few stray particles stretch the box so far that the table
    // would outgrow the particles many times over: then coarser cells, searched further out.
    const auto cellsAt = [&](double size) {
        double cells = 1;
        for (int a = 0; a < 3; ++a) {
            cells *= std::floor((hi[a] - lo[a]) / size) + 1;
        }
        return cells;
    };
    const double most = 8.0 * double(n) + 4096.0;
    while (cellsAt(cellSize_) > most) {
        cellSize_ *= 1.5;
    }
    reach_ = std::max(1, int(std::ceil(radius_ / cellSize_)));
    origin_ = lo;
    for (int a = 0; a < 3; ++a) {
        dims_[a] = int(std::floor((hi[a] - lo[a]) / cellSize_)) + 1;
    }
    const std::size_t cells = std::size_t(dims_[0]) * std::size_t(dims_[1]) * std::size_t(dims_[2]);
    std::vector<std::uint32_t> cellOf(n);
    cellStart_.assign(cells + 1, 0);
    for (std::size_t i = 0; i < n; ++i) {
        int c[3];
        const double x[3] = {double(fluid.x[i]), double(fluid.y[i]), double(fluid.z[i])};
        for (int a = 0; a < 3; ++a) {
            c[a] = std::clamp(int((x[a] - origin_[a]) / cellSize_), 0, dims_[a] - 1);
        }
        cellOf[i] = std::uint32_t((std::size_t(c[2]) * std::size_t(dims_[1]) + std::size_t(c[1])) *
                                      std::size_t(dims_[0]) +
                                  std::size_t(c[0]));
        ++cellStart_[cellOf[i] + 1];
    }
    for (std::size_t c = 0; c < cells; ++c) {
        cellStart_[c + 1] += cellStart_[c];
    }
    std::vector<std::uint32_t> next(cellStart_.begin(), cellStart_.end() - 1);
    sortedPosition_.resize(n);
    sortedIndex_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        const std::uint32_t k = next[cellOf[i]]++;
        sortedPosition_[k] = Vec3f(float(fluid.x[i]), float(fluid.y[i]), float(fluid.z[i]));
        sortedIndex_[k] = std::uint32_t(i);
    }
}

}  // namespace weir
