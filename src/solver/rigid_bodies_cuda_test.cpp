// Rigid bodies on the GPU against the CPU: the same bodies moved by the same fluid. Skipped where
// no GPU is visible (CI); run on the device machine before GPU work is done.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "scene/scene.h"
#include "scene/setup.h"
#include "solver/solver_test_support.h"

namespace weir {
namespace {

using namespace weir::testing;

TEST(RigidBodiesCuda, AgreesWithCpu) {
    if (!cudaDeviceAvailable()) {
        GTEST_SKIP() << "no CUDA device visible";
    }
    // A floating box dropped into a tank beside a paddle that turns: both kinds of body, both
    // ways of coupling.
    const Scene scene = parseScene(R"({"fluid": {"preset": "water"},
        "container": {"min": [0, 0, 0], "max": [0.4, 0.3, 0.2]},
        "blocks": [{"min": [0, 0, 0], "max": [0.4, 0.12, 0.2]}],
        "bodies": [
            {"box": {"min": [0.05, 0.15, 0.06], "max": [0.13, 0.21, 0.14]}, "density": 600},
            {"box": {"min": [0.26, 0.02, 0.07], "max": [0.34, 0.1, 0.13]},
             "motion": {"rotate": {"rate": [0, 0, 4]}}}],
        "particles": {"spacing": 0.01},
        "time": {"duration": 0.3}})",
                                   "<test bodies cuda>");
    SetupReport report;
    auto cpu = makeSimulation(Backend::Cpu, NeighbourMode::Auto, buildSetup(scene, {}, &report));
    auto gpu = makeSimulation(Backend::Cuda, NeighbourMode::Auto, buildSetup(scene, {}, nullptr));
    const double end = 0.3;
    cpu->advanceTo(end);
    gpu->advanceTo(end);
    ASSERT_EQ(gpu->fault().code, 0) << describeFault(gpu->fault(), gpu->params());
    ASSERT_EQ(cpu->fault().code, 0);
    const std::vector<RigidBody> a = cpu->rigidBodies(), b = gpu->rigidBodies();
    ASSERT_EQ(a.size(), 2u);
    ASSERT_EQ(b.size(), 2u);
    // The box has fallen into the water and been slowed by it on both.
    EXPECT_LT(a[0].x.y, 0.15);
    // Rounding differs and the splash amplifies it: the box lands within a fifth of a spacing of
    // the CPU's, moving at nearly the same velocity; the paddle has turned as far (to within
    // the step each takes last).
    EXPECT_LT(length(a[0].x - b[0].x), 0.2 * report.spacing);
    EXPECT_LT(length(a[0].v - b[0].v), 0.05 * length(a[0].v) + 0.01);
    EXPECT_NEAR(a[1].q.z, b[1].q.z, 0.01);
    EXPECT_GT(std::abs(a[1].q.z), 0.5);  // 1.2 rad by 0.3 s: sin(0.6)
    HostParticles pa, pb;
    cpu->download(pa);
    gpu->download(pb);
    EXPECT_LT(rmsPositionDifference(pa, pb), 0.5 * report.spacing);
    EXPECT_NEAR(maxSpeed(pa), maxSpeed(pb), 0.15 * maxSpeed(pa));
}

}  // namespace
}  // namespace weir
