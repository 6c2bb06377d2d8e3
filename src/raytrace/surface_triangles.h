// The live water look's surface triangles as the tracer takes them, written once for the CPU and
// CUDA: the offline scene's rule (tracing_scene.cpp) for which faces of the marching-cubes mesh
// are kept, applied to a mesh in device memory a thread per triangle.
#pragma once

#include <cmath>
#include <cstdint>

#include "raytrace/bvh.h"
#include "raytrace/tracing_scene.h"

namespace weir {

// A surface mesh's arrays, in the memory of the backend that reads them.
struct SurfaceMeshView {
    const Vec3f* positions;
    const Vec3f* normals;
    const std::uint32_t* indices;
};

// What decides which of the surface's faces are left out: the container, the walls that are
// there and the contact distance (TracingSceneDescription::contactDistance; 0: none).
struct ContactRule {
    Vec3d lo, hi;
    std::uint32_t walls;
    double distance;
};

// Whether a face lies on the plane (within `distance`) and faces it: the rule of both the offline
// scene (tracing_scene.cpp) and the live one, in double arithmetic.
WEIR_HD inline bool faceLiesOnPlane(const Vec3f corners[3], const Vec3f& faceNormal, int axis,
                                    double position, double outward, double distance) {
    if (double(faceNormal[axis]) * outward < 0.5) {
        return false;
    }
    for (int c = 0; c < 3; ++c) {
        if (fabs(double(corners[c][axis]) - position) > distance) {
            return false;
        }
    }
    return true;
}

// The unit normal of the face with these corners, or false for a degenerate face: one whose
// doubled area is below 1e-6 of its longest edge squared. The relative test gives the CPU and CUDA
// the same answer: on a GPU the cross product is contracted to fused multiply-adds, which leave a
// rounding residue (about 1e-8 of an edge squared) where two corners coincide, so "area > 0"
// alone keeps on the GPU faces the CPU drops.
WEIR_HD inline bool faceNormalOf(const Vec3f corners[3], Vec3f& faceNormal) {
    const Vec3f u = corners[1] - corners[0], v = corners[2] - corners[0],
                w = corners[2] - corners[1];
    const Vec3f face = cross(u, v);
    const float area = length(face);
    const float longest = fmaxf(dot(u, u), fmaxf(dot(v, v), dot(w, w)));
    if (!(area > 1e-6f * longest)) {
        return false;
    }
    faceNormal = face / area;
    return true;
}
// Surface triangle t as the tracer takes it, as the offline scene makes it: left out (false) when
// degenerate or on the floor or a wall; vertex normals made unit, the face's where one is 0.
WEIR_HD inline bool keptSurfaceTriangle(const SurfaceMeshView& mesh, std::int64_t t,
                                        const ContactRule& rule, BvhTriangle& out,
                                        TriangleShading& shade) {
    Vec3f corners[3], normals[3];
    for (int c = 0; c < 3; ++c) {
        const std::uint32_t v = mesh.indices[3 * t + c];
        corners[c] = mesh.positions[v];
        normals[c] = mesh.normals[v];
    }
    Vec3f faceNormal;
    if (!faceNormalOf(corners, faceNormal)) {
        return false;
    }
    if (rule.distance > 0) {
        bool onContainer = faceLiesOnPlane(corners, faceNormal, 1, rule.lo.y, -1, rule.distance);
        for (int axis = 0; axis < 3 && !onContainer; axis += 2) {
            for (int side = 0; side < 2 && !onContainer; ++side) {
                onContainer =
                    (rule.walls & wallBit(axis, side)) != 0 &&
                    faceLiesOnPlane(corners, faceNormal, axis, side ? rule.hi[axis] : rule.lo[axis],
                                    side ? 1 : -1, rule.distance);
            }
        }
        if (onContainer) {
            return false;
        }
    }
    for (Vec3f& n : normals) {
        const float l = length(n);
        n = l > 0 ? n / l : faceNormal;
    }
    out = {corners[0], corners[1] - corners[0], corners[2] - corners[0]};
    shade = {normals[0], normals[1], normals[2], TriangleKind::Water};
    return true;
}

}  // namespace weir
