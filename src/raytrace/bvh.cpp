// The hierarchy's build: binned surface area heuristic (16 bins on each axis, Wald 2007).
#include "raytrace/bvh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace weir {

namespace {

struct Bounds {
    bool empty() const { return !(lo.x <= hi.x); }
    Vec3f lo{std::numeric_limits<float>::infinity(), std::numeric_limits<float>::infinity(),
             std::numeric_limits<float>::infinity()};
    Vec3f hi{-std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
             -std::numeric_limits<float>::infinity()};

    void grow(const Vec3f& p) {
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
    void grow(const Bounds& b) {
        if (b.empty()) {
            return;  // its corners are +inf and -inf
        }
        grow(b.lo);
        grow(b.hi);
    }
    // Half the surface area: what the heuristic compares.
    float halfArea() const {
        if (empty()) {
            return 0;
        }
        const Vec3f e = hi - lo;
        return e.x * e.y + e.y * e.z + e.z * e.x;
    }
};

struct BuildTriangle {
    Bounds box;
    Vec3f centre;
};

constexpr int kBins = 16;

class Builder {
   public:
    Builder(const std::vector<BuildTriangle>& triangles, std::vector<std::uint32_t>& order,
            std::vector<BvhNode>& nodes)
        : triangles_(triangles), order_(order), nodes_(nodes) {}

    int depth = 0;

    void build(std::size_t node, std::size_t first, std::size_t count, int level) {
        depth = std::max(depth, level);
        Bounds box, centres;
        for (std::size_t k = first; k < first + count; ++k) {
            box.grow(triangles_[order_[k]].box);
            centres.grow(triangles_[order_[k]].centre);
        }
        nodes_[node].lo = box.lo;
        nodes_[node].hi = box.hi;
        const auto makeLeaf = [&] {
            nodes_[node].first = std::int32_t(first);
            nodes_[node].count = std::int32_t(count);
        };
        if (count <= std::size_t(Bvh::kMaxLeafSize) || level >= kBvhMaxDepth) {
            makeLeaf();
            return;
        }
        // The best of 15 planes on each axis by the surface area heuristic.
        float bestCost = std::numeric_limits<float>::infinity();
        int bestAxis = -1, bestPlane = 0;
        for (int axis = 0; axis < 3; ++axis) {
            const float lo = centres.lo[axis], extent = centres.hi[axis] - lo;
            if (!(extent > 0)) {
                continue;
            }
            std::array<Bounds, kBins> binBox;
            std::array<std::size_t, kBins> binCount{};
            for (std::size_t k = first; k < first + count; ++k) {
                const BuildTriangle& t = triangles_[order_[k]];
                const int bin = binOf(t.centre[axis], lo, extent);
                binBox[std::size_t(bin)].grow(t.box);
                ++binCount[std::size_t(bin)];
            }
            // Areas and counts left of each plane, then sweep from the right.
            std::array<float, kBins> leftArea{};
            std::array<std::size_t, kBins> leftCount{};
            Bounds left;
            std::size_t n = 0;
            for (int b = 0; b < kBins - 1; ++b) {
                left.grow(binBox[std::size_t(b)]);
                n += binCount[std::size_t(b)];
                leftArea[std::size_t(b)] = left.halfArea();
                leftCount[std::size_t(b)] = n;
            }
            Bounds right;
            std::size_t m = 0;
            for (int b = kBins - 1; b > 0; --b) {
                right.grow(binBox[std::size_t(b)]);
                m += binCount[std::size_t(b)];
                const std::size_t l = leftCount[std::size_t(b - 1)];
                if (l == 0 || m == 0) {
                    continue;
                }
                const float cost =
                    leftArea[std::size_t(b - 1)] * float(l) + right.halfArea() * float(m);
                if (cost < bestCost) {
                    bestCost = cost;
                    bestAxis = axis;
                    bestPlane = b;  // bins below b go left
                }
            }
        }
        if (bestAxis < 0) {
            makeLeaf();  // every centre at one point: no plane separates them
            return;
        }
        const float lo = centres.lo[bestAxis], extent = centres.hi[bestAxis] - lo;
        const auto middle =
            std::partition(order_.begin() + std::ptrdiff_t(first),
                           order_.begin() + std::ptrdiff_t(first + count), [&](std::uint32_t t) {
                               return binOf(triangles_[t].centre[bestAxis], lo, extent) < bestPlane;
                           });
        const std::size_t leftCount = std::size_t(middle - order_.begin()) - first;
        const std::size_t children = nodes_.size();
        nodes_.resize(children + 2);
        nodes_[node].first = std::int32_t(children);
        nodes_[node].count = 0;
        build(children, first, leftCount, level + 1);
        build(children + 1, first + leftCount, count - leftCount, level + 1);
    }

   private:
    static int binOf(float value, float lo, float extent) {
        const int bin = int(float(kBins) * (value - lo) / extent);
        return std::clamp(bin, 0, kBins - 1);
    }

    const std::vector<BuildTriangle>& triangles_;
    std::vector<std::uint32_t>& order_;
    std::vector<BvhNode>& nodes_;
};

}  // namespace

Bvh::Bvh(const std::vector<Vec3f>& positions, const std::vector<std::uint32_t>& indices) {
    const std::size_t n = indices.size() / 3;
    if (n == 0) {
        return;
    }
    std::vector<BuildTriangle> build(n);
    for (std::size_t t = 0; t < n; ++t) {
        for (int c = 0; c < 3; ++c) {
            build[t].box.grow(positions[indices[3 * t + std::size_t(c)]]);
        }
        build[t].centre = (build[t].box.lo + build[t].box.hi) * 0.5f;
    }
    order_.resize(n);
    for (std::size_t t = 0; t < n; ++t) {
        order_[t] = std::uint32_t(t);
    }
    nodes_.reserve(2 * n);
    nodes_.resize(1);
    Builder builder(build, order_, nodes_);
    builder.build(0, 0, n, 0);
    depth_ = builder.depth;
    triangles_.resize(n);
    for (std::size_t k = 0; k < n; ++k) {
        const std::size_t t = order_[k];
        const Vec3f& a = positions[indices[3 * t]];
        triangles_[k] = {a, positions[indices[3 * t + 1]] - a, positions[indices[3 * t + 2]] - a};
    }
}

}  // namespace weir
