// The linear hierarchy's CUDA build (lbvh_cuda.cuh): the steps of lbvh.h, a thread per triangle or
// inner node, and the boxes filled in from the leaves up, each inner node by the second of its
// children's threads to arrive (an atomic counter per node).
#include <stdexcept>

#include "core/backend.h"
#include "raytrace/lbvh_cuda.cuh"

namespace weir {

namespace {

// A node another thread wrote, read past this SM's L1 (which does not see other SMs' writes).
__device__ BvhNode loadNodeFromL2(const BvhNode* node) {
    const float4* parts = reinterpret_cast<const float4*>(node);
    const float4 a = __ldcg(parts), b = __ldcg(parts + 1);
    BvhNode n;
    n.lo = Vec3f(a.x, a.y, a.z);
    n.first = __float_as_int(a.w);
    n.hi = Vec3f(b.x, b.y, b.z);
    n.count = __float_as_int(b.w);
    return n;
}

__global__ void fillBoxesKernel(const BvhTriangle* triangles, Index n, LbvhLinks links,
                                BvhNode* nodes, std::int32_t* arrived) {
    const Index k = Index(blockIdx.x * blockDim.x + threadIdx.x);
    if (k >= n) {
        return;
    }
    nodes[links.leafSlot[k]] = lbvhLeaf(triangles[k], k);
    for (std::int32_t p = links.leafParent[k]; p >= 0; p = links.innerParent[p]) {
        __threadfence();  // this thread's node written before the counter says so
        if (atomicAdd(&arrived[p], 1) == 0) {
            return;  // the sibling's thread comes later and goes on up
        }
        __threadfence();
        nodes[links.innerSlot[p]] =
            lbvhInner(loadNodeFromL2(nodes + 1 + 2 * p), loadNodeFromL2(nodes + 2 + 2 * p), p);
    }
}

}  // namespace

static_assert(sizeof(BvhNode) == 32, "loadNodeFromL2 reads a node as two float4");

void DeviceLbvh::build(CudaExec& exec, const BvhTriangle* triangles, const TriangleShading* shading,
                       Index n) {
    count_ = n;
    if (n <= 0) {
        count_ = 0;
        return;
    }
    const std::size_t size = std::size_t(n);
    bounds_.resize(6);
    codes_.resize(size);
    sortedCodes_.resize(size);
    identity_.resize(size);
    order_.resize(size);
    sortedTriangles_.resize(size);
    sortedShading_.resize(shading != nullptr ? size : 1);
    nodes_.resize(2 * size - 1);
    leafSlot_.resize(size);
    leafParent_.resize(size);
    innerSlot_.resize(std::max<std::size_t>(size - 1, 1));
    innerParent_.resize(std::max<std::size_t>(size - 1, 1));
    arrived_.resize(std::max<std::size_t>(size - 1, 1));

    // Morton codes of the key points over their bounds (read back to the host: none, the scale is
    // worked out by each thread from the 6 integers).
    int* lohi = bounds_.data();
    reduceBounds(
        exec.stream(), n,
        [=] __device__(Index i, Vec3f & lo, Vec3f & hi) {
            lo = hi = triangleKeyPoint(triangles[i]);
        },
        lohi);
    {
        std::uint32_t* codes = codes_.data();
        Index* identity = identity_.data();
        exec.forEach(n, [=] __device__(Index i) {
            const Vec3f lo(__int_as_float(lohi[0] >= 0 ? lohi[0] : lohi[0] ^ 0x7FFFFFFF),
                           __int_as_float(lohi[1] >= 0 ? lohi[1] : lohi[1] ^ 0x7FFFFFFF),
                           __int_as_float(lohi[2] >= 0 ? lohi[2] : lohi[2] ^ 0x7FFFFFFF));
            const Vec3f hi(__int_as_float(lohi[3] >= 0 ? lohi[3] : lohi[3] ^ 0x7FFFFFFF),
                           __int_as_float(lohi[4] >= 0 ? lohi[4] : lohi[4] ^ 0x7FFFFFFF),
                           __int_as_float(lohi[5] >= 0 ? lohi[5] : lohi[5] ^ 0x7FFFFFFF));
            codes[i] = mortonCode(triangleKeyPoint(triangles[i]), lo, mortonScale(lo, hi));
            identity[i] = i;
        });
    }
    exec.sortPairs(codes_.data(), sortedCodes_.data(), identity_.data(), order_.data(), n,
                   kMortonBits);
    {
        const Index* order = order_.data();
        BvhTriangle* sortedTriangles = sortedTriangles_.data();
        TriangleShading* sortedShading = sortedShading_.data();
        exec.forEach(n, [=] __device__(Index k) {
            sortedTriangles[k] = triangles[order[k]];
            if (shading != nullptr) {
                sortedShading[k] = shading[order[k]];
            }
        });
    }

    const LbvhLinks links{leafSlot_.data(), leafParent_.data(), innerSlot_.data(),
                          innerParent_.data()};
    BvhNode* nodes = nodes_.data();
    if (n == 1) {
        const BvhTriangle* sorted = sortedTriangles_.data();
        exec.forEach(1, [=] __device__(Index) { nodes[0] = lbvhLeaf(sorted[0], 0); });
        return;
    }
    {
        const std::uint32_t* sortedCodes = sortedCodes_.data();
        std::int32_t* arrived = arrived_.data();
        exec.forEach(n - 1, [=] __device__(Index i) {
            if (i == 0) {
                links.innerSlot[0] = 0;
                links.innerParent[0] = -1;
            }
            arrived[i] = 0;
            lbvhLink(lbvhChildrenOf(sortedCodes, n, i), i, links);
        });
    }
    const int block = 256;
    fillBoxesKernel<<<unsigned((n + block - 1) / block), block, 0, exec.stream()>>>(
        sortedTriangles_.data(), n, links, nodes, arrived_.data());
    WEIR_CUDA_CHECK(cudaGetLastError());
}

HostLbvh buildLbvhOnDevice(const std::vector<BvhTriangle>& triangles) {
    if (!cudaDeviceAvailable()) {
        throw std::runtime_error("no CUDA device is visible");
    }
    CudaExec exec;
    DeviceBuffer<BvhTriangle> input;
    exec.upload(input, triangles.data(), triangles.size());
    DeviceLbvh lbvh;
    lbvh.build(exec, input.data(), nullptr, Index(triangles.size()));
    HostLbvh out;
    const BvhView view = lbvh.view();
    out.nodes.resize(std::size_t(view.nodeCount));
    out.triangles.resize(triangles.size());
    std::vector<Index> order(triangles.size());
    exec.synchronize();
    if (!triangles.empty()) {
        exec.copyToHost(out.nodes.data(), view.nodes, out.nodes.size() * sizeof(BvhNode));
        exec.copyToHost(out.triangles.data(), view.triangles,
                        out.triangles.size() * sizeof(BvhTriangle));
        exec.copyToHost(order.data(), lbvh.order(), order.size() * sizeof(Index));
    }
    out.order.assign(order.begin(), order.end());
    return out;
}

}  // namespace weir
