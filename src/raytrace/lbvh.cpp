// The linear hierarchy's host build: the reference the CUDA build is tested against, by the same
// WEIR_HD steps run one after another.
#include "raytrace/lbvh.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>

namespace weir {

int HostLbvh::depth() const {
    if (nodes.empty()) {
        return 0;
    }
    int deepest = 0;
    std::vector<std::pair<std::int32_t, int>> stack{{0, 0}};
    while (!stack.empty()) {
        const auto [node, level] = stack.back();
        stack.pop_back();
        deepest = std::max(deepest, level);
        const BvhNode& n = nodes[std::size_t(node)];
        if (n.count == 0) {
            stack.push_back({n.first, level + 1});
            stack.push_back({n.first + 1, level + 1});
        }
    }
    return deepest;
}

HostLbvh buildLbvhOnHost(const std::vector<BvhTriangle>& input) {
    HostLbvh out;
    const auto n = std::int32_t(input.size());
    if (n == 0) {
        return out;
    }
    // Morton codes of the key points over their bounds.
    Vec3f lo = triangleKeyPoint(input[0]), hi = lo;
    for (const BvhTriangle& t : input) {
        const Vec3f p = triangleKeyPoint(t);
        lo = Vec3f(fminf(lo.x, p.x), fminf(lo.y, p.y), fminf(lo.z, p.z));
        hi = Vec3f(fmaxf(hi.x, p.x), fmaxf(hi.y, p.y), fmaxf(hi.z, p.z));
    }
    const Vec3f scale = mortonScale(lo, hi);
    std::vector<std::uint32_t> codes(input.size());
    for (std::size_t t = 0; t < input.size(); ++t) {
        codes[t] = mortonCode(triangleKeyPoint(input[t]), lo, scale);
    }
    // A stable sort, as CUB's radix sort: equal codes keep the input order.
    out.order.resize(input.size());
    std::iota(out.order.begin(), out.order.end(), 0u);
    std::stable_sort(out.order.begin(), out.order.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return codes[a] < codes[b]; });
    std::vector<std::uint32_t> sorted(input.size());
    out.triangles.resize(input.size());
    for (std::size_t k = 0; k < input.size(); ++k) {
        sorted[k] = codes[out.order[k]];
        out.triangles[k] = input[out.order[k]];
    }

    out.nodes.resize(2 * std::size_t(n) - 1);
    if (n == 1) {
        out.nodes[0] = lbvhLeaf(out.triangles[0], 0);
        return out;
    }
    std::vector<std::int32_t> leafSlot(std::size_t(n), -1), leafParent(std::size_t(n), -1),
        innerSlot(std::size_t(n - 1), -1), innerParent(std::size_t(n - 1), -1);
    const LbvhLinks links{leafSlot.data(), leafParent.data(), innerSlot.data(), innerParent.data()};
    innerSlot[0] = 0;
    for (std::int32_t i = 0; i < n - 1; ++i) {
        lbvhLink(lbvhChildrenOf(sorted.data(), n, i), i, links);
    }
    // From each leaf up: an inner node is filled in by the second of its children to arrive, as
    // the GPU's threads do with an atomic counter.
    std::vector<int> arrived(std::size_t(n - 1), 0);
    for (std::int32_t k = 0; k < n; ++k) {
        out.nodes[std::size_t(leafSlot[std::size_t(k)])] =
            lbvhLeaf(out.triangles[std::size_t(k)], k);
        for (std::int32_t p = leafParent[std::size_t(k)]; p >= 0; p = innerParent[std::size_t(p)]) {
            if (arrived[std::size_t(p)]++ == 0) {
                break;
            }
            out.nodes[std::size_t(innerSlot[std::size_t(p)])] =
                lbvhInner(out.nodes[std::size_t(1 + 2 * p)], out.nodes[std::size_t(2 + 2 * p)], p);
        }
    }
    return out;
}

#if !defined(WEIR_HAS_CUDA)
HostLbvh buildLbvhOnDevice(const std::vector<BvhTriangle>&) {
    throw std::runtime_error("the hierarchy's CUDA build: this weir was built without CUDA");
}
#endif

}  // namespace weir
