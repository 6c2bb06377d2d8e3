// A neighbour grid over one fluid frame on the host, for whitewater's queries at arbitrary points
// (fluid particles and diffuse particles alike): cells of half the query radius over the fluid's
// bounding box, the particles counting-sorted into them. The solver's grid (grid/) lives in the
// simulation's store and is built for its own particles; this one is built once per frame read.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "core/vec3.h"
#include "solver/particles.h"

namespace weir {

class FluidGrid {
   public:
    // Particles within `radius` of a query point are its neighbours.
    FluidGrid(const HostParticles& fluid, double radius);

    double radius() const { return radius_; }
    std::size_t size() const { return sortedPosition_.size(); }

    // Calls visit(j, r2) for every fluid particle j (its index in the frame) whose squared
    // distance r2 from p is below radius^2; in a fixed order for a given frame and p.
    template <class Visit>
    void forEachWithin(const Vec3d& p, Visit&& visit) const {
        if (sortedPosition_.empty()) {
            return;
        }
        const double r2max = radius_ * radius_;
        int lo[3], hi[3];
        for (int a = 0; a < 3; ++a) {
            const double c = (p[a] - origin_[a]) / cellSize_;
            if (!(c > -reach_ - 1.0) || !(c < double(dims_[a]) + reach_ + 1.0)) {
                return;  // further than the radius from every fluid particle (or not finite)
            }
            const int cell = int(std::floor(c));
            lo[a] = cell - reach_ < 0 ? 0 : cell - reach_;
            hi[a] = cell + reach_ >= dims_[a] ? dims_[a] - 1 : cell + reach_;
        }
        for (int z = lo[2]; z <= hi[2]; ++z) {
            for (int y = lo[1]; y <= hi[1]; ++y) {
                const std::size_t row = (std::size_t(z) * std::size_t(dims_[1]) + std::size_t(y)) *
                                        std::size_t(dims_[0]);
                const std::uint32_t end = cellStart_[row + std::size_t(hi[0]) + 1];
                for (std::uint32_t k = cellStart_[row + std::size_t(lo[0])]; k < end; ++k) {
                    const Vec3d d = Vec3d(sortedPosition_[k]) - p;
                    const double r2 = dot(d, d);
                    if (r2 < r2max) {
                        visit(std::size_t(sortedIndex_[k]), r2);
                    }
                }
            }
        }
    }

   private:
    double radius_, cellSize_;
    Vec3d origin_;
    int dims_[3] = {0, 0, 0};
    int reach_ = 1;                           // cells searched on each side of the query's cell
    std::vector<std::uint32_t> cellStart_;    // cell c holds [cellStart_[c], cellStart_[c + 1])
    std::vector<Vec3f> sortedPosition_;       // in cell order
    std::vector<std::uint32_t> sortedIndex_;  // the frame's index of each, in cell order
};

}  // namespace weir
