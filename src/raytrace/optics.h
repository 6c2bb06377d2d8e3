// The optics of a smooth water surface and of matte surfaces: Fresnel reflectance, Snell
// refraction, Beer-Lambert absorption, and the direction samplers of the path tracer.
#pragma once

#include <cmath>

#include "raytrace/ray.h"

namespace weir {

// pi in float (physics/kernels.h has kPi, a double).
constexpr float kPiF = 3.14159265358979323846f;

// Fraction of unpolarised light reflected at a smooth interface (Fresnel's equations, the mean
// of the s and p reflectances), for light arriving at cosIncident > 0 to the normal from a medium
// of index n1 into one of index n2; 1 beyond the critical angle (total internal reflection).
WEIR_HD inline float fresnelReflectance(float cosIncident, float n1, float n2) {
    const float cosI = fminf(fmaxf(cosIncident, 0.0f), 1.0f);
    const float eta = n1 / n2;
    const float sin2T = eta * eta * (1.0f - cosI * cosI);
    if (sin2T >= 1.0f) {
        return 1.0f;
    }
    const float cosT = std::sqrt(1.0f - sin2T);
    const float rs = (n1 * cosI - n2 * cosT) / (n1 * cosI + n2 * cosT);
    const float rp = (n1 * cosT - n2 * cosI) / (n1 * cosT + n2 * cosI);
    return 0.5f * (rs * rs + rp * rp);
}

// Snell's law: the direction of unit d refracted through a surface of unit normal n (facing
// against d: dot(d, n) < 0) from index n1 into n2 (eta = n1 / n2). False at total internal
// reflection, and out is left as it was.
WEIR_HD inline bool refracted(const Vec3f& d, const Vec3f& n, float eta, Vec3f& out) {
    const float cosI = -dot(d, n);
    const float sin2T = eta * eta * (1.0f - cosI * cosI);
    if (sin2T >= 1.0f) {
        return false;
    }
    out = normalized(d * eta + n * (eta * cosI - std::sqrt(1.0f - sin2T)));
    return true;
}

// Beer-Lambert: the fraction of light per channel left after `distance` metres in a medium of
// absorption coefficients `absorption` (1/m).
WEIR_HD inline Vec3f transmittance(const Vec3f& absorption, float distance) {
    return {std::exp(-absorption.x * distance), std::exp(-absorption.y * distance),
            std::exp(-absorption.z * distance)};
}

// A direction about unit n with density cos(theta) / pi (Malley's method), from two uniform
// numbers: the sampler of a Lambertian surface, whose weight is then just its albedo.
WEIR_HD inline Vec3f cosineWeightedDirection(const Vec3f& n, float u1, float u2) {
    Vec3f t, b;
    tangentsOf(n, t, b);
    const float r = std::sqrt(u1), phi = 2.0f * kPiF * u2;
    const float z = std::sqrt(fmaxf(0.0f, 1.0f - u1));
    return normalized(t * (r * std::cos(phi)) + b * (r * std::sin(phi)) + n * z);
}

// 1 - cos(angle), exact for small angles (2 sin^2(angle / 2): no cancellation in float).
WEIR_HD inline float oneMinusCos(float angle) {
    const float s = std::sin(0.5f * angle);
    return 2.0f * s * s;
}

// A direction uniform in solid angle within the cone of half-angle `angle` about unit axis.
WEIR_HD inline Vec3f directionInCone(const Vec3f& axis, float angle, float u1, float u2) {
    Vec3f t, b;
    tangentsOf(axis, t, b);
    const float cosTheta = 1.0f - u1 * oneMinusCos(angle);
    const float sinTheta = std::sqrt(fmaxf(0.0f, 1.0f - cosTheta * cosTheta));
    const float phi = 2.0f * kPiF * u2;
    return normalized(t * (sinTheta * std::cos(phi)) + b * (sinTheta * std::sin(phi)) +
                      axis * cosTheta);
}

}  // namespace weir
