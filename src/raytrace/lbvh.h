// A linear bounding volume hierarchy (Karras 2012, "Maximizing parallelism in the construction
// of BVHs, octrees, and k-d trees"), built in parallel every frame of the live water look: the
// triangles sorted by the Morton code of their box centres, every inner node of the radix tree
// over the sorted codes found on its own (a thread each), boxes filled in from the leaves up. The
// nodes are laid out as the tracer's BvhView wants them (an inner node's children side by side),
// so the same closestHit and tracePixel walk it. Each step is a WEIR_HD function here; the CUDA
// build (lbvh_cuda.cu) and the host reference (lbvh.cpp, for tests) run the same ones.
#pragma once

#include <cstdint>
#include <vector>

#include "raytrace/bvh.h"

namespace weir {

// 10 bits per axis: the codes are 30 bits, CUB sorts them in 4 passes of 8 bits.
constexpr int kMortonBitsPerAxis = 10;
constexpr int kMortonBits = 3 * kMortonBitsPerAxis;

// The low 10 bits of v, spread to every third bit (bit k to bit 3k).
WEIR_HD inline std::uint32_t spreadBits10(std::uint32_t v) {
    v &= 0x3FFu;
    v = (v * 0x00010001u) & 0xFF0000FFu;
    v = (v * 0x00000101u) & 0x0F00F00Fu;
    v = (v * 0x00000011u) & 0xC30C30C3u;
    v = (v * 0x00000005u) & 0x49249249u;
    return v;
}

// The box of a triangle as the intersection test sees it (corners v0, v0 + e1, v0 + e2).
WEIR_HD inline void triangleBox(const BvhTriangle& t, Vec3f& lo, Vec3f& hi) {
    const Vec3f a = t.v0, b = t.v0 + t.e1, c = t.v0 + t.e2;
    lo = Vec3f(fminf(a.x, fminf(b.x, c.x)), fminf(a.y, fminf(b.y, c.y)),
               fminf(a.z, fminf(b.z, c.z)));
    hi = Vec3f(fmaxf(a.x, fmaxf(b.x, c.x)), fmaxf(a.y, fmaxf(b.y, c.y)),
               fmaxf(a.z, fmaxf(b.z, c.z)));
}

// The point a triangle is sorted by: its box's centre. (Min, max, an add and a halving: no
// multiply-add the GPU could fuse differently from the host, so both give the same codes.)
WEIR_HD inline Vec3f triangleKeyPoint(const BvhTriangle& t) {
    Vec3f lo, hi;
    triangleBox(t, lo, hi);
    return (lo + hi) * 0.5f;
}

// The Morton code of p among key points spanning [lo, lo + 1 / inverseExtent): each axis cut
// into 1024 cells (a flat axis, inverseExtent 0, puts everything in cell 0).
WEIR_HD inline std::uint32_t mortonCode(const Vec3f& p, const Vec3f& lo,
                                        const Vec3f& inverseExtent) {
    std::uint32_t code = 0;
    for (int axis = 0; axis < 3; ++axis) {
        const float cell = (p[axis] - lo[axis]) * inverseExtent[axis];
        const float clamped = fminf(fmaxf(cell, 0.0f), 1023.0f);
        code |= spreadBits10(std::uint32_t(clamped)) << (2 - axis);  // x highest, as in Karras
    }
    return code;
}

// 1024 cells per axis over [lo, hi]: the inverseExtent of mortonCode (0 on a flat axis).
WEIR_HD inline Vec3f mortonScale(const Vec3f& lo, const Vec3f& hi) {
    Vec3f s;
    for (int axis = 0; axis < 3; ++axis) {
        const float extent = hi[axis] - lo[axis];
        s[axis] = extent > 0.0f ? 1024.0f / extent : 0.0f;
    }
    return s;
}

WEIR_HD inline int countLeadingZeros32(std::uint32_t v) {
#if defined(__CUDA_ARCH__)
    return __clz(int(v));
#else
    return v == 0 ? 32 : __builtin_clz(v);
#endif
}

// Karras's delta: the length of the common prefix of sorted keys i and j, where equal codes are
// told apart by their position (32 more bits: the index); -1 outside [0, n).
WEIR_HD inline int lbvhCommonPrefix(const std::uint32_t* codes, std::int32_t n, std::int32_t i,
                                    std::int32_t j) {
    if (j < 0 || j >= n) {
        return -1;
    }
    const std::uint32_t a = codes[i], b = codes[j];
    if (a != b) {
        return countLeadingZeros32(a ^ b);
    }
    return 32 + countLeadingZeros32(std::uint32_t(i) ^ std::uint32_t(j));
}

// An inner node's children (Karras 2012, figure 4): each is a leaf (a sorted triangle) or an
// inner node, by index.
struct LbvhChildren {
    std::int32_t left = 0, right = 0;
    bool leftIsLeaf = false, rightIsLeaf = false;
};

// Inner node i (0 <= i < n - 1, n >= 2) of the radix tree over n sorted codes: the end of its
// range found by an exponential then a binary search, then the split by a binary search for the
// last key sharing the node's whole prefix with key i.
WEIR_HD inline LbvhChildren lbvhChildrenOf(const std::uint32_t* codes, std::int32_t n,
                                           std::int32_t i) {
    const int direction =
        lbvhCommonPrefix(codes, n, i, i + 1) - lbvhCommonPrefix(codes, n, i, i - 1) > 0 ? 1 : -1;
    const int minPrefix = lbvhCommonPrefix(codes, n, i, i - direction);
    std::int32_t maxLength = 2;
    while (lbvhCommonPrefix(codes, n, i, i + maxLength * direction) > minPrefix) {
        maxLength *= 2;
    }
    std::int32_t length = 0;
    for (std::int32_t step = maxLength / 2; step >= 1; step /= 2) {
        if (lbvhCommonPrefix(codes, n, i, i + (length + step) * direction) > minPrefix) {
            length += step;
        }
    }
    const std::int32_t j = i + length * direction;
    const int nodePrefix = lbvhCommonPrefix(codes, n, i, j);
    std::int32_t split = 0;
    for (std::int32_t divisor = 2;; divisor *= 2) {
        const std::int32_t step = (length + divisor - 1) / divisor;
        if (lbvhCommonPrefix(codes, n, i, i + (split + step) * direction) > nodePrefix) {
            split += step;
        }
        if (step <= 1) {
            break;
        }
    }
    const std::int32_t gamma = i + split * direction + (direction < 0 ? -1 : 0);
    LbvhChildren c;
    c.left = gamma;
    c.right = gamma + 1;
    c.leftIsLeaf = (i < j ? i : j) == gamma;
    c.rightIsLeaf = (i > j ? i : j) == gamma + 1;
    return c;
}

// Where nodes go in the BvhView array of 2n - 1 nodes: the root (inner node 0) at 0, the children
// of inner node i at 1 + 2i and 2 + 2i (every node but the root is one inner node's child, so
// each slot is taken once). A node's slot and its parent (-1: none), per leaf and per inner node.
struct LbvhLinks {
    std::int32_t* leafSlot;
    std::int32_t* leafParent;
    std::int32_t* innerSlot;
    std::int32_t* innerParent;
};

// Inner node i's part of the links: its children's slots and parent.
WEIR_HD inline void lbvhLink(const LbvhChildren& c, std::int32_t i, const LbvhLinks& links) {
    const std::int32_t slots[2] = {1 + 2 * i, 2 + 2 * i};
    const std::int32_t child[2] = {c.left, c.right};
    const bool leaf[2] = {c.leftIsLeaf, c.rightIsLeaf};
    for (int k = 0; k < 2; ++k) {
        if (leaf[k]) {
            links.leafSlot[child[k]] = slots[k];
            links.leafParent[child[k]] = i;
        } else {
            links.innerSlot[child[k]] = slots[k];
            links.innerParent[child[k]] = i;
        }
    }
}

// A leaf node: sorted triangle k alone, in its box.
WEIR_HD inline BvhNode lbvhLeaf(const BvhTriangle& t, std::int32_t k) {
    BvhNode node;
    triangleBox(t, node.lo, node.hi);
    node.first = k;
    node.count = 1;
    return node;
}

// Inner node i, its box the union of its children's (at slots 1 + 2i and 2 + 2i).
WEIR_HD inline BvhNode lbvhInner(const BvhNode& a, const BvhNode& b, std::int32_t i) {
    BvhNode node;
    node.lo = Vec3f(fminf(a.lo.x, b.lo.x), fminf(a.lo.y, b.lo.y), fminf(a.lo.z, b.lo.z));
    node.hi = Vec3f(fmaxf(a.hi.x, b.hi.x), fmaxf(a.hi.y, b.hi.y), fmaxf(a.hi.z, b.hi.z));
    node.first = 1 + 2 * i;
    node.count = 0;
    return node;
}

// Depth: each inner node's prefix is longer than its parent's, and the prefix has 30 bits of code
// then, for a run of equal codes, the bits of the index, whose subtree over consecutive indices
// is balanced. A leaf lies at most 31 + ceil(log2(longest run of equal codes)) deep, within the
// tracer's stack (kBvhMaxDepth + 2 entries) unless more than 2^19 triangles share one of the
// 2^30 cells: for the live surface, a cell of 1/1024 of the mesh's extent holds a few.

// A hierarchy built on the host (the reference of the CUDA build, for tests) or downloaded.
struct HostLbvh {
    std::vector<BvhNode> nodes;
    std::vector<BvhTriangle> triangles;  // in the hierarchy's (Morton) order
    std::vector<std::uint32_t> order;    // order[k]: the input index of triangle k
    BvhView view() const { return {nodes.data(), triangles.data(), std::int32_t(nodes.size())}; }
    int depth() const;  // the deepest leaf, the root at 0
};

// The same build on one host thread, by the functions above.
HostLbvh buildLbvhOnHost(const std::vector<BvhTriangle>& triangles);

// The CUDA build (lbvh_cuda.cu), its result downloaded: for tests on a GPU. Throws
// std::runtime_error in a build without CUDA.
HostLbvh buildLbvhOnDevice(const std::vector<BvhTriangle>& triangles);

}  // namespace weir
