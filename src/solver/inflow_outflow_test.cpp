// Emitters and sinks on the CPU (issue 18): an emitter lets in exactly the layers that have come
// due, each particle with a fresh id, moving at the emitter's velocity; a sink takes out what
// enters it and nothing else; the live count is always the initial one plus what came in minus
// what went out; a full reservoir refuses and counts what it refused; bad emitters and sinks are
// refused naming the field.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>

#include "scene/scene.h"
#include "scene/setup.h"
#include "solver/simulation.h"
#include "solver/solver_test_support.h"

namespace weir {
namespace {

Scene flowScene(const std::string& fields) {
    const std::string fluid =
        fields.find("\"fluid\"") == std::string::npos ? R"("fluid": {"preset": "water"}, )" : "";
    return parseScene(R"({"name": "flow_test", )" + fluid + fields + "}", "<test flow>");
}

// A tank 0.2 m square and 0.3 m high with 4 cm of water, a hose of radius 2 cm 0.25 m up
// pointing down at 1 m/s, at 1 cm spacing.
Scene hoseScene(const std::string& extra, double duration) {
    return flowScene(R"(
        "container": {"min": [0, 0, 0], "max": [0.2, 0.3, 0.2]},
        "blocks": [{"min": [0, 0, 0], "max": [0.2, 0.04, 0.2]}],
        "emitters": [{"disc": {"center": [0.1, 0.25, 0.1], "radius": 0.02},
                      "direction": [0, -1, 0], "speed": 1.0}],
        "particles": {"spacing": 0.01},
        "limits": {"maxSpeed": 4}, )" +
                     extra + R"("time": {"duration": )" + std::to_string(duration) + "}");
}

// Every id once, in increasing order (the frame's order).
void expectUniqueSortedIds(const HostParticles& p) {
    ASSERT_EQ(p.id.size(), p.size());
    for (std::size_t k = 1; k < p.id.size(); ++k) {
        ASSERT_LT(p.id[k - 1], p.id[k]) << "at " << k;
    }
}

TEST(InflowOutflow, EmitterLetsInTheLayersDueWithFreshIds) {
    const Scene scene = hoseScene("", 0.3);
    SetupReport report;
    const SimulationSetup setup = buildSetup(scene, {}, &report);
    ASSERT_EQ(setup.flow.emitters.size(), 1u);
    const Emitter emitter = setup.flow.emitters[0];
    // A disc of radius 2 spacings: the 13 lattice sites within it.
    EXPECT_EQ(emitter.siteCount, 13);
    const Index initial = Index(setup.particleCount());
    auto sim = makeSimulation(Backend::Cpu, NeighbourMode::Auto, setup);
    EXPECT_EQ(sim->particleCount(), initial);
    for (double t : {0.05, 0.1, 0.2, 0.3}) {
        sim->advanceTo(t);
        ASSERT_EQ(sim->fault().code, 0) << describeFault(sim->fault(), sim->params());
        const FlowCounters c = sim->flowCounters();
        // Each step lets in the layers due at its start: by t, those due at the last step's
        // start (one fewer than at t if a layer fell due inside the last step).
        ASSERT_EQ(c.emitted % emitter.siteCount, 0) << t;
        const Index layers = c.emitted / emitter.siteCount;
        EXPECT_GE(layers, emitter.layersDue(t) - 1) << t;
        EXPECT_LE(layers, emitter.layersDue(t)) << t;
        EXPECT_EQ(c.removed, 0);
        EXPECT_EQ(c.refused, 0);
        EXPECT_EQ(c.live, initial + c.emitted);
        EXPECT_EQ(c.nextId, initial + c.emitted);
        EXPECT_EQ(sim->particleCount(), c.live);
        HostParticles p;
        sim->download(p);
        ASSERT_EQ(Index(p.size()), c.live);
        expectUniqueSortedIds(p);
        EXPECT_EQ(p.id.front(), 0);
        EXPECT_EQ(p.id.back(), c.nextId - 1);
        // The newest layer has just left the disc, straight down at about 1 m/s; the jet below
        // it has fallen faster since (g t), and nothing moves up out of the hose's column.
        const std::size_t newest = p.size() - 1;
        EXPECT_NEAR(p.vy[newest], -1.0, 0.15);
        EXPECT_NEAR(p.y[newest], 0.25, 0.015);
        EXPECT_NEAR(p.x[newest], 0.1, 0.021);
        for (std::size_t k = std::size_t(initial); k < p.size(); ++k) {
            if (p.y[k] > 0.1) {
                ASSERT_LT(p.vy[k], -0.8) << "id " << p.id[k] << " at t " << t;
                ASSERT_LT(std::hypot(p.x[k] - 0.1, p.z[k] - 0.1), 0.035) << "id " << p.id[k];
            }
        }
    }
}

TEST(InflowOutflow, HoseFillsAnEmptyTank) {
    // No fluid at the start: the count starts at zero and the reservoir holds what comes in.
    const Scene scene = flowScene(R"(
        "container": {"min": [0, 0, 0], "max": [0.15, 0.2, 0.15]},
        "emitters": [{"rectangle": {"center": [0.075, 0.15, 0.075], "size": [0.03, 0.02]},
                      "direction": [0, -1, 0], "rate": 0.0006, "stop": 0.2}],
        "particles": {"spacing": 0.01},
        "time": {"duration": 0.4})");
    const SimulationSetup setup = buildSetup(scene, {}, nullptr);
    EXPECT_EQ(setup.particleCount(), 0);
    ASSERT_EQ(setup.flow.emitters.size(), 1u);
    EXPECT_EQ(setup.flow.emitters[0].siteCount, 6);                           // 3 x 2 sites
    EXPECT_NEAR(setup.flow.emitters[0].speed, 0.0006 / (0.03 * 0.02), 1e-6);  // rate / area
    auto sim = makeSimulation(Backend::Cpu, NeighbourMode::Auto, setup);
    EXPECT_EQ(sim->particleCount(), 0);
    sim->advanceTo(0.4);
    ASSERT_EQ(sim->fault().code, 0) << describeFault(sim->fault(), sim->params());
    const FlowCounters c = sim->flowCounters();
    // 1 m/s: a layer every 10 ms from 0 to 0.2 s inclusive, then none.
    EXPECT_EQ(c.emitted, 6 * setup.flow.emitters[0].layersDue(0.2));
    EXPECT_EQ(c.live, c.emitted);
    HostParticles p;
    sim->download(p);
    ASSERT_EQ(Index(p.size()), c.emitted);
    expectUniqueSortedIds(p);
    // The water has landed: all of it low in the tank, none left in the air.
    for (std::size_t k = 0; k < p.size(); ++k) {
        ASSERT_LT(p.y[k], 0.1) << "id " << p.id[k];
    }
}

TEST(InflowOutflow, SinkTakesOutWhatEntersIt) {
    // A dam break whose front runs into a drain along the far wall's foot.
    const Scene scene = flowScene(R"(
        "container": {"min": [0, 0, 0], "max": [0.4, 0.2, 0.1]},
        "blocks": [{"min": [0, 0, 0], "max": [0.1, 0.15, 0.1]}],
        "sinks": [{"min": [0.3, 0, 0], "max": [0.4, 0.03, 0.1]}],
        "particles": {"spacing": 0.01},
        "time": {"duration": 0.6})");
    const SimulationSetup setup = buildSetup(scene, {}, nullptr);
    const Index initial = Index(setup.particleCount());
    auto sim = makeSimulation(Backend::Cpu, NeighbourMode::Auto, setup);
    Index lastRemoved = 0;
    for (double t : {0.2, 0.4, 0.6}) {
        sim->advanceTo(t);
        ASSERT_EQ(sim->fault().code, 0) << describeFault(sim->fault(), sim->params());
        const FlowCounters c = sim->flowCounters();
        EXPECT_EQ(c.emitted, 0);
        EXPECT_GE(c.removed, lastRemoved);
        lastRemoved = c.removed;
        EXPECT_EQ(c.live, initial - c.removed);
        HostParticles p;
        sim->download(p);
        ASSERT_EQ(Index(p.size()), c.live);
        expectUniqueSortedIds(p);
        EXPECT_LT(p.id.back(), initial);
        // Nothing stays in the drain: what entered it in the last step has not been taken out
        // yet, so it lies at most one step's travel (under 2 mm at these speeds) inside.
        for (std::size_t k = 0; k < p.size(); ++k) {
            ASSERT_FALSE(p.x[k] > 0.302 && p.y[k] < 0.028) << "id " << p.id[k] << " at " << t;
        }
    }
    // The front reaches the drain (0.3 m from a 0.1 m column: ~0.25 s) and the drain takes a
    // good share of the water by 0.6 s.
    EXPECT_GT(lastRemoved, initial / 10);
}

TEST(InflowOutflow, FullReservoirRefusesAndCounts) {
    // The reservoir is sized for 0.05 s of the hose (the scene's duration); run to 0.15 s.
    const Scene scene = hoseScene("", 0.05);
    const SimulationSetup setup = buildSetup(scene, {}, nullptr);
    const Index initial = Index(setup.particleCount());
    const Index capacity = setup.flow.capacity;
    const Index sites = setup.flow.emitters[0].siteCount;
    auto sim = makeSimulation(Backend::Cpu, NeighbourMode::Auto, setup);
    sim->advanceTo(0.15);
    ASSERT_EQ(sim->fault().code, 0);
    const FlowCounters c = sim->flowCounters();
    EXPECT_GT(c.refused, 0);
    EXPECT_LE(c.live, capacity);
    EXPECT_GT(c.live, capacity - sites);  // filled to within one layer
    EXPECT_EQ(c.live, initial + c.emitted);
    EXPECT_EQ(c.emitted + c.refused, sites * setup.flow.emitters[0].layersDue(0.15 - 1e-9));
}

TEST(InflowOutflow, HoseAndDrainKeepTheBooks) {
    // Water comes in and drains out at the same time; parked slots are reused.
    const Scene scene =
        hoseScene(R"("sinks": [{"min": [0, 0, 0], "max": [0.2, 0.02, 0.2]}], )", 0.4);
    const SimulationSetup setup = buildSetup(scene, {}, nullptr);
    const Index initial = Index(setup.particleCount());
    auto sim = makeSimulation(Backend::Cpu, NeighbourMode::Auto, setup);
    sim->advanceTo(0.4);
    ASSERT_EQ(sim->fault().code, 0) << describeFault(sim->fault(), sim->params());
    const FlowCounters c = sim->flowCounters();
    EXPECT_GT(c.emitted, 0);
    EXPECT_GT(c.removed, 0);
    EXPECT_EQ(c.refused, 0);
    EXPECT_EQ(c.live, initial + c.emitted - c.removed);
    HostParticles p;
    sim->download(p);
    ASSERT_EQ(Index(p.size()), c.live);
    expectUniqueSortedIds(p);
    const std::set<Index> ids(p.id.begin(), p.id.end());
    EXPECT_EQ(Index(ids.size()), c.live);
}

TEST(InflowOutflow, OtherNeighbourSearchesAreRefused) {
    const SimulationSetup setup = buildSetup(hoseScene("", 0.1), {}, nullptr);
    try {
        makeSimulation(Backend::Cpu, NeighbourMode::Grid, setup);
        FAIL() << "the paper's grid ran with an emitter";
    } catch (const SimulationError& e) {
        EXPECT_NE(std::string(e.what()).find("--neighbours dense"), std::string::npos) << e.what();
    }
}

void expectSceneError(const std::string& fields, const std::string& field,
                      const std::string& fragment) {
    try {
        flowScene(fields);
        FAIL() << "accepted: " << fields;
    } catch (const SceneError& e) {
        const std::string text = e.what();
        EXPECT_NE(text.find("'" + field + "'"), std::string::npos) << text;
        EXPECT_NE(text.find(fragment), std::string::npos) << text;
    }
}

TEST(InflowOutflow, BadEmittersAndSinksAreRefusedNamingTheField) {
    const std::string box = R"("container": {"min": [0, 0, 0], "max": [1, 1, 1]},
        "blocks": [{"min": [0, 0, 0], "max": [1, 0.2, 1]}], )";
    const std::string disc = R"("disc": {"center": [0.5, 0.8, 0.5], "radius": 0.05})";
    expectSceneError(box + R"("emitters": [{"disc": {"center": [0.5, 0.8, 0.98], "radius": 0.05},
                     "direction": [0, -1, 0], "speed": 1}])",
                     "emitters[0]", "inside the container");
    expectSceneError(box + R"("emitters": [{)" + disc + R"(, "direction": [0, 0, 0], "speed": 1}])",
                     "emitters[0].direction", "a non-zero vector");
    expectSceneError(box + R"("emitters": [{)" + disc +
                         R"(, "direction": [0, -1, 0], "speed": 1, "rate": 0.01}])",
                     "emitters[0].speed", "exactly one of");
    expectSceneError(box + R"("emitters": [{)" + disc + R"(, "direction": [0, -1, 0]}])",
                     "emitters[0].speed", "missing");
    expectSceneError(
        box + R"("emitters": [{)" + disc + R"(, "direction": [0, -1, 0], "speed": -2}])",
        "emitters[0].speed", "> 0");
    expectSceneError(box + R"("emitters": [{)" + disc +
                         R"(, "direction": [0, -1, 0], "speed": 1, "start": 1, "stop": 0.5}])",
                     "emitters[0].stop", "after \"start\"");
    expectSceneError(box + R"("emitters": [{"direction": [0, -1, 0], "speed": 1}])", "emitters[0]",
                     "neither a disc nor a rectangle");
    expectSceneError(box + R"("emitters": [{"rectangle": {"center": [0.5, 0.5, 0.5],
                     "size": [0.1]}, "direction": [1, 0, 0], "speed": 1}])",
                     "emitters[0].rectangle.size", "an array of 2 numbers");
    expectSceneError(box + R"("sinks": [{"min": [2, 0, 0], "max": [3, 1, 1]}])", "sinks[0]",
                     "outside the container");
    expectSceneError(box + R"("sinks": [{"min": [0.4, 0.7, 0.4], "max": [0.6, 0.9, 0.6]}],
                     "emitters": [{)" +
                         disc + R"(, "direction": [0, -1, 0], "speed": 1}])",
                     "emitters[0]", "inside sinks[0]");
    expectSceneError(box + R"("fluid": {"model": "paper"},
                     "sinks": [{"min": [0, 0, 0], "max": [0.1, 0.1, 0.1]}])",
                     "sinks", "delta-sph");
    expectSceneError(box + R"("solver": "dfsph",
                     "emitters": [{)" +
                         disc + R"(, "direction": [0, -1, 0], "speed": 1}])",
                     "emitters", "wcsph");
}

}  // namespace
}  // namespace weir
