// A slab of space: the points whose coordinate along `axis` lies in [lo, hi), a distributed
// run's share of the domain for one rank (cluster/). The first and last slabs reach to -inf and
// +inf, so no particle is ever outside every slab. Host and device code.
#pragma once

#include <limits>

#include "core/config.h"
#include "core/vec3.h"

namespace weir {

struct Slab {
    int axis = 0;
    double lo = -std::numeric_limits<double>::infinity();
    double hi = std::numeric_limits<double>::infinity();

    WEIR_HD Real coordinate(const Real4& p) const {
        return axis == 0 ? p.x : (axis == 1 ? p.y : p.z);
    }
    WEIR_HD double coordinate(const Vec3d& p) const {
        return axis == 0 ? p.x : (axis == 1 ? p.y : p.z);
    }
    WEIR_HD bool contains(double c) const { return c >= lo && c < hi; }
    // Within `width` inside either border (a halo other ranks need), for a coordinate inside.
    WEIR_HD bool nearBorder(double c, double width) const {
        return c < lo + width || c >= hi - width;
    }
    bool everything() const {
        return lo == -std::numeric_limits<double>::infinity() &&
               hi == std::numeric_limits<double>::infinity();
    }
};

}  // namespace weir
