// A small 3-vector usable on host and device.
#pragma once

#include <cmath>

#include "core/config.h"

namespace weir {

template <class T>
struct Vec3T {
    T x{}, y{}, z{};

    WEIR_HD constexpr Vec3T() = default;
    WEIR_HD constexpr Vec3T(T x_, T y_, T z_) : x(x_), y(y_), z(z_) {}
    template <class U>
    WEIR_HD constexpr explicit Vec3T(const Vec3T<U>& o) : x(T(o.x)), y(T(o.y)), z(T(o.z)) {}

    WEIR_HD constexpr T& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
    WEIR_HD constexpr T operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }

    WEIR_HD constexpr Vec3T operator+(const Vec3T& o) const { return {x + o.x, y + o.y, z + o.z}; }
    WEIR_HD constexpr Vec3T operator-(const Vec3T& o) const { return {x - o.x, y - o.y, z - o.z}; }
    WEIR_HD constexpr Vec3T operator-() const { return {-x, -y, -z}; }
    WEIR_HD constexpr Vec3T operator*(T s) const { return {x * s, y * s, z * s}; }
    WEIR_HD constexpr Vec3T operator/(T s) const { return {x / s, y / s, z / s}; }
    WEIR_HD constexpr Vec3T& operator+=(const Vec3T& o) {
        x += o.x;
        y += o.y;
        z += o.z;
        return *this;
    }
    WEIR_HD constexpr Vec3T& operator-=(const Vec3T& o) {
        x -= o.x;
        y -= o.y;
        z -= o.z;
        return *this;
    }
    WEIR_HD constexpr Vec3T& operator*=(T s) {
        x *= s;
        y *= s;
        z *= s;
        return *this;
    }
};

template <class T>
WEIR_HD constexpr Vec3T<T> operator*(T s, const Vec3T<T>& v) {
    return v * s;
}
template <class T>
WEIR_HD constexpr T dot(const Vec3T<T>& a, const Vec3T<T>& b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <class T>
WEIR_HD constexpr T lengthSquared(const Vec3T<T>& a) {
    return dot(a, a);
}
template <class T>
WEIR_HD inline T length(const Vec3T<T>& a) {
    return std::sqrt(dot(a, a));
}

template <class T>
WEIR_HD constexpr Vec3T<T> cross(const Vec3T<T>& a, const Vec3T<T>& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

using Vec3 = Vec3T<Real>;
using Vec3d = Vec3T<double>;
using Vec3f = Vec3T<float>;

// A 3-vector padded to 16 (float) or 32 (double) bytes, so that one particle's position or
// velocity is one aligned vector load on the GPU. w is free for a scalar.
struct alignas(4 * sizeof(Real)) Real4 {
    Real x, y, z, w;

    WEIR_HD Vec3 xyz() const { return {x, y, z}; }
    WEIR_HD static Real4 from(const Vec3& v, Real w = 0) { return {v.x, v.y, v.z, w}; }
};

}  // namespace weir
