// Tests for scene files: the shipped scenes, defaults, and one error per validation rule.
#include "scene/scene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>

namespace weir {
namespace {

using Json = nlohmann::json;

// Like gmock's HasSubstr, which would need libgmock (the test binary links only gtest).
::testing::AssertionResult contains(const std::string& text, const std::string& part) {
    if (text.find(part) != std::string::npos) {
        return ::testing::AssertionSuccess();
    }
    return ::testing::AssertionFailure() << "\"" << text << "\" lacks \"" << part << "\"";
}

void expectVec(const Vec3d& v, double x, double y, double z) {
    EXPECT_DOUBLE_EQ(v.x, x);
    EXPECT_DOUBLE_EQ(v.y, y);
    EXPECT_DOUBLE_EQ(v.z, z);
}

// The message of the SceneError that parsing text throws ("" and a test failure if none).
std::string errorOf(const std::string& text, const std::string& source = "bad.json") {
    try {
        parseScene(text, source);
    } catch (const SceneError& e) {
        return e.what();
    }
    ADD_FAILURE() << "no SceneError for " << text;
    return "";
}

// A valid scene that uses every object; each bad case changes one field of it.
const char* kValidScene = R"({
    "name": "valid",
    "description": "every object present",
    "container": {"min": [0, 0, 0], "max": [1.6, 1.0, 0.6]},
    "blocks": [{"min": [0, 0, 0], "max": [0.4, 0.6, 0.6], "velocity": [0, 0, 0]}],
    "spheres": [{"center": [0.8, 0.5, 0.3], "radius": 0.15, "velocity": [0, -1, 0]}],
    "obstacles": {"boxes": [{"min": [1.0, 0, 0], "max": [1.2, 0.2, 0.6]}],
                  "spheres": [{"center": [1.4, 0.1, 0.3], "radius": 0.1}]},
    "fluid": {"restDensity": 998, "viscosity": 0.5, "stiffness": 1000},
    "particles": {"count": 1000, "smoothingRatio": 2.5},
    "gravity": [0, -9.81, 0],
    "time": {"duration": 1.5, "frameRate": 60, "timeStep": 0.0002,
             "integrator": "explicit-euler"},
    "walls": {"restitution": 0.3, "friction": 0.1},
    "limits": {"maxSpeed": 50}
})";

TEST(Scene, ValidSceneReadsEveryField) {
    Scene s = parseScene(kValidScene, "valid.json");
    EXPECT_EQ(s.name, "valid");
    EXPECT_EQ(s.description, "every object present");
    EXPECT_EQ(s.sourcePath, "valid.json");
    expectVec(s.container.max, 1.6, 1.0, 0.6);
    ASSERT_EQ(s.blocks.size(), 1u);
    expectVec(s.blocks[0].box.max, 0.4, 0.6, 0.6);
    ASSERT_EQ(s.spheres.size(), 1u);
    expectVec(s.spheres[0].sphere.center, 0.8, 0.5, 0.3);
    EXPECT_DOUBLE_EQ(s.spheres[0].sphere.radius, 0.15);
    expectVec(s.spheres[0].velocity, 0, -1, 0);
    ASSERT_EQ(s.obstacleBoxes.size(), 1u);
    expectVec(s.obstacleBoxes[0].min, 1.0, 0, 0);
    ASSERT_EQ(s.obstacleSpheres.size(), 1u);
    EXPECT_DOUBLE_EQ(s.obstacleSpheres[0].radius, 0.1);
    EXPECT_DOUBLE_EQ(s.restDensity, 998);
    EXPECT_EQ(s.viscosity, 0.5);
    EXPECT_EQ(s.stiffness, 1000.0);
    EXPECT_EQ(s.particleCount, 1000);
    EXPECT_FALSE(s.spacing);
    EXPECT_DOUBLE_EQ(s.smoothingRatio, 2.5);
    expectVec(s.gravity, 0, -9.81, 0);
    EXPECT_DOUBLE_EQ(s.duration, 1.5);
    EXPECT_DOUBLE_EQ(s.frameRate, 60);
    EXPECT_EQ(s.timeStep, 0.0002);
    EXPECT_EQ(s.integrator, Integrator::ExplicitEuler);
    EXPECT_DOUBLE_EQ(s.wallRestitution, 0.3);
    EXPECT_DOUBLE_EQ(s.wallFriction, 0.1);
    EXPECT_EQ(s.maxSpeed, 50.0);
}

TEST(Scene, OmittedFieldsTakeDefaults) {
    Scene s = parseScene(R"({"container": {"min": [0, 0, 0], "max": [1, 1, 1]},
                             "blocks": [{"min": [0, 0, 0], "max": [1, 0.5, 1]}]})",
                         "some/dir/minimal.json");
    EXPECT_EQ(s.name, "minimal");  // the file stem
    EXPECT_EQ(s.description, "");
    expectVec(s.blocks[0].velocity, 0, 0, 0);
    EXPECT_TRUE(s.spheres.empty());
    EXPECT_TRUE(s.obstacleBoxes.empty());
    EXPECT_TRUE(s.obstacleSpheres.empty());
    EXPECT_DOUBLE_EQ(s.restDensity, 1000);
    EXPECT_FALSE(s.viscosity);
    EXPECT_FALSE(s.stiffness);
    EXPECT_FALSE(s.particleCount);
    EXPECT_FALSE(s.spacing);
    EXPECT_DOUBLE_EQ(s.smoothingRatio, 3.0);  // delta-SPH's (defaultSmoothingRatio)
    expectVec(s.gravity, 0, -9.81, 0);
    EXPECT_DOUBLE_EQ(s.duration, 2.0);
    EXPECT_DOUBLE_EQ(s.frameRate, 30);
    EXPECT_FALSE(s.timeStep);
    EXPECT_EQ(s.integrator, Integrator::SemiImplicitEuler);
    EXPECT_DOUBLE_EQ(s.wallRestitution, 0);
    EXPECT_DOUBLE_EQ(s.wallFriction, 0);
    EXPECT_FALSE(s.maxSpeed);
}

TEST(Scene, SpacingInsteadOfCountAndSpheresOnly) {
    Scene s = parseScene(R"({"container": {"min": [0, 0, 0], "max": [1, 1, 1]},
                             "spheres": [{"center": [0.5, 0.5, 0.5], "radius": 0.5}],
                             "particles": {"spacing": 0.01}})",
                         "s.json");
    EXPECT_EQ(s.spacing, 0.01);
    EXPECT_FALSE(s.particleCount);
    EXPECT_EQ(s.spheres.size(), 1u);  // touching the walls counts as inside
}

// The smoothing ratio follows the model and the solver unless the scene gives one: 3 for
// delta-SPH under WCSPH (enough neighbours for small waves), 2 for the paper's model and DFSPH;
// re-reading the scene with another model or solver follows it too.
TEST(Scene, SmoothingRatioFollowsTheModelAndSolverUnlessGiven) {
    const std::string base = R"({"container": {"min": [0, 0, 0], "max": [1, 1, 1]},
                             "blocks": [{"min": [0, 0, 0], "max": [1, 0.5, 1]}])";
    const Scene delta = parseScene(base + "}", "r.json");
    EXPECT_DOUBLE_EQ(delta.smoothingRatio, 3.0);
    EXPECT_DOUBLE_EQ(
        parseScene(base + R"(, "fluid": {"model": "paper"}})", "r.json").smoothingRatio, 2.0);
    EXPECT_DOUBLE_EQ(parseScene(base + R"(, "solver": "dfsph"})", "r.json").smoothingRatio, 2.0);
    EXPECT_DOUBLE_EQ(withFluidModel(delta, "paper").smoothingRatio, 2.0);
    EXPECT_DOUBLE_EQ(withSolver(delta, "dfsph").smoothingRatio, 2.0);
    const Scene given =
        parseScene(base + R"(, "particles": {"count": 100, "smoothingRatio": 2.5}})", "r.json");
    EXPECT_DOUBLE_EQ(withFluidModel(given, "paper").smoothingRatio, 2.5);
}

TEST(Scene, CommentsAreAllowed) {
    Scene s = parseScene(R"({"container": {"min": [0, 0, 0], "max": [1, 1, 1]},  // metres
                             "blocks": [{"min": [0, 0, 0], "max": [1, 0.5, 1]}]})",
                         "c.json");
    EXPECT_EQ(s.blocks.size(), 1u);
}

TEST(Scene, ShippedDamBreak) {
    Scene s = builtinScene("dam_break");
    EXPECT_EQ(s.name, "dam_break");
    EXPECT_EQ(s.sourcePath, "<built-in dam_break>");
    EXPECT_FALSE(s.description.empty());
    expectVec(s.container.min, 0, 0, 0);
    expectVec(s.container.max, 1.6, 1.0, 0.6);
    ASSERT_EQ(s.blocks.size(), 1u);
    expectVec(s.blocks[0].box.min, 0, 0, 0);
    expectVec(s.blocks[0].box.max, 0.4, 0.6, 0.6);
    EXPECT_TRUE(s.spheres.empty());
    EXPECT_EQ(s.particleCount, 20000);
    EXPECT_DOUBLE_EQ(s.smoothingRatio, 3.0);  // the model's default: the scene gives none
    expectVec(s.gravity, 0, -9.81, 0);
    EXPECT_DOUBLE_EQ(s.duration, 2.0);
    EXPECT_DOUBLE_EQ(s.frameRate, 30);
    // Water, under the default model (delta-SPH: its walls are boundary particles).
    EXPECT_EQ(s.preset, "water");
    EXPECT_DOUBLE_EQ(s.restDensity, 998);
    EXPECT_DOUBLE_EQ(s.physicalViscosity, 1e-3);
    EXPECT_EQ(s.model, FluidModelName::DeltaSph);
    EXPECT_EQ(s.walls, WallModel::Particles);
    EXPECT_EQ(s.eos, EquationOfState::Tait);
    EXPECT_FALSE(s.viscosity);
    EXPECT_FALSE(s.stiffness);
    EXPECT_FALSE(s.timeStep);
}

TEST(Scene, ShippedDoubleDamBreak) {
    Scene s = builtinScene("double_dam_break");
    EXPECT_EQ(s.name, "double_dam_break");
    EXPECT_FALSE(s.description.empty());
    expectVec(s.container.max, 1.6, 1.0, 0.6);
    ASSERT_EQ(s.blocks.size(), 2u);
    expectVec(s.blocks[0].box.min, 0, 0, 0);
    expectVec(s.blocks[0].box.max, 0.3, 0.6, 0.6);
    expectVec(s.blocks[1].box.min, 1.3, 0, 0);
    expectVec(s.blocks[1].box.max, 1.6, 0.6, 0.6);
    EXPECT_EQ(s.particleCount, 30000);
    EXPECT_DOUBLE_EQ(s.duration, 2.5);
    EXPECT_DOUBLE_EQ(s.restDensity, 998);
    EXPECT_FALSE(s.viscosity);
    EXPECT_FALSE(s.stiffness);
    EXPECT_FALSE(s.timeStep);
}

TEST(Scene, ShippedDropIntoPool) {
    Scene s = builtinScene("drop_into_pool");
    EXPECT_EQ(s.name, "drop_into_pool");
    EXPECT_FALSE(s.description.empty());
    expectVec(s.container.max, 1, 1, 1);
    ASSERT_EQ(s.blocks.size(), 1u);
    expectVec(s.blocks[0].box.max, 1, 0.25, 1);
    ASSERT_EQ(s.spheres.size(), 1u);
    expectVec(s.spheres[0].sphere.center, 0.5, 0.65, 0.5);
    EXPECT_DOUBLE_EQ(s.spheres[0].sphere.radius, 0.15);
    expectVec(s.spheres[0].velocity, 0, -1, 0);
    EXPECT_EQ(s.particleCount, 40000);
    EXPECT_DOUBLE_EQ(s.duration, 2.0);
    EXPECT_DOUBLE_EQ(s.restDensity, 998);
}

// Every shipped scene names its fluid (so delta-SPH, the default, gets its own viscosity) and
// runs the default model; the paper's is one setting away, with the paper's defaults.
TEST(Scene, ShippedScenesNameTheirFluidAndRunTheDefaultModel) {
    for (const std::string& name : builtinSceneNames()) {
        const Scene s = builtinScene(name);
        EXPECT_FALSE(s.preset.empty()) << name;
        EXPECT_EQ(s.model, FluidModelName::DeltaSph) << name;
        // Rigid bodies couple through delta-SPH's walls only; emitters and sinks run with it only.
        const char* deltaOnly = !s.bodies.empty()     ? "bodies"
                                : !s.emitters.empty() ? "emitters"
                                : !s.sinks.empty()    ? "sinks"
                                                      : nullptr;
        if (deltaOnly != nullptr) {
            try {
                withFluidModel(s, "paper");
                ADD_FAILURE() << name << " ran its " << deltaOnly << " under the paper's model";
            } catch (const SceneError& e) {
                EXPECT_NE(std::string(e.what()).find("field '" + std::string(deltaOnly) + "'"),
                          std::string::npos)
                    << e.what();
            }
            continue;
        }
        const Scene paper = withFluidModel(s, "paper");
        EXPECT_EQ(paper.model, FluidModelName::Paper) << name;
        EXPECT_EQ(paper.name, s.name);
        EXPECT_EQ(paper.sourcePath, s.sourcePath);
        EXPECT_EQ(paper.particleCount, s.particleCount) << name;
        EXPECT_EQ(paper.eos, EquationOfState::Linear) << name;  // the paper's eq. 3
        EXPECT_TRUE(paper.clampNegativePressure) << name;
        // Simple walls, unless the scene asks for boundary particles (viscous_pour does).
        EXPECT_EQ(paper.walls, s.json.find("\"walls\"") == std::string::npos ? WallModel::Simple
                                                                             : WallModel::Particles)
            << name;
        EXPECT_EQ(withFluidModel(paper, "delta-sph").json, withFluidModel(s, "delta-sph").json);
    }
}

TEST(Scene, ModelDefaultsToDeltaSphAndPaperIsOneSettingAway) {
    const std::string base = R"({"container": {"min": [0, 0, 0], "max": [1, 1, 1]},
        "blocks": [{"min": [0, 0, 0], "max": [0.5, 0.5, 0.5]}])";
    const Scene delta = parseScene(base + "}", "d.json");
    EXPECT_EQ(delta.model, FluidModelName::DeltaSph);
    EXPECT_EQ(delta.walls, WallModel::Particles);
    EXPECT_EQ(delta.eos, EquationOfState::Tait);
    EXPECT_FALSE(delta.clampNegativePressure);
    const Scene paper = parseScene(base + R"(, "fluid": {"model": "paper"}})", "p.json");
    EXPECT_EQ(paper.model, FluidModelName::Paper);
    EXPECT_EQ(paper.walls, WallModel::Simple);
    EXPECT_EQ(paper.eos, EquationOfState::Linear);
    EXPECT_TRUE(paper.clampNegativePressure);
    // A delta-SPH field asked of the paper's model is refused, naming the field.
    const Scene shifted = parseScene(base + R"(, "fluid": {"densityDiffusion": 0.1}})", "s.json");
    try {
        withFluidModel(shifted, "paper");
        FAIL() << "no SceneError";
    } catch (const SceneError& e) {
        EXPECT_TRUE(contains(e.what(), "fluid.densityDiffusion")) << e.what();
    }
}

TEST(Scene, BuiltinNamesListEveryShippedScene) {
    std::vector<std::string> names = builtinSceneNames();
    for (const char* name : {"dam_break", "double_dam_break", "drop_into_pool"}) {
        EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
    }
    for (const std::string& name : names) {
        EXPECT_NO_THROW(builtinScene(name)) << name;
    }
}

TEST(Scene, UnknownBuiltinListsAvailableNames) {
    try {
        builtinScene("dam_brake");
        FAIL() << "no SceneError";
    } catch (const SceneError& e) {
        EXPECT_TRUE(contains(e.what(), "'dam_brake'"));
        // Every built-in scene, in order (issue 20 added scenes to the three of this list).
        std::string all;
        for (const std::string& name : builtinSceneNames()) {
            all += (all.empty() ? "" : ", ") + name;
        }
        EXPECT_TRUE(contains(e.what(), all));
        EXPECT_TRUE(
            contains(e.what(), "dam_break, dam_break_obstacle, double_dam_break, drop_into_pool"));
        EXPECT_TRUE(contains(e.what(), "did you mean 'dam_break'?"));
    }
}

#ifdef WEIR_SOURCE_DIR
TEST(Scene, ShippedFilesLoadFromDisk) {
    for (const std::string& name : builtinSceneNames()) {
        std::string path = std::string(WEIR_SOURCE_DIR) + "/scenes/" + name + ".json";
        Scene s = loadScene(path);
        EXPECT_EQ(s.name, name);
        EXPECT_EQ(s.sourcePath, path);
        EXPECT_EQ(s.particleCount, builtinScene(name).particleCount);
    }
}
#endif

// One bad value: the JSON pointer it replaces in kValidScene (a missing value removes the
// field) and what the message must hold: the field path, the value as written, what is allowed.
struct BadCase {
    const char* pointer;
    std::optional<const char*> value;
    const char* field;
    const char* written;
    const char* allowed;
};

const BadCase kBadCases[] = {
    // Types and shapes.
    {"", "[1, 2]", "the top level", "[1, 2]", "an object with keys name, description"},
    {"/container", std::nullopt, "'container'", "missing", "an object {\"min\""},
    {"/container/min", "\"zero\"", "'container.min'", "\"zero\"", "an array of 3 finite numbers"},
    {"/gravity", "[0, -9.81]", "'gravity'", "[0, -9.81]", "an array of 3 finite numbers"},
    {"/blocks/0/velocity", "[0, \"a\", 0]", "'blocks[0].velocity'", "[0, \"a\", 0]",
     "an array of 3 finite numbers"},
    {"/blocks", "{}", "'blocks'", "{}", "an array of objects with keys min, max, velocity"},
    {"/blocks/0", "7", "'blocks[0]'", "7", "an object with keys min, max, velocity"},
    {"/fluid", "5", "'fluid'", "5",
     "an object with keys preset, restDensity, viscosity, stiffness, eos, pressureForce"},
    {"/fluid/restDensity", "\"1000\"", "'fluid.restDensity'", "\"1000\"", "a number > 0"},
    {"/fluid/preset", "\"mercury\"", "'fluid.preset'", "\"mercury\"", "one of water, oil, honey"},
    {"/fluid/eos", "\"ideal\"", "'fluid.eos'", "\"ideal\"",
     "\"linear\" (the paper's eq. 3) or \"tait\""},
    {"/fluid/negativePressureScale", "2", "'fluid.negativePressureScale'", "2",
     "a number in [0, 1]"},
    {"/fluid/tensileCorrection", "-0.1", "'fluid.tensileCorrection'", "-0.1", "a number in [0, 1]"},
    {"/walls/model", "\"mirror\"", "'walls.model'", "\"mirror\"",
     "\"particles\" (boundary particles, Akinci et al. 2012) or \"simple\""},
    {"/time/adaptive", "1", "'time.adaptive'", "1", "true or false"},
    {"/name", "5", "'name'", "5", "a string"},
    {"/name", "\"\"", "'name'", "\"\"", "a non-empty string"},
    {"/description", "true", "'description'", "true", "a string"},
    {"/spheres/0/radius", std::nullopt, "'spheres[0].radius'", "missing", "a number > 0"},
    // Unknown keys at every level, with the allowed ones.
    {"/gravty", "[0, -9.81, 0]", "'gravty'", "an unknown key (did you mean 'gravity'?)",
     "one of: name, description, container, blocks, spheres, obstacles, bodies, emitters, sinks, "
     "fluid, particles"},
    {"/fluid/restDensty", "1000", "'fluid.restDensty'", "(did you mean 'restDensity'?)",
     "one of: preset, restDensity, viscosity, stiffness, eos, pressureForce"},
    {"/blocks/0/speed", "[0, 0, 0]", "'blocks[0].speed'", "an unknown key",
     "one of: min, max, velocity"},
    {"/obstacles/planes", "[]", "'obstacles.planes'", "an unknown key", "one of: boxes, spheres"},
    // Geometry.
    {"/container/max", "[1.6, 0, 0.6]", "'container.max'", "[1.6, 0, 0.6]",
     "greater than min [0, 0, 0] on every axis (it is not on y)"},
    {"/blocks/0/max", "[0.4, 0.6, 0]", "'blocks[0].max'", "[0.4, 0.6, 0]",
     "greater than min [0, 0, 0] on every axis (it is not on z)"},
    {"/obstacles/boxes/0/max", "[0.9, 0.2, 0.6]", "'obstacles.boxes[0].max'", "[0.9, 0.2, 0.6]",
     "greater than min [1.0, 0, 0] on every axis (it is not on x)"},
    {"/spheres/0/radius", "0", "'spheres[0].radius'", "is 0", "a number > 0"},
    {"/obstacles/spheres/0/radius", "-0.1", "'obstacles.spheres[0].radius'", "-0.1",
     "a number > 0"},
    {"/blocks/0/max", "[1.7, 0.6, 0.6]", "'blocks[0]'", "max [1.7, 0.6, 0.6]",
     "inside the container [0, 0, 0] to [1.6, 1, 0.6] (it sticks out by 0.1 on +x)"},
    {"/spheres/0/center", "[0.8, 0.9, 0.1]", "'spheres[0]'", "center [0.8, 0.9, 0.1]",
     "inside the container [0, 0, 0] to [1.6, 1, 0.6] (it sticks out by 0.05 on +y, 0.05 on -z)"},
    {"/blocks", "[]", "'blocks'", "[]", "a non-empty array of fluid blocks"},
    // Fluid.
    {"/fluid/restDensity", "-5", "'fluid.restDensity'", "is -5", "a number > 0"},
    {"/fluid/viscosity", "-0.1", "'fluid.viscosity'", "-0.1", "a number >= 0"},
    {"/fluid/stiffness", "0", "'fluid.stiffness'", "is 0", "a number > 0"},
    // Particles.
    {"/particles/count", "0", "'particles.count'", "is 0", "an integer in [1, 2147483647]"},
    {"/particles/count", "2147483648", "'particles.count'", "2147483648",
     "an integer in [1, 2147483647]"},
    {"/particles/count", "1.5", "'particles.count'", "1.5", "an integer in [1, 2147483647]"},
    {"/particles/spacing", "0.01", "'particles'", "\"spacing\":0.01",
     "an object with at most one of 'count' and 'spacing'"},
    {"/particles", "{\"spacing\": -0.01}", "'particles.spacing'", "-0.01", "a number > 0"},
    {"/particles/smoothingRatio", "1.0", "'particles.smoothingRatio'", "1.0",
     "a number in [1.2, 5]"},
    {"/particles/smoothingRatio", "6", "'particles.smoothingRatio'", "6", "a number in [1.2, 5]"},
    // Time.
    {"/time/duration", "0", "'time.duration'", "is 0", "a number > 0"},
    {"/time/frameRate", "-30", "'time.frameRate'", "-30", "a number > 0"},
    {"/time/timeStep", "0", "'time.timeStep'", "is 0", "a number > 0"},
    {"/time/timeStep", "0.1", "'time.timeStep'", "0.1",
     "a number > 0 and <= 0.01666666667 (1 / frameRate)"},
    {"/time/integrator", "\"rk4\"", "'time.integrator'", "\"rk4\"",
     "one of \"semi-implicit-euler\", \"explicit-euler\""},
    {"/time/integrator", "2", "'time.integrator'", "is 2", "a string"},
    // Walls and limits.
    {"/walls/restitution", "1.5", "'walls.restitution'", "1.5", "a number in [0, 1]"},
    {"/walls/friction", "-0.1", "'walls.friction'", "-0.1", "a number in [0, 1]"},
    {"/limits/maxSpeed", "0", "'limits.maxSpeed'", "is 0", "a number > 0"},
    // The settings of solver dfsph.
    {"/dfsph/densityError", "0", "'dfsph.densityError'", "is 0", "a number > 0 and <= 10"},
    {"/dfsph/divergenceError", "-1", "'dfsph.divergenceError'", "-1", "a number in [0, 100]"},
    {"/dfsph/maxSweeps", "1", "'dfsph.maxSweeps'", "is 1", "an integer in [2, 10000]"},
    {"/dfsph/worstDensityError", "-1", "'dfsph.worstDensityError'", "-1", "a number in [0, 100]"},
    {"/dfsph/maxSweeps", "20.5", "'dfsph.maxSweeps'", "20.5", "an integer in [2, 10000]"},
    {"/dfsph/cfl", "3", "'dfsph.cfl'", "is 3", "a number > 0 and <= 2"},
    {"/dfsph/tolerance", "1", "'dfsph.tolerance'", "an unknown key",
     "one of: densityError, divergenceError, worstDensityError, maxSweeps, cfl"},
};

TEST(Scene, EachBadValueNamesFileFieldValueAndAllowedRange) {
    for (const BadCase& c : kBadCases) {
        Json scene = Json::parse(kValidScene);
        Json::json_pointer pointer(c.pointer);
        if (c.value) {
            scene[pointer] = Json::parse(*c.value);
        } else {
            scene[pointer.parent_pointer()].erase(pointer.back());
        }
        if (c.pointer == std::string("/blocks")) {
            scene.erase("spheres");  // no fluid at all
        }
        std::string message = errorOf(scene.dump(), "scenes/bad.json");
        SCOPED_TRACE(std::string(c.pointer) + " = " + c.value.value_or("(removed)"));
        EXPECT_TRUE(contains(message, "scene 'scenes/bad.json'"));
        EXPECT_TRUE(contains(message, c.field));
        EXPECT_TRUE(contains(message, c.written));
        EXPECT_TRUE(contains(message, "must be " + std::string(c.allowed)));
    }
}

TEST(Scene, MessageReadsWell) {
    EXPECT_EQ(errorOf(R"({"container": {"min": [0, 0, 0], "max": [1, 1, 1]},
                          "blocks": [{"min": [0, 0, 0], "max": [1, 0.5, 1]}],
                          "fluid": {"restDensity": -5}})",
                      "scenes/x.json"),
              "scene 'scenes/x.json': field 'fluid.restDensity' is -5, must be a number > 0 and "
              "<= 100000");
}

TEST(Scene, MalformedJsonReportsFileAndPosition) {
    std::string message = errorOf("{\n  \"container\": ,\n}", "scenes/broken.json");
    EXPECT_TRUE(contains(message, "scene 'scenes/broken.json': invalid JSON"));
    EXPECT_TRUE(contains(message, "line 2"));
    EXPECT_TRUE(contains(errorOf(R"({"fluid": {"restDensity": 1e400}})"), "1e400"));
}

TEST(Scene, LoadSceneReadsAFileAndNamesItByStem) {
    auto path = std::filesystem::temp_directory_path() / "weir_scene_test_load.json";
    std::ofstream(path) << R"({"container": {"min": [0, 0, 0], "max": [1, 1, 1]},
                               "blocks": [{"min": [0, 0, 0], "max": [1, 0.5, 1]}]})";
    Scene s = loadScene(path.string());
    std::filesystem::remove(path);
    EXPECT_EQ(s.name, "weir_scene_test_load");
    EXPECT_EQ(s.sourcePath, path.string());
}

TEST(Scene, UnreadableFilesReportPathAndReason) {
    try {
        loadScene("/nonexistent/weir/scene.json");
        FAIL() << "no SceneError";
    } catch (const SceneError& e) {
        EXPECT_TRUE(contains(e.what(), "'/nonexistent/weir/scene.json'"));
        EXPECT_TRUE(contains(e.what(), "No such file or directory"));
    }
    std::string directory = std::filesystem::temp_directory_path().string();
    try {
        loadScene(directory);
        FAIL() << "no SceneError";
    } catch (const SceneError& e) {
        EXPECT_TRUE(contains(e.what(), "'" + directory + "'"));
        EXPECT_TRUE(contains(e.what(), "Is a directory"));
    }
}

// A scene nested thousands deep (an 18 KB gravity of 9,000 arrays crashed the reader's messages,
// nested objects its JSON writer): refused before anything recurses, naming file, line, limit.
TEST(Scene, DeepNestingIsRefusedWithItsPlace) {
    const std::string arrays = std::string(9000, '[') + std::string(9000, ']');
    std::string message = errorOf(R"({"container": {"min": [0, 0, 0], "max": [1, 1, 1]},
  "gravity": )" + arrays + "}",
                                  "deep.json");
    EXPECT_TRUE(contains(message, "scene 'deep.json': invalid JSON at line 2, column"));
    EXPECT_TRUE(contains(message, "nested more than 64 deep"));

    std::string objects;
    for (int i = 0; i < 9000; ++i) {
        objects += "{\"a\": ";
    }
    objects += "1" + std::string(9000, '}');
    message = errorOf("{\"description\": " + objects + "}", "objects.json");
    EXPECT_TRUE(contains(message, "objects.json"));
    EXPECT_TRUE(contains(message, "64"));

    // Brackets inside strings and comments do not count; 64 levels are allowed.
    const std::string deepest = std::string(62, '[') + "1" + std::string(62, ']');
    message = errorOf(R"({"name": "[[[[{{{{", /* [[[[ */
        "container": {"min": [0, 0, 0], "max": [1, 1, 1]},
        "blocks": [{"min": [0, 0, 0], "max": [1, 0.5, 1]}], // {{{{
        "gravity": )" +
                      deepest + "}");
    EXPECT_TRUE(contains(message, "'gravity' is [[[[[[[[")) << message;  // a value, not nesting
    EXPECT_TRUE(contains(message, "an array of 3 finite numbers")) << message;
}

// Every JSON error names the line and column, number overflow (1e309) included.
TEST(Scene, JsonErrorsNameLineAndColumn) {
    std::string message = errorOf("{\n  \"fluid\": {\n    \"restDensity\": 1e309\n  }\n}");
    EXPECT_TRUE(contains(message, "scene 'bad.json': invalid JSON at line 3, column")) << message;
    EXPECT_TRUE(contains(message, "1e309"));
    EXPECT_TRUE(contains(message, "finite"));
    message = errorOf("{\"a\": 1,\n\n   x}");
    EXPECT_TRUE(contains(message, "invalid JSON at line 3, column 4")) << message;
    EXPECT_FALSE(contains(message, "json.exception"));
}

// Numbers that overflowed downstream (a density of 1e300 gave NaN at step 0) are refused with the
// file, the field, the value and the allowed range.
TEST(Scene, HugeNumbersAreRefusedWithTheirRange) {
    struct Huge {
        const char* pointer;
        const char* value;
        const char* field;
        const char* allowed;
    };
    const Huge cases[] = {
        {"/fluid/restDensity", "1e300", "'fluid.restDensity'", "a number > 0 and <= 100000"},
        {"/fluid/stiffness", "1e300", "'fluid.stiffness'", "<= 1e+12"},
        {"/fluid/viscosity", "1e300", "'fluid.viscosity'", "< 1000000"},
        {"/gravity", "[0, -1e300, 0]", "'gravity'", "each a number in [-10000, 10000]"},
        {"/blocks/0/velocity", "[1e300, 0, 0]", "'blocks[0].velocity'",
         "each a number in [-100000, 100000]"},
        {"/container/max", "[1e300, 1, 1]", "'container.max'",
         "each a number in [-1000000, 1000000]"},
        {"/spheres/0/radius", "1e300", "'spheres[0].radius'", "<= 1000000"},
        {"/time/frameRate", "1e300", "'time.frameRate'", "<= 100000"},
        {"/time/duration", "1e300", "'time.duration'", "<= 1000000"},
        {"/limits/maxSpeed", "1e300", "'limits.maxSpeed'", "<= 100000000"},
        {"/limits/maxCompression", "1e300", "'limits.maxCompression'", "<= 1000"},
    };
    for (const Huge& c : cases) {
        Json scene = Json::parse(kValidScene);
        scene[Json::json_pointer(c.pointer)] = Json::parse(c.value);
        const std::string message = errorOf(scene.dump(), "huge.json");
        SCOPED_TRACE(c.pointer);
        EXPECT_TRUE(contains(message, "scene 'huge.json'"));
        EXPECT_TRUE(contains(message, c.field));
        EXPECT_TRUE(contains(message, "1e+300"));
        EXPECT_TRUE(contains(message, c.allowed));
    }
}

// Every seed is tested against every shape: arrays of shapes are bounded.
TEST(Scene, TooManyShapesAreRefused) {
    Json scene = Json::parse(kValidScene);
    Json boxes = Json::array();
    for (int i = 0; i < 1025; ++i) {
        boxes.push_back({{"min", {1.0, 0, 0}}, {"max", {1.2, 0.2, 0.6}}});
    }
    scene["obstacles"]["boxes"] = boxes;
    const std::string message = errorOf(scene.dump(), "many.json");
    EXPECT_TRUE(contains(message, "'obstacles.boxes' is an array of 1025 entries"));
    EXPECT_TRUE(contains(message, "at most 1024"));
}

}  // namespace
}  // namespace weir
