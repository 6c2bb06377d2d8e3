// The CUDA backend against the CPU one, and grid against brute force on the GPU.
// Skipped where no GPU is visible (CI); run on the device machine before GPU work is done.
#include <gtest/gtest.h>

#include "solver/solver_test_support.h"

namespace weir {
namespace {

using namespace weir::testing;

#define SKIP_WITHOUT_GPU()                                  \
    if (!cudaDeviceAvailable()) {                           \
        GTEST_SKIP() << "no CUDA device visible";           \
    }

TEST(CudaSolver, AgreesWithCpuAfterManySteps) {
    SKIP_WITHOUT_GPU();
    Scene scene = smallDamBreak(4000);
    SetupReport report;
    auto cpu = start(scene, Backend::Cpu, NeighbourMode::Grid, &report);
    auto gpu = start(scene, Backend::Cuda, NeighbourMode::Grid);
    const int steps = 300;
    HostParticles a = stateAfter(*cpu, steps), b = stateAfter(*gpu, steps);
    ASSERT_EQ(gpu->fault().code, 0);
    // FMA contraction on the GPU changes rounding; the fluid must still be the same fluid.
    EXPECT_LT(maxPositionDifference(a, b), 0.01 * report.spacing);
    EXPECT_NEAR(meanDensity(a), meanDensity(b), 1e-4 * scene.restDensity);
    EXPECT_GT(maxSpeed(b), 0.3);
}

TEST(CudaSolver, GridAndBruteForceAgree) {
    SKIP_WITHOUT_GPU();
    Scene scene = smallDamBreak(3000);
    SetupReport report;
    auto grid = start(scene, Backend::Cuda, NeighbourMode::Grid, &report);
    auto brute = start(scene, Backend::Cuda, NeighbourMode::Brute);
    HostParticles a = stateAfter(*grid, 60), b = stateAfter(*brute, 60);
    EXPECT_LT(maxPositionDifference(a, b), 1e-4 * report.spacing);
}

TEST(CudaSolver, BlowUpIsDetectedOnTheGpu) {
    SKIP_WITHOUT_GPU();
    Scene scene = smallDamBreak(1500);
    scene.timeStep = 0.005;  // 20x the CFL limit for this stiffness
    scene.stiffness = 1e5;
    auto sim = start(scene, Backend::Cuda, NeighbourMode::Grid);
    sim->advance(50);
    EXPECT_NE(sim->fault().code, 0);
}

TEST(CudaSolver, ConservesMomentum) {
    SKIP_WITHOUT_GPU();
    Scene scene = parseScene(R"({
        "container": {"min": [-1, -1, -1], "max": [1, 1, 1]},
        "spheres": [{"center": [-0.12, 0, 0], "radius": 0.1, "velocity": [1.0, 0.2, 0]},
                    {"center": [0.12, 0.03, 0], "radius": 0.1, "velocity": [-0.5, 0, 0.1]}],
        "gravity": [0, 0, 0],
        "particles": {"count": 20000}
    })",
                             "<test collision>");
    auto sim = start(scene, Backend::Cuda, NeighbourMode::Grid);
    HostParticles before;
    sim->download(before);
    HostParticles after = stateAfter(*sim, 400);
    Vec3d p0, p1;
    double scale = 0;
    for (std::size_t i = 0; i < before.size(); ++i) {
        p0 += Vec3d(before.vx[i], before.vy[i], before.vz[i]);
        p1 += Vec3d(after.vx[i], after.vy[i], after.vz[i]);
        scale += std::sqrt(double(before.vx[i]) * before.vx[i] + double(before.vy[i]) * before.vy[i] +
                           double(before.vz[i]) * before.vz[i]);
    }
    EXPECT_LT(length(p1 - p0), 1e-4 * scale);
}

}  // namespace
}  // namespace weir
