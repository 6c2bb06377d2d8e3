// Emitters and sinks on the GPU against the CPU: the same hose into the same drain keeps the same
// books, and the water goes the same way. Skipped where no GPU is visible (CI); run on the device
// machine before GPU work is done.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "scene/scene.h"
#include "scene/setup.h"
#include "solver/solver_test_support.h"

namespace weir {
namespace {

TEST(InflowOutflowCuda, AgreesWithCpu) {
    if (!cudaDeviceAvailable()) {
        GTEST_SKIP() << "no CUDA device visible";
    }
    const Scene scene = parseScene(R"({"fluid": {"preset": "water"},
        "container": {"min": [0, 0, 0], "max": [0.3, 0.3, 0.2]},
        "blocks": [{"min": [0, 0, 0], "max": [0.3, 0.04, 0.2]}],
        "emitters": [{"disc": {"center": [0.1, 0.25, 0.1], "radius": 0.03},
                      "direction": [0.3, -1, 0], "speed": 1.2}],
        "sinks": [{"min": [0.25, 0, 0], "max": [0.3, 0.03, 0.2]}],
        "particles": {"spacing": 0.01},
        "time": {"duration": 0.5}})",
                                   "<test flow cuda>");
    SetupReport report;
    auto cpu = makeSimulation(Backend::Cpu, NeighbourMode::Auto, buildSetup(scene, {}, &report));
    auto gpu = makeSimulation(Backend::Cuda, NeighbourMode::Auto, buildSetup(scene, {}, nullptr));
    const Index sites = buildSetup(scene, {}, nullptr).flow.emitters[0].siteCount;
    for (double t : {0.25, 0.5}) {
        cpu->advanceTo(t);
        gpu->advanceTo(t);
        ASSERT_EQ(gpu->fault().code, 0) << describeFault(gpu->fault(), gpu->params());
        ASSERT_EQ(cpu->fault().code, 0);
        const FlowCounters a = cpu->flowCounters(), b = gpu->flowCounters();
        // Each lets in the layers due at its steps' starts: the same, or one layer apart where a
        // layer fell due inside the last step of one and not the other.
        EXPECT_LE(std::abs(a.emitted - b.emitted), sites) << t;
        EXPECT_EQ(b.live,
                  Index(buildSetup(scene, {}, nullptr).particleCount()) + b.emitted - b.removed);
        EXPECT_EQ(b.refused, 0);
        // The drain takes about as much on both (the splash that reaches it differs in detail).
        EXPECT_LE(std::abs(a.removed - b.removed), 0.1 * a.removed + 2 * sites) << t;
        HostParticles pa, pb;
        cpu->download(pa);
        gpu->download(pb);
        ASSERT_EQ(Index(pb.size()), b.live);
        for (std::size_t k = 1; k < pb.id.size(); ++k) {
            ASSERT_LT(pb.id[k - 1], pb.id[k]);
        }
        double sum = 0;
        std::size_t common = 0;
        for (std::size_t i = 0, j = 0; i < pa.size() && j < pb.size();) {
            if (pa.id[i] < pb.id[j]) {
                ++i;
            } else if (pb.id[j] < pa.id[i]) {
                ++j;
            } else {
                sum += std::sqrt(std::pow(pa.x[i] - pb.x[j], 2) + std::pow(pa.y[i] - pb.y[j], 2) +
                                 std::pow(pa.z[i] - pb.z[j], 2));
                ++common;
                ++i;
                ++j;
            }
        }
        ASSERT_GT(common, pa.size() * 9 / 10);
        if (t < 0.3) {
            // Before the jet lands, the same ids hold the same places: the mean distance
            // between a particle on the CPU and the one with its id on the GPU is under a
            // spacing. (After it lands the splash amplifies rounding: 2.7 spacings at 0.5 s on
            // an H200.)
            EXPECT_LT(sum / double(common), report.spacing) << t;
        }
        // The water as a whole is in the same place: its centre within a spacing.
        double ya = 0, yb = 0, xa = 0, xb = 0;
        for (std::size_t i = 0; i < pa.size(); ++i) {
            ya += pa.y[i] / double(pa.size());
            xa += pa.x[i] / double(pa.size());
        }
        for (std::size_t j = 0; j < pb.size(); ++j) {
            yb += pb.y[j] / double(pb.size());
            xb += pb.x[j] / double(pb.size());
        }
        EXPECT_NEAR(ya, yb, report.spacing) << t;
        EXPECT_NEAR(xa, xb, report.spacing) << t;
    }
}

}  // namespace
}  // namespace weir
