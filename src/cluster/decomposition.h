// How a distributed run splits the domain: slabs along one axis (the container's longest), one
// per rank, with borders placed so that each slab holds the same number of particles, moved as
// the fluid flows. Pure arithmetic on counts: no MPI here.
#pragma once

#include <cstdint>
#include <vector>

#include "core/slab.h"
#include "core/vec3.h"

namespace weir {

// Particle counts in equal bins along an axis: bin b covers [lo + b w, lo + (b + 1) w).
struct AxisHistogram {
    int axis = 0;
    double lo = 0, binWidth = 1;
    std::vector<std::int64_t> counts;

    std::int64_t total() const;
};

class Decomposition {
   public:
    // `borders` has ranks - 1 inner borders, increasing.
    Decomposition(int axis, std::vector<double> innerBorders);

    int ranks() const { return int(inner_.size()) + 1; }
    int axis() const { return axis_; }
    const std::vector<double>& innerBorders() const { return inner_; }
    Slab slab(int rank) const;
    // The rank whose slab holds coordinate c (a NaN goes to `fallback`).
    int ownerOf(double c, int fallback) const;
    // Calls f(r) for each rank r other than `self` whose slab, widened by `width` on both
    // sides, holds coordinate c: the ranks that need a ghost copy of a particle there.
    template <class F>
    void forEachRankNear(double c, double width, int self, F&& f) const {
        for (int r = 0; r < ranks(); ++r) {
            const Slab s = slab(r);
            if (r != self && c >= s.lo - width && c < s.hi + width) {
                f(r);
            }
        }
    }

   private:
    int axis_;
    std::vector<double> inner_;
};

// The longest axis of a box (0 = x, 1 = y, 2 = z; the first of equals).
int longestAxis(const Vec3& boxMin, const Vec3& boxMax);

// Borders that give each of `ranks` slabs an equal share of the histogram's particles
// (interpolated inside a bin); slabs of a histogram with no particles are equally wide.
Decomposition balancedDecomposition(const AxisHistogram& histogram, int ranks);

// max / mean of per-rank counts (1 = perfectly balanced; 1 when there are no particles).
double imbalance(const std::vector<std::int64_t>& perRank);

// Particles per rank of a decomposition, counted from a histogram by bin centres.
std::vector<std::int64_t> countsPerRank(const AxisHistogram& histogram,
                                        const Decomposition& decomposition);

}  // namespace weir
