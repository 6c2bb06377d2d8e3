// On a GPU, the water look's CUDA image is the CPU's: the same per-pixel function and the same
// random numbers, so pixels agree up to float rounding, except the few whose paths a rounding
// difference sends another way (a Fresnel choice, a grazing hit).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "raytrace/raytrace_test_support.h"
#include "raytrace/water_renderer.h"

namespace weir {
namespace {

using namespace weir::testing;

TEST(WaterLookCuda, CudaImageEqualsTheCpuImage) {
    if (!cudaDeviceAvailable()) {
        GTEST_SKIP()
            << "no CUDA device visible: the water look's CUDA path runs on GPU machines only";
    }
    const TriangleMesh ball = waterBall(Vec3f(0.5f, 0.45f, 0.5f), 0.25f);
    TracingSceneDescription description;
    description.water = &ball;
    description.container = {{0, 0, 0}, {1, 1, 1}};
    description.obstacleBoxes = {{{0.3, 0, 0.3}, {0.7, 0.2, 0.7}}};
    description.cameraEye = Vec3d(0.5, 1.4, 2.2);
    const TracingScene scene(description);
    const int width = 96, height = 64, samples = 32;
    const PinholeCamera camera =
        lookAt(Vec3f(description.cameraEye), Vec3f(0.5f, 0.4f, 0.5f), width, height);
    const WaterLook look;
    const std::vector<Vec3f> cpu =
        traceWaterImage(Backend::Cpu, scene, look, camera, width, height, samples);
    const std::vector<Vec3f> gpu =
        traceWaterImage(Backend::Cuda, scene, look, camera, width, height, samples);
    ASSERT_EQ(cpu.size(), gpu.size());
    double cpuSum = 0, gpuSum = 0;
    std::size_t close = 0;
    for (std::size_t i = 0; i < cpu.size(); ++i) {
        float worst = 0;
        for (int c = 0; c < 3; ++c) {
            worst = std::max(
                worst, std::abs(cpu[i][c] - gpu[i][c]) / std::max(0.05f, std::abs(cpu[i][c])));
        }
        close += worst < 1e-3f;
        cpuSum += double(cpu[i].x + cpu[i].y + cpu[i].z);
        gpuSum += double(gpu[i].x + gpu[i].y + gpu[i].z);
    }
    EXPECT_GT(double(close), 0.95 * double(cpu.size()))
        << close << " of " << cpu.size() << " pixels agree within 0.1%";
    EXPECT_NEAR(gpuSum, cpuSum, 0.005 * cpuSum);
}

}  // namespace
}  // namespace weir
