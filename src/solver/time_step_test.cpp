// The adaptive time step: chosen on the device from the CFL, force and viscous conditions,
// frames landing exactly on output times, fixed steps when the scene gives one.
#include <gtest/gtest.h>

#include <cmath>

#include "solver/solver_test_support.h"

namespace weir {
namespace {

using namespace weir::testing;

TEST(TimeStep, FramesLandExactlyOnOutputTimes) {
    for (NeighbourMode mode : {NeighbourMode::Dense, NeighbourMode::Grid}) {
        auto sim = start(smallDamBreak(1000), Backend::Cpu, mode);
        ASSERT_TRUE(sim->params().adaptiveTimeStep);
        long long steps = 0;
        for (int frame = 1; frame <= 6; ++frame) {
            const double t = frame / 30.0;
            sim->advanceTo(t);
            EXPECT_EQ(sim->time(), t) << "frame " << frame;  // exactly, not nearly
            EXPECT_GT(sim->stepCount(), steps);
            steps = sim->stepCount();
        }
        EXPECT_EQ(sim->fault().code, 0);
        // Plain steps after a frame go on past it.
        sim->advance(3);
        EXPECT_GT(sim->time(), 6 / 30.0);
        EXPECT_EQ(sim->stepCount(), steps + 3);
    }
}

TEST(TimeStep, EachStepObeysTheCflLimitOfThePreviousState) {
    Scene scene = smallDamBreak(1500);
    auto sim = start(scene, Backend::Cpu, NeighbourMode::Dense);
    const SphParams& p = sim->params();
    HostParticles state;
    sim->download(state);
    double firstDt = 0, lastDt = 0;
    int binding = 0;
    for (int s = 0; s < 300; ++s) {
        const double vMax = maxSpeed(state), before = sim->time();
        sim->advance(1);
        const double dt = sim->time() - before;
        const double cfl =
            double(p.cflNumber) * double(p.kernel.h) / (double(p.speedOfSound) + vMax);
        ASSERT_GT(dt, 0);
        ASSERT_LE(dt, cfl * (1 + 1e-5)) << "step " << s;
        binding += dt > cfl * (1 - 1e-4) ? 1 : 0;
        firstDt = s == 0 ? dt : firstDt;
        lastDt = dt;
        sim->download(state);
    }
    // The fluid sped up, so the step shrank; and the CFL condition, not another, set most steps.
    EXPECT_GT(maxSpeed(state), 0.3);
    EXPECT_LT(lastDt, firstDt);
    EXPECT_GT(binding, 250);
    // It is larger than the fixed step derived for the expected top speed while the fluid is slow.
    EXPECT_GT(firstDt, double(p.timeStep));
}

TEST(TimeStep, ForceLimitBindsWhenAccelerationsDominate) {
    // Strong gravity on a soft fluid: 0.25 sqrt(h / |a|) is below the CFL value from the start
    // (the first step sees gravity alone), and it falls as the fluid piles up on the floor.
    Scene scene = parseScene(R"({
        "container": {"min": [0, 0, 0], "max": [0.3, 0.3, 0.3]},
        "blocks": [{"min": [0.05, 0.05, 0.05], "max": [0.25, 0.15, 0.25]}],
        "particles": {"spacing": 0.02},
        "gravity": [0, -5000, 0],
        "fluid": {"stiffness": 25},
        "limits": {"maxSpeed": 1000}
    })",
                             "<test heavy>");
    auto sim = start(scene, Backend::Cpu, NeighbourMode::Dense);
    const SphParams& p = sim->params();
    const double h = double(p.kernel.h);
    sim->advance(1);
    const double forceLimit = 0.25 * std::sqrt(h / 5000.0);
    EXPECT_NEAR(sim->time(), forceLimit, 1e-6 * forceLimit);
    EXPECT_LT(forceLimit, double(p.cflNumber) * h / double(p.speedOfSound));
    double smallest = forceLimit;
    for (int s = 0; s < 40; ++s) {
        const double before = sim->time();
        sim->advance(1);
        smallest = std::min(smallest, sim->time() - before);
    }
    EXPECT_LT(smallest, 0.99 * forceLimit);  // pressure adds to gravity at the floor
}

TEST(TimeStep, AGivenTimeStepIsFixedAndStillLandsOnFrames) {
    Scene scene = smallDamBreak(800);
    scene.timeStep = 7e-4;  // does not divide 1/30 s
    auto sim = start(scene, Backend::Cpu, NeighbourMode::Dense);
    ASSERT_FALSE(sim->params().adaptiveTimeStep);
    const double dt = double(sim->params().timeStep);
    sim->advance(5);
    EXPECT_NEAR(sim->time(), 5 * dt, 1e-12);
    sim->advanceTo(1 / 30.0);
    EXPECT_EQ(sim->time(), 1 / 30.0);
    EXPECT_EQ(sim->stepCount(), long(std::ceil(1 / 30.0 / dt - 1e-9)));
}

}  // namespace
}  // namespace weir
