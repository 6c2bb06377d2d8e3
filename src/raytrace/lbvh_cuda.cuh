// The linear hierarchy built on the GPU (lbvh.h's steps, a thread per triangle or node): key
// point bounds, Morton codes, CUB's radix sort, the radix tree, boxes from the leaves up. Its
// buffers only grow: rebuilt every frame, it allocates only when the mesh outgrows them.
#pragma once

#include <algorithm>
#include <cstring>

#include "core/exec_cuda.cuh"
#include "raytrace/lbvh.h"
#include "raytrace/tracing_scene.h"

namespace weir {

class DeviceLbvh {
   public:
    // Builds over the n triangles at `triangles` (device memory), taking each one's shading (device
    // memory; may be null) into the hierarchy's order with it. Queued on exec's stream.
    void build(CudaExec& exec, const BvhTriangle* triangles, const TriangleShading* shading,
               Index n);

    BvhView view() const {
        return {nodes_.data(), sortedTriangles_.data(), count_ > 0 ? 2 * count_ - 1 : 0};
    }
    const TriangleShading* shading() const { return sortedShading_.data(); }
    const Index* order() const { return order_.data(); }  // order()[k]: the input index
    Index count() const { return count_; }

   private:
    DeviceBuffer<int> bounds_;  // key points' lo, hi as order-preserving integers
    DeviceBuffer<std::uint32_t> codes_, sortedCodes_;
    DeviceBuffer<Index> identity_, order_;
    DeviceBuffer<BvhTriangle> sortedTriangles_;
    DeviceBuffer<TriangleShading> sortedShading_;
    DeviceBuffer<BvhNode> nodes_;
    DeviceBuffer<std::int32_t> leafSlot_, leafParent_, innerSlot_, innerParent_, arrived_;
    Index count_ = 0;
};

// Bounds reduced on the GPU, as 6 ints (lo x, y, z, then hi x, y, z) of orderedFloatBits: the
// integers compare as the floats do, so atomicMin and atomicMax reduce them exactly.
__device__ inline int orderedFloatBits(float f) {
    const int i = __float_as_int(f);
    return i >= 0 ? i : i ^ 0x7FFFFFFF;
}
inline float floatOfOrderedBits(int i) {
    const int bits = i >= 0 ? i : i ^ 0x7FFFFFFF;
    float f;
    static_assert(sizeof f == sizeof bits);
    std::memcpy(&f, &bits, sizeof f);
    return f;
}

template <class Point>
__global__ void boundsKernel(Index n, Point point, int* lohi) {
    Vec3f lo(3.0e38f, 3.0e38f, 3.0e38f), hi(-3.0e38f, -3.0e38f, -3.0e38f);
    for (Index i = Index(blockIdx.x * blockDim.x + threadIdx.x); i < n;
         i += Index(gridDim.x * blockDim.x)) {
        Vec3f l, h;
        point(i, l, h);
        lo = Vec3f(fminf(lo.x, l.x), fminf(lo.y, l.y), fminf(lo.z, l.z));
        hi = Vec3f(fmaxf(hi.x, h.x), fmaxf(hi.y, h.y), fmaxf(hi.z, h.z));
    }
    for (int offset = 16; offset > 0; offset /= 2) {
        for (int a = 0; a < 3; ++a) {
            lo[a] = fminf(lo[a], __shfl_down_sync(0xFFFFFFFFu, lo[a], offset));
            hi[a] = fmaxf(hi[a], __shfl_down_sync(0xFFFFFFFFu, hi[a], offset));
        }
    }
    if ((threadIdx.x & 31) == 0) {
        for (int a = 0; a < 3; ++a) {
            atomicMin(&lohi[a], orderedFloatBits(lo[a]));
            atomicMax(&lohi[3 + a], orderedFloatBits(hi[a]));
        }
    }
}

// Queues the reduction: lohi reset, then the kernel (point(i, lo, hi) gives a box per item; a
// point's lo and hi are the same).
// (A template, as boundsKernel: a kernel defined in a header included by several .cu files.)
template <int Unused = 0>
__global__ void resetBoundsKernel(int* lohi) {
    const int a = int(threadIdx.x);
    if (a < 6) {
        lohi[a] = a < 3 ? 0x7FFFFFFF : int(0x80000000u);
    }
}

template <class Point>
void reduceBounds(cudaStream_t stream, Index n, Point point, int* lohi) {
    resetBoundsKernel<><<<1, 32, 0, stream>>>(lohi);
    WEIR_CUDA_CHECK(cudaGetLastError());
    if (n > 0) {
        const int block = 256;
        const int blocks = int(std::min<std::int64_t>((std::int64_t(n) + block - 1) / block, 1024));
        boundsKernel<<<blocks, block, 0, stream>>>(n, point, lohi);
        WEIR_CUDA_CHECK(cudaGetLastError());
    }
}

}  // namespace weir
