// What the water look's tests share: a ball of water as a smooth-shaded latitude-longitude mesh,
// and a pinhole camera looking at a point.
#pragma once

#include <cmath>
#include <cstdint>

#include "raytrace/path_tracer.h"
#include "surface/triangle_mesh.h"

namespace weir::testing {

// A ball of water: `slices` x `stacks` quads of a sphere, vertex normals pointing out.
inline TriangleMesh waterBall(const Vec3f& centre, float radius, int slices = 48, int stacks = 24) {
    TriangleMesh mesh;
    for (int j = 0; j <= stacks; ++j) {
        for (int i = 0; i <= slices; ++i) {
            const float theta = kPiF * float(j) / float(stacks);
            const float phi = 2 * kPiF * float(i) / float(slices);
            const Vec3f n(std::sin(theta) * std::cos(phi), std::cos(theta),
                          std::sin(theta) * std::sin(phi));
            mesh.positions.push_back(centre + n * radius);
            mesh.normals.push_back(n);
        }
    }
    for (int j = 0; j < stacks; ++j) {
        for (int i = 0; i < slices; ++i) {
            const auto a = std::uint32_t(j * (slices + 1) + i), b = a + 1, c = a + slices + 1,
                       d = c + 1;
            mesh.indices.insert(mesh.indices.end(), {a, b, d, a, d, c});
        }
    }
    return mesh;
}

// A pinhole camera at `eye` looking at `target`, y up, for a width x height image.
inline PinholeCamera lookAt(const Vec3f& eye, const Vec3f& target, int width, int height) {
    PinholeCamera camera;
    camera.eye = eye;
    camera.forward = normalized(target - eye);
    camera.right = normalized(cross(camera.forward, Vec3f(0, 1, 0)));
    camera.up = cross(camera.right, camera.forward);
    camera.aspect = float(width) / float(height);
    return camera;
}

}  // namespace weir::testing
