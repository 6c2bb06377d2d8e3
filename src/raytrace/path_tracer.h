// The water look's path tracer, written once for the CPU and CUDA: a camera ray per sample, the
// water surface as a smooth dielectric (Fresnel reflection or Snell refraction, chosen at random
// with the Fresnel reflectance as probability), Beer-Lambert absorption along every length
// travelled in the water, matte surfaces lit by the sun (a direct, soft-shadowed sample of its
// disc through the water) and by the sky (a cosine-weighted bounce).
#pragma once

#include <cmath>

#include "raytrace/bvh.h"
#include "raytrace/optics.h"
#include "raytrace/sample_stream.h"
#include "raytrace/sky.h"
#include "raytrace/tracing_scene.h"
#include "raytrace/water_look.h"

namespace weir {

// A pinhole camera: the eye, unit forward/right/up, the vertical field of view as
// tan(fovY / 2) and the image's width over height. Pixel rows run from the top.
struct PinholeCamera {
    Vec3f eye;
    Vec3f forward{0, 0, -1}, right{1, 0, 0}, up{0, 1, 0};
    float tanHalfFovY = 0.3639702f;  // 40 degrees
    float aspect = 1.0f;
};

// The ray through the image point (px, py), in pixels from the image's top-left corner.
WEIR_HD inline Ray cameraRay(const PinholeCamera& c, int width, int height, float px, float py) {
    const float sx = (2.0f * px / float(width) - 1.0f) * c.tanHalfFovY * c.aspect;
    const float sy = (1.0f - 2.0f * py / float(height)) * c.tanHalfFovY;
    return {c.eye, normalized(c.forward + c.right * sx + c.up * sy)};
}

constexpr float kNoHit = 3.0e38f;

enum class SurfaceType { None, Water, Matte };

// The nearest surface along a ray: how far, its geometric normal (the water's points out of the
// fluid; a matte surface's faces the ray), its shading normal on the same side, and a matte
// surface's albedo.
struct SurfaceHit {
    SurfaceType type = SurfaceType::None;
    float t = kNoHit;
    Vec3f normal, shadingNormal, albedo;
};

// The floor: light and dark squares of look.checkerSize inside the container, plain ground
// outside it.
WEIR_HD inline Vec3f floorAlbedo(const TracingSceneView& s, const WaterLook& look, float x,
                                 float z) {
    if (x < s.containerLo.x || x > s.containerHi.x || z < s.containerLo.z || z > s.containerHi.z) {
        return look.groundAlbedo;
    }
    const float squares = floorf(x / look.checkerSize) + floorf(z / look.checkerSize);
    return fabsf(fmodf(squares, 2.0f)) > 0.5f ? look.floorDark : look.floorLight;
}

WEIR_HD inline SurfaceHit nearestSurface(const TracingSceneView& s, const WaterLook& look,
                                         const Ray& ray) {
    SurfaceHit hit;
    const RayHit triangle = closestHit(s.bvh, ray, 0.0f, kNoHit);
    if (triangle.triangle >= 0) {
        hit.t = triangle.t;
    }
    // The floor (y = the container's bottom, endless) and the side walls that are there.
    int plane = -1;  // 0: floor; 1 + 2 * axis + side: a wall
    if (ray.direction.y != 0.0f) {
        const float t = (s.containerLo.y - ray.origin.y) / ray.direction.y;
        if (t > 0.0f && t < hit.t) {
            hit.t = t;
            plane = 0;
        }
    }
    for (int axis = 0; axis < 3; axis += 2) {
        const int across = 2 - axis;  // the other horizontal axis
        for (int side = 0; side < 2; ++side) {
            if ((s.walls & wallBit(axis, side)) == 0 || ray.direction[axis] == 0.0f) {
                continue;
            }
            const float at = side ? s.containerHi[axis] : s.containerLo[axis];
            const float t = (at - ray.origin[axis]) / ray.direction[axis];
            if (!(t > 0.0f && t < hit.t)) {
                continue;
            }
            const float y = ray.origin.y + ray.direction.y * t;
            const float w = ray.origin[across] + ray.direction[across] * t;
            if (y >= s.containerLo.y && y <= s.containerHi.y && w >= s.containerLo[across] &&
                w <= s.containerHi[across]) {
                hit.t = t;
                plane = 1 + 2 * axis + side;
            }
        }
    }
    if (plane >= 0) {
        hit.type = SurfaceType::Matte;
        Vec3f n;
        if (plane == 0) {
            n = Vec3f(0, 1, 0);
            const Vec3f p = ray.origin + ray.direction * hit.t;
            hit.albedo = floorAlbedo(s, look, p.x, p.z);
        } else {
            const int axis = (plane - 1) / 2, side = (plane - 1) % 2;
            n[axis] = side ? -1.0f : 1.0f;  // into the container
            hit.albedo = look.wallAlbedo;
        }
        hit.normal = dot(n, ray.direction) < 0.0f ? n : -n;
        hit.shadingNormal = hit.normal;
        return hit;
    }
    if (triangle.triangle < 0) {
        return hit;
    }
    const BvhTriangle& tri = s.bvh.triangles[triangle.triangle];
    const TriangleShading& shade = s.shading[triangle.triangle];
    Vec3f n = normalized(cross(tri.e1, tri.e2));
    Vec3f smooth = normalized(shade.n0 * (1.0f - triangle.u - triangle.v) + shade.n1 * triangle.u +
                              shade.n2 * triangle.v);
    if (!(dot(smooth, n) > 0.0f)) {
        smooth = n;  // vertex normals that disagree with the face (or that sum to 0)
    }
    if (shade.kind == TriangleKind::Water) {
        hit.type = SurfaceType::Water;
    } else {
        hit.type = SurfaceType::Matte;
        hit.albedo = shade.kind == TriangleKind::Body         ? look.bodyAlbedo
                     : shade.kind == TriangleKind::Whitewater ? look.whitewaterAlbedo
                                                              : look.obstacleAlbedo;
        if (dot(n, ray.direction) > 0.0f) {
            n = -n;
            smooth = -smooth;
        }
    }
    hit.normal = n;
    hit.shadingNormal = smooth;
    return hit;
}

// The fraction of the sun's light that reaches a point along `direction` (towards the sun) from
// it: 0 behind a matte surface; through the water, the Fresnel transmittance (1 - R) at each
// crossing of its surface and Beer-Lambert absorption inside, along the straight line (the
// bending is left out: shadows through water are soft, without caustics).
WEIR_HD inline Vec3f sunTransmittance(const TracingSceneView& s, const WaterLook& look, Ray ray,
                                      bool inWater) {
    Vec3f left(1.0f, 1.0f, 1.0f);
    for (int crossing = 0; crossing < 16; ++crossing) {
        const SurfaceHit hit = nearestSurface(s, look, ray);
        if (hit.type == SurfaceType::None) {
            return left;
        }
        if (hit.type == SurfaceType::Matte) {
            return Vec3f();
        }
        const bool entering = dot(ray.direction, hit.normal) < 0.0f;
        if (inWater || !entering) {
            left = times(left, transmittance(look.absorption, hit.t));
        }
        const float n1 = entering ? 1.0f : look.refractiveIndex;
        const float n2 = entering ? look.refractiveIndex : 1.0f;
        left = left *
               (1.0f - fresnelReflectance(fabsf(dot(ray.direction, hit.shadingNormal)), n1, n2));
        if (largestOf(left) < 1e-4f) {
            return Vec3f();
        }
        inWater = entering;
        const Vec3f facing = entering ? hit.normal : -hit.normal;
        ray.origin = ray.origin + ray.direction * hit.t - facing * s.rayEpsilon;
    }
    return Vec3f();
}

// The radiance arriving along a ray (towards its origin), by one random path. inWater: whether
// the ray starts in the water.
WEIR_HD inline Vec3f traceRadiance(const TracingSceneView& s, const WaterLook& look, Ray ray,
                                   bool inWater, SampleStream& random) {
    Vec3f radiance, throughput(1.0f, 1.0f, 1.0f);
    int specularBounces = 0, diffuseBounces = 0;
    bool sunDiscSeen = true;  // until a matte bounce, whose direct sun sample counts the disc
    const Vec3f toSun = normalized(look.sunDirection);
    while (true) {
        const SurfaceHit hit = nearestSurface(s, look, ray);
        if (hit.type == SurfaceType::None) {
            radiance += times(throughput, skyRadiance(look, ray.direction, sunDiscSeen));
            break;
        }
        const bool frontFace = dot(ray.direction, hit.normal) < 0.0f;
        if (inWater || (hit.type == SurfaceType::Water && !frontFace)) {
            throughput = times(throughput, transmittance(look.absorption, hit.t));
        }
        const Vec3f position = ray.origin + ray.direction * hit.t;
        const Vec3f facing = frontFace ? hit.normal : -hit.normal;  // on the ray's side

        if (hit.type == SurfaceType::Water) {
            if (specularBounces == look.maxSpecularBounces) {
                break;
            }
            ++specularBounces;
            Vec3f n = frontFace ? hit.shadingNormal : -hit.shadingNormal;
            if (dot(ray.direction, n) >= 0.0f) {
                n = facing;  // the smooth normal faces away from the ray: the true one
            }
            const float n1 = frontFace ? 1.0f : look.refractiveIndex;
            const float n2 = frontFace ? look.refractiveIndex : 1.0f;
            const float reflectance = fresnelReflectance(-dot(ray.direction, n), n1, n2);
            bool reflect = random.next() < reflectance;
            Vec3f next;
            if (!reflect) {
                reflect = !refracted(ray.direction, n, n1 / n2, next);
                if (!reflect && dot(next, facing) >= 0.0f) {
                    // Bent back to the ray's side by the smooth normal: refract by the true one.
                    n = facing;
                    reflect = !refracted(ray.direction, n, n1 / n2, next);
                }
            }
            if (reflect) {
                next = reflected(ray.direction, n);
                if (dot(next, facing) <= 0.0f) {
                    next = reflected(ray.direction, facing);
                }
            }
            inWater = reflect ? !frontFace : frontFace;
            ray = {position + facing * (reflect ? s.rayEpsilon : -s.rayEpsilon), next};
            continue;
        }

        // A matte surface: the sun directly, then (bounces left) a cosine-weighted bounce that
        // gathers the sky and the light off other surfaces.
        const Vec3f n = hit.shadingNormal;
        const Vec3f origin = position + facing * s.rayEpsilon;
        // Each number drawn in a statement of its own: the order in which a call's arguments
        // are evaluated is the compiler's (GCC and nvcc differ), and the CPU and CUDA must draw
        // alike.
        const float sunU1 = random.next();
        const float sunU2 = random.next();
        const Vec3f sunSample = directionInCone(toSun, look.sunAngularRadius, sunU1, sunU2);
        const float cosSun = dot(n, sunSample);
        if (cosSun > 0.0f && dot(facing, sunSample) > 0.0f) {
            const Vec3f lit = sunTransmittance(s, look, {origin, sunSample}, inWater);
            radiance += times(times(throughput, hit.albedo), times(look.sunIrradiance, lit)) *
                        (cosSun / kPiF);
        }
        if (diffuseBounces == look.maxDiffuseBounces) {
            break;
        }
        ++diffuseBounces;
        throughput = times(throughput, hit.albedo);
        const float bounceU1 = random.next();
        const float bounceU2 = random.next();
        Vec3f next = cosineWeightedDirection(n, bounceU1, bounceU2);
        if (dot(next, facing) <= 0.0f) {
            next = reflected(next, facing);  // a smooth normal's lobe dipping under the face
        }
        sunDiscSeen = false;
        ray = {origin, next};
    }
    return radiance;
}

// A pixel's mean radiance over `samples` paths, each through a random point of the pixel: the
// paths numbered firstSample on (the live look adds a few each frame to those traced before).
WEIR_HD inline Vec3f tracePixel(const TracingSceneView& s, const WaterLook& look,
                                const PinholeCamera& camera, int width, int height, int x, int y,
                                int samples, int firstSample = 0) {
    Vec3f sum;
    const auto pixel = std::uint32_t(y) * std::uint32_t(width) + std::uint32_t(x);
    for (int k = 0; k < samples; ++k) {
        SampleStream random(pixel, std::uint32_t(firstSample + k));
        const float px = float(x) + random.next();
        const float py = float(y) + random.next();
        sum += traceRadiance(s, look, cameraRay(camera, width, height, px, py), false, random);
    }
    return sum * (1.0f / float(samples));
}

}  // namespace weir
