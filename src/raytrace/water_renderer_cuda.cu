// The water look on CUDA: the scene copied to the GPU, one thread per pixel running the same
// tracePixel as the CPU loop, the radiance copied back.
#include "core/exec_cuda.cuh"
#include "raytrace/water_renderer.h"

namespace weir {

namespace {

// 16 x 8 pixels per block: neighbouring pixels' rays take similar paths through the hierarchy.
__global__ void tracePixelsKernel(TracingSceneView scene, WaterLook look, PinholeCamera camera,
                                  int width, int height, int samples, int firstSample,
                                  Vec3f* image) {
    const int x = int(blockIdx.x * blockDim.x + threadIdx.x);
    const int y = int(blockIdx.y * blockDim.y + threadIdx.y);
    if (x < width && y < height) {
        image[std::size_t(y) * std::size_t(width) + std::size_t(x)] =
            tracePixel(scene, look, camera, width, height, x, y, samples, firstSample);
    }
}

template <class T>
DeviceBuffer<T> deviceCopy(const std::vector<T>& host) {
    DeviceBuffer<T> buffer(std::max<std::size_t>(host.size(), 1));
    if (!host.empty()) {
        WEIR_CUDA_CHECK(cudaMemcpy(buffer.data(), host.data(), host.size() * sizeof(T),
                                   cudaMemcpyHostToDevice));
    }
    return buffer;
}

}  // namespace

std::vector<Vec3f> traceWaterImageCuda(const TracingScene& scene, const WaterLook& look,
                                       const PinholeCamera& camera, int width, int height,
                                       int samples, int firstSample) {
    const DeviceBuffer<BvhNode> nodes = deviceCopy(scene.bvh().nodes());
    const DeviceBuffer<BvhTriangle> triangles = deviceCopy(scene.bvh().triangles());
    const DeviceBuffer<TriangleShading> shading = deviceCopy(scene.shading());
    TracingSceneView view = scene.view();
    view.bvh.nodes = nodes.data();
    view.bvh.triangles = triangles.data();
    view.shading = shading.data();

    const std::size_t pixels = std::size_t(width) * std::size_t(height);
    DeviceBuffer<Vec3f> image(pixels);
    const dim3 block(16, 8);
    const dim3 grid(unsigned((width + 15) / 16), unsigned((height + 7) / 8));
    tracePixelsKernel<<<grid, block>>>(view, look, camera, width, height, samples, firstSample,
                                       image.data());
    WEIR_CUDA_CHECK(cudaGetLastError());
    std::vector<Vec3f> host(pixels);
    WEIR_CUDA_CHECK(
        cudaMemcpy(host.data(), image.data(), pixels * sizeof(Vec3f), cudaMemcpyDeviceToHost));
    return host;
}

}  // namespace weir
