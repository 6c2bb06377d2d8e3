// A bounding volume hierarchy over triangles: built on the host (binned surface area heuristic),
// traversed with a small stack by the same code on the CPU and in CUDA.
#pragma once

#include <cstdint>
#include <vector>

#include "raytrace/ray.h"

namespace weir {

// A node's box; an inner node's children are nodes `first` and `first + 1`; a leaf (count > 0)
// holds triangles first .. first + count - 1.
struct BvhNode {
    Vec3f lo;
    std::int32_t first = 0;
    Vec3f hi;
    std::int32_t count = 0;
};

// A triangle as the Moller-Trumbore test takes it: a corner and the two edges from it.
struct BvhTriangle {
    Vec3f v0, e1, e2;
};

// The hierarchy in the memory of the backend that traverses it: plain pointers, passed by value.
struct BvhView {
    const BvhNode* nodes = nullptr;
    const BvhTriangle* triangles = nullptr;
    std::int32_t nodeCount = 0;
};

// The nearest hit: distance t along the ray, the triangle (in the hierarchy's order; -1: none)
// and the barycentric coordinates of the hit (u towards corner 1, v towards corner 2).
struct RayHit {
    float t = 0;
    std::int32_t triangle = -1;
    float u = 0, v = 0;
};

// Moller-Trumbore, both faces: the distance t in (tMin, tMax) at which the ray meets the
// triangle, with the barycentric u, v; false when it does not.
WEIR_HD inline bool intersectTriangle(const BvhTriangle& tri, const Ray& ray, float tMin,
                                      float tMax, float& t, float& u, float& v) {
    const Vec3f p = cross(ray.direction, tri.e2);
    const float det = dot(tri.e1, p);
    if (fabsf(det) < 1e-20f) {
        return false;  // parallel to the triangle's plane, or a degenerate triangle
    }
    const float inv = 1.0f / det;
    const Vec3f s = ray.origin - tri.v0;
    u = dot(s, p) * inv;
    if (u < 0.0f || u > 1.0f) {
        return false;
    }
    const Vec3f q = cross(s, tri.e1);
    v = dot(ray.direction, q) * inv;
    if (v < 0.0f || u + v > 1.0f) {
        return false;
    }
    t = dot(tri.e2, q) * inv;
    return t > tMin && t < tMax;
}

// Whether the ray passes through the box between tMin and tMax, and where it enters it (at
// tMin or later). invDirection: 1 / direction per axis (inf where it is 0; fminf and fmaxf drop
// the NaN that 0 * inf gives on a slab's plane).
WEIR_HD inline bool boxEntry(const Vec3f& lo, const Vec3f& hi, const Ray& ray,
                             const Vec3f& invDirection, float tMin, float tMax, float& enter) {
    const float tx0 = (lo.x - ray.origin.x) * invDirection.x;
    const float tx1 = (hi.x - ray.origin.x) * invDirection.x;
    const float ty0 = (lo.y - ray.origin.y) * invDirection.y;
    const float ty1 = (hi.y - ray.origin.y) * invDirection.y;
    const float tz0 = (lo.z - ray.origin.z) * invDirection.z;
    const float tz1 = (hi.z - ray.origin.z) * invDirection.z;
    enter = fmaxf(fmaxf(fminf(tx0, tx1), fminf(ty0, ty1)), fmaxf(fminf(tz0, tz1), tMin));
    const float leave =
        fminf(fminf(fmaxf(tx0, tx1), fmaxf(ty0, ty1)), fminf(fmaxf(tz0, tz1), tMax));
    return enter <= leave;
}

// The deepest path from the root to a leaf the build makes, so that traversal's stack suffices.
constexpr int kBvhMaxDepth = 48;

// The nearest triangle the ray meets in (tMin, tMax): depth-first, the nearer child first, the
// farther one on a stack; subtrees entered beyond the nearest hit so far are skipped.
WEIR_HD inline RayHit closestHit(const BvhView& bvh, const Ray& ray, float tMin, float tMax) {
    RayHit hit;
    if (bvh.nodeCount == 0) {
        return hit;
    }
    const Vec3f invDirection(1.0f / ray.direction.x, 1.0f / ray.direction.y,
                             1.0f / ray.direction.z);
    float nearest = tMax;
    std::int32_t stack[kBvhMaxDepth + 2];
    int top = 0;
    std::int32_t node = 0;
    float entry;
    if (!boxEntry(bvh.nodes[0].lo, bvh.nodes[0].hi, ray, invDirection, tMin, nearest, entry)) {
        return hit;
    }
    while (true) {
        const BvhNode& n = bvh.nodes[node];
        if (n.count > 0) {
            for (std::int32_t k = n.first; k < n.first + n.count; ++k) {
                float t, u, v;
                if (intersectTriangle(bvh.triangles[k], ray, tMin, nearest, t, u, v)) {
                    nearest = t;
                    hit = {t, k, u, v};
                }
            }
        } else {
            const std::int32_t a = n.first, b = n.first + 1;
            float ta, tb;
            const bool hitA =
                boxEntry(bvh.nodes[a].lo, bvh.nodes[a].hi, ray, invDirection, tMin, nearest, ta);
            const bool hitB =
                boxEntry(bvh.nodes[b].lo, bvh.nodes[b].hi, ray, invDirection, tMin, nearest, tb);
            if (hitA && hitB) {
                node = ta <= tb ? a : b;
                stack[top++] = ta <= tb ? b : a;
                continue;
            }
            if (hitA || hitB) {
                node = hitA ? a : b;
                continue;
            }
        }
        // A leaf, or an inner node whose children the ray misses: the next subtree on the stack
        // (entered again only if it may still hold a nearer hit).
        bool found = false;
        while (top > 0 && !found) {
            node = stack[--top];
            found = boxEntry(bvh.nodes[node].lo, bvh.nodes[node].hi, ray, invDirection, tMin,
                             nearest, entry);
        }
        if (!found) {
            return hit;
        }
    }
}

// The hierarchy on the host. `order[k]` is the index, in the input, of the hierarchy's triangle k.
class Bvh {
   public:
    Bvh() = default;
    // positions: the vertices; indices: three per triangle. Leaves hold at most kMaxLeafSize
    // triangles, unless a set of triangles has coincident centres (then one leaf holds them).
    Bvh(const std::vector<Vec3f>& positions, const std::vector<std::uint32_t>& indices);

    static constexpr int kMaxLeafSize = 4;

    BvhView view() const { return {nodes_.data(), triangles_.data(), std::int32_t(nodes_.size())}; }
    const std::vector<BvhNode>& nodes() const { return nodes_; }
    const std::vector<BvhTriangle>& triangles() const { return triangles_; }
    const std::vector<std::uint32_t>& order() const { return order_; }
    int depth() const { return depth_; }

   private:
    std::vector<BvhNode> nodes_;
    std::vector<BvhTriangle> triangles_;
    std::vector<std::uint32_t> order_;
    int depth_ = 0;
};

}  // namespace weir
