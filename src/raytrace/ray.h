// Rays and the small vector helpers of the ray tracer (colours are linear RGB in a Vec3f), written
// once for the CPU and CUDA.
#pragma once

#include <cmath>

#include "core/config.h"
#include "core/vec3.h"

namespace weir {

// A half-line: origin + t direction for t > 0; direction is unit length.
struct Ray {
    Vec3f origin;
    Vec3f direction;
};

WEIR_HD inline Vec3f normalized(const Vec3f& v) { return v * (1.0f / std::sqrt(dot(v, v))); }

// Channel by channel: a colour filtered by a reflectance or a transmittance.
WEIR_HD inline Vec3f times(const Vec3f& a, const Vec3f& b) {
    return {a.x * b.x, a.y * b.y, a.z * b.z};
}

WEIR_HD inline float largestOf(const Vec3f& v) { return fmaxf(v.x, fmaxf(v.y, v.z)); }

// The mirror image of direction d about the plane of unit normal n.
WEIR_HD inline Vec3f reflected(const Vec3f& d, const Vec3f& n) {
    return d - n * (2.0f * dot(d, n));
}

// Two unit vectors that make a right-handed orthonormal frame with the unit vector n (Duff et al.
// 2017, "Building an orthonormal basis, revisited": no branch on a threshold, no division by 0).
WEIR_HD inline void tangentsOf(const Vec3f& n, Vec3f& t, Vec3f& b) {
    const float sign = copysignf(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float c = n.x * n.y * a;
    t = Vec3f(1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x);
    b = Vec3f(c, sign + n.y * n.y * a, -n.y);
}

}  // namespace weir
