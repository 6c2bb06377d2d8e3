// Rigid bodies in the fluid on the CPU (issue 18): a light box floats at the draft Archimedes
// gives it, a dense one sinks to the floor, the momentum the fluid gains is the momentum the body
// loses, a driven piston follows its law and pushes the water, and bad bodies are refused with
// the field named.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

#include "scene/scene.h"
#include "scene/setup.h"
#include "solver/solver_test_support.h"

namespace weir {
namespace {

Scene bodyScene(const std::string& fields) {
    return parseScene(R"({"name": "bodies_test", "fluid": {"preset": "water"}, )" + fields + "}",
                      "<test bodies>");
}

// A tank 0.3 m long, 0.1 m across, with water 0.1 m deep, and a box 0.08 m long and high and
// 0.06 m across of `density` whose bottom starts at `bottom`, in the middle (2 cm of water
// between it and the side walls). At h = 2 d: the draft of the floating box (4 cm, 4 d) is then
// 2 h; at delta-SPH's default 3 d it is 1.3 h, and the box floated 5% high (draft 0.947 of
// Archimedes', measured on this machine at 5f2e673, in 485 s where 2 d takes 40 s).
Scene tankWithBox(double density, double bottom, double duration, const std::string& limits) {
    const std::string lo = "[0.11, " + std::to_string(bottom) + ", 0.02]";
    const std::string hi = "[0.19, " + std::to_string(bottom + 0.08) + ", 0.08]";
    return bodyScene(R"(
        "container": {"min": [0, 0, 0], "max": [0.3, 0.2, 0.1]},
        "blocks": [{"min": [0, 0, 0], "max": [0.3, 0.1, 0.1]}],
        "bodies": [{"box": {"min": )" +
                     lo + R"(, "max": )" + hi + R"(}, "density": )" + std::to_string(density) +
                     R"(}],
        "particles": {"spacing": 0.01, "smoothingRatio": 2}, )" +
                     limits + R"(
        "time": {"duration": )" +
                     std::to_string(duration) + R"(, "frameRate": 20})");
}

// The water level away from the box: the mean height of the top particle (plus d/2) of the
// columns of the lattice more than 2 cm from it along x.
double waterLevel(const HostParticles& p, const RigidBody& box, double d) {
    double sum = 0;
    int columns = 0;
    for (int cx = 0; cx < 30; ++cx) {
        const double x = (cx + 0.5) * d;
        if (std::abs(x - box.x.x) < box.halfSize.x + 0.02) {
            continue;
        }
        for (int cz = 0; cz < 10; ++cz) {
            const double z = (cz + 0.5) * d;
            double top = -1;
            for (std::size_t i = 0; i < p.size(); ++i) {
                if (std::abs(p.x[i] - x) < 0.5 * d && std::abs(p.z[i] - z) < 0.5 * d) {
                    top = std::max(top, double(p.y[i]));
                }
            }
            if (top > 0) {
                sum += top + 0.5 * d;
                ++columns;
            }
        }
    }
    return sum / columns;
}

// A floating box's draft (the water level away from it less its lowest point), averaged over
// frames 21-32 of 0.05 s (the last 0.6 s of 1.6 s: the heave period is about 0.4 s), each frame
// checked for a fault and for the box standing upright.
double meanDraft(Simulation& sim, double d) {
    HostParticles p;
    double draftSum = 0;
    int samples = 0;
    for (int frame = 1; frame <= 32; ++frame) {
        sim.advanceTo(0.05 * frame);
        EXPECT_EQ(sim.fault().code, 0) << describeFault(sim.fault(), sim.params());
        if (sim.fault().code != 0) {
            return 0;
        }
        if (frame > 20) {
            const RigidBody box = sim.rigidBodies()[0];
            sim.download(p);
            const double lowest = box.x.y + box.boxCentre.y - box.halfSize.y;
            draftSum += waterLevel(p, box, d) - lowest;
            ++samples;
            EXPECT_GT(std::abs(box.q.w), 0.99) << "frame " << frame;  // it stays upright
        }
    }
    return draftSum / samples;
}

TEST(RigidBodies, LightBoxFloatsAtArchimedesDraft) {
    // Density 500: Archimedes puts 500 / 998 of the box's 0.08 m under water at rest. It starts
    // 8 mm higher and bobs; the draft is averaged over the last 0.6 s (the heave period is
    // 0.4 s). The speed of sound follows a speed bound of 1 m/s (the box moves at 0.2 m/s).
    const double d = 0.01;
    const Scene scene =
        tankWithBox(500, 0.1 - 0.0401 + 0.008, 1.6, R"("limits": {"maxSpeed": 1},)");
    const double expected = 0.08 * 500 / scene.restDensity;
    auto sim = makeSimulation(Backend::Cpu, NeighbourMode::Auto, buildSetup(scene, {}, nullptr));
    ASSERT_EQ(sim->rigidBodies().size(), 1u);
    const double draft = meanDraft(*sim, d);
    std::cout << "floating box: draft " << draft << " m against Archimedes' " << expected << "\n";
    EXPECT_NEAR(draft / expected, 1.0, 0.03);
}

// The box [lo, hi] as an OBJ file: 8 vertices, 6 outward quads (fanned by the reader).
void writeBoxObj(const std::filesystem::path& path, const Vec3d& lo, const Vec3d& hi) {
    std::ofstream f(path);
    for (int c = 0; c < 8; ++c) {
        f << "v " << ((c & 1) ? hi.x : lo.x) << " " << ((c & 2) ? hi.y : lo.y) << " "
          << ((c & 4) ? hi.z : lo.z) << "\n";
    }
    f << "f 1 5 7 3\nf 2 4 8 6\nf 1 2 6 5\nf 3 7 8 4\nf 1 3 4 2\nf 5 6 8 7\n";
}

// A box read from an OBJ file (a mesh body: its volume, centroid and inertia from the surface,
// its boundary particles from the triangles) floats at Archimedes' draft. Squatter than the box
// above: 0.12 m long, 0.05 m high, 0.07 m across, density 600, so its metacentre is above its
// centre of mass and it is stable upright (GM = T/2 + B^2/(12 T) - H/2 = 3.6 mm); the box above
// (GM < 0) floats upright only by the symmetry of its sampling, which a mesh's triangles break.
TEST(RigidBodies, MeshBoxFloatsAtArchimedesDraft) {
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / "weir_mesh_body_test";
    std::filesystem::create_directories(dir);
    const double d = 0.01, height = 0.05, draftExpected = height * 600 / 998.0;
    const double bottom = 0.1 - draftExpected + 0.005;
    writeBoxObj(dir / "box.obj", Vec3d(0.09, bottom, 0.015), Vec3d(0.21, bottom + height, 0.085));
    const Scene scene = parseScene(R"({"name": "mesh_body_test",
        "container": {"min": [0, 0, 0], "max": [0.3, 0.2, 0.1]},
        "blocks": [{"min": [0, 0, 0], "max": [0.3, 0.1, 0.1]}],
        "bodies": [{"mesh": {"file": "box.obj"}, "density": 600}], "fluid": {"preset": "water"},
        "particles": {"spacing": 0.01, "smoothingRatio": 2},
        "time": {"duration": 1.6, "frameRate": 20}})",
                                   (dir / "scene.json").string());
    ASSERT_TRUE(scene.bodies[0].isMesh);
    EXPECT_NEAR(scene.bodies[0].mass, 600 * 0.12 * 0.05 * 0.07, 1e-5 * 0.252);  // OBJ's 6 digits
    const double expected = height * 600 / scene.restDensity;
    auto sim = makeSimulation(Backend::Cpu, NeighbourMode::Auto, buildSetup(scene, {}, nullptr));
    ASSERT_EQ(sim->rigidBodies().size(), 1u);
    EXPECT_EQ(sim->rigidBodies()[0].shape, BodyShape::Mesh);
    const double draft = meanDraft(*sim, d);
    std::cout << "floating mesh box: draft " << draft << " m against Archimedes' " << expected
              << "\n";
    EXPECT_NEAR(draft / expected, 1.0, 0.03);
    std::filesystem::remove_all(dir);
}

TEST(RigidBodies, DenseBoxSinksToTheFloor) {
    const Scene scene = tankWithBox(2000, 0.06, 0.6, "");
    auto sim = makeSimulation(Backend::Cpu, NeighbourMode::Auto, buildSetup(scene, {}, nullptr));
    sim->advanceTo(0.6);
    ASSERT_EQ(sim->fault().code, 0) << describeFault(sim->fault(), sim->params());
    const RigidBody box = sim->rigidBodies()[0];
    // On the floor (its bottom within a spacing of it) and at rest.
    EXPECT_LT(box.x.y - box.halfSize.y, 0.01);
    EXPECT_LT(length(box.v), 0.05);
}

// Without gravity, a sphere shot through still water: every force between them is a pair of
// opposite forces, so the fluid's momentum plus the sphere's stays what it was. Run for less time
// than sound takes from the sphere to the walls and back (c = 4.8 m/s: ten times the sphere's 0.3
// m/s plus its spin's 0.18), so the walls play no part.
TEST(RigidBodies, MomentumLostByTheBodyIsGainedByTheFluid) {
    const Scene scene = bodyScene(R"(
        "container": {"min": [0, 0, 0], "max": [0.6, 0.6, 0.6]},
        "blocks": [{"min": [0, 0, 0], "max": [0.6, 0.6, 0.6]}],
        "bodies": [{"sphere": {"center": [0.3, 0.3, 0.3], "radius": 0.06}, "density": 800,
                    "velocity": [0.3, 0.05, 0], "angularVelocity": [0, 0, 3]}],
        "gravity": [0, 0, 0],
        "particles": {"spacing": 0.02},
        "time": {"duration": 0.015, "frameRate": 200})");
    const SimulationSetup setup = buildSetup(scene, {}, nullptr);
    const double mass = double(setup.params.mass);
    auto sim = makeSimulation(Backend::Cpu, NeighbourMode::Auto, setup);
    const double bodyMass = scene.bodies[0].mass;
    auto total = [&] {
        HostParticles p;
        sim->download(p);
        Vec3d momentum;
        for (std::size_t i = 0; i < p.size(); ++i) {
            momentum += Vec3d(p.vx[i], p.vy[i], p.vz[i]) * mass;
        }
        const RigidBody body = sim->rigidBodies()[0];
        return std::pair{momentum, Vec3d(body.v) * bodyMass};
    };
    const auto [fluid0, body0] = total();
    sim->advanceTo(0.015);
    ASSERT_EQ(sim->fault().code, 0) << describeFault(sim->fault(), sim->params());
    const auto [fluid1, body1] = total();
    // The body has given the fluid some of its momentum (as the added mass builds up over the
    // acoustic time, R / c = 12 ms; sound reaches the walls at 50 ms) ...
    const double exchanged = length(body0 - body1);
    std::cout << "momentum: the sphere passed on " << exchanged << " of its " << length(body0)
              << " kg m/s; fluid plus sphere changed by "
              << length((fluid1 + body1) - (fluid0 + body0)) << "\n";
    EXPECT_GT(exchanged, 0.05 * length(body0));
    // ... and the sum has kept it, to round-off of the float sums.
    EXPECT_LT(length((fluid1 + body1) - (fluid0 + body0)), 1e-3 * exchanged)
        << "fluid gained " << length(fluid1 - fluid0) << ", body lost " << exchanged;
}

// A piston at the end of a tank moves by its law and pushes the water ahead of it.
TEST(RigidBodies, DrivenPistonFollowsItsLawAndPushesTheWater) {
    const Scene scene = bodyScene(R"(
        "container": {"min": [0, 0, 0], "max": [0.5, 0.2, 0.1]},
        "blocks": [{"min": [0.06, 0, 0], "max": [0.5, 0.1, 0.1]}],
        "bodies": [{"box": {"min": [0.02, 0.0, 0.0], "max": [0.05, 0.15, 0.1]},
                    "motion": {"oscillate": {"amplitude": [0.02, 0, 0], "period": 0.8}}}],
        "particles": {"spacing": 0.01},
        "time": {"duration": 0.2, "frameRate": 20})");
    auto sim = makeSimulation(Backend::Cpu, NeighbourMode::Auto, buildSetup(scene, {}, nullptr));
    sim->advanceTo(0.2);
    ASSERT_EQ(sim->fault().code, 0) << describeFault(sim->fault(), sim->params());
    // The pose is that of the step's start (the last step's), within a step of the law.
    const RigidBody piston = sim->rigidBodies()[0];
    const double expected = 0.035 + 0.02 * std::sin(2 * M_PI * 0.2 / 0.8);
    EXPECT_NEAR(piston.x.x, expected, 0.002);
    HostParticles p;
    sim->download(p);
    double momentum = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        momentum += p.vx[i];
    }
    EXPECT_GT(momentum / double(p.size()), 0.005);  // the water moves away from it
}

TEST(RigidBodies, BadBodiesAreRefusedNamingTheField) {
    const std::string tank = R"(
        "container": {"min": [0, 0, 0], "max": [1, 1, 1]},
        "blocks": [{"min": [0, 0, 0], "max": [1, 0.5, 1]}], )";
    auto fails = [&](const std::string& bodies, const std::string& expected) {
        try {
            bodyScene(tank + R"("bodies": )" + bodies);
            ADD_FAILURE() << "accepted " << bodies;
        } catch (const SceneError& e) {
            EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
        }
    };
    fails(R"([{"box": {"min": [0.9, 0, 0], "max": [1.1, 0.1, 0.1]}, "density": 500}])",
          "bodies[0]");
    fails(R"([{"box": {"min": [0.9, 0, 0], "max": [1.1, 0.1, 0.1]}, "density": 500}])",
          "sticks out");
    fails(R"([{"sphere": {"center": [0.5, 0.5, 0.5], "radius": 0.1}, "mass": 0}])",
          "bodies[0].mass");
    fails(R"([{"sphere": {"center": [0.5, 0.5, 0.5], "radius": 0.1}}])", "bodies[0].density");
    fails(R"([{"sphere": {"center": [0.5, 0.5, 0.5], "radius": 0.1}, "density": 1, "mass": 1}])",
          "bodies[0].density");
    fails(R"([{"sphere": {"center": [0.5, 0.5, 0.5], "radius": 0.1}, "density": 500},
              {"box": {"min": [0.5, 0.5, 0.5], "max": [0.7, 0.7, 0.7]}, "density": 500}])",
          "overlap those of bodies[0]");
    fails(R"([{"density": 500}])", "a body with no shape");
    // A piston whose stroke takes it through a wall (it would crush the fluid caught behind it:
    // a flume whose piston reached 5 mm past its wall blew up at 2.5 mm spacing on an H200), and
    // a paddle that turns through the floor.
    fails(R"([{"box": {"min": [0.02, 0, 0], "max": [0.06, 0.4, 1]},
               "motion": {"oscillate": {"amplitude": [0.03, 0, 0], "period": 1}}}])",
          "field 'bodies[0].motion'");
    fails(R"([{"box": {"min": [0.02, 0, 0], "max": [0.06, 0.4, 1]},
               "motion": {"oscillate": {"amplitude": [0.03, 0, 0], "period": 1}}}])",
          "reaches out by 0.01 on -x");
    fails(R"([{"box": {"min": [0.4, 0.02, 0.4], "max": [0.6, 0.1, 0.6]},
               "motion": {"rotate": {"rate": [0, 0, 2]}}}])",
          "bodies[0].motion");
    fails(R"([{"box": {"min": [0.1, 0.1, 0.1], "max": [0.2, 0.2, 0.2]},
               "motion": {"oscillate": {"amplitude": [0.1, 0, 0], "period": 1}}, "mass": 3}])",
          "bodies[0].mass");
    // Mesh bodies: closed, facing outwards.
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / "weir_bad_mesh_body_test";
    std::filesystem::create_directories(dir);
    writeBoxObj(dir / "box.obj", Vec3d(0.4, 0.6, 0.4), Vec3d(0.6, 0.8, 0.6));
    {
        std::ofstream open(dir / "open.obj");      // the box without its top
        std::ofstream inward(dir / "inward.obj");  // the box turned inside out
        for (int c = 0; c < 8; ++c) {
            const std::string v = std::string("v ") + ((c & 1) ? "0.6" : "0.4") + " " +
                                  ((c & 2) ? "0.8" : "0.6") + " " + ((c & 4) ? "0.6" : "0.4") +
                                  "\n";
            open << v;
            inward << v;
        }
        open << "f 1 5 7 3\nf 2 4 8 6\nf 1 2 6 5\nf 1 3 4 2\nf 5 6 8 7\n";
        inward << "f 3 7 5 1\nf 6 8 4 2\nf 5 6 2 1\nf 4 8 7 3\nf 2 4 3 1\nf 7 8 6 5\n";
    }
    auto mesh = [&](const std::string& name, const std::string& more) {
        return R"([{"mesh": {"file": ")" + (dir / name).string() + R"("})" + more + "}]";
    };
    fails(mesh("open.obj", R"(, "density": 500)"), "bodies[0].mesh.file");
    fails(mesh("open.obj", R"(, "density": 500)"), "a closed surface");
    fails(mesh("inward.obj", R"(, "density": 500)"), "face inwards");
    fails(mesh("missing.obj", R"(, "density": 500)"), "bodies[0].mesh.file");
    fails(mesh("box.obj", R"(, "box": {"min": [0, 0.6, 0], "max": [0.1, 0.7, 0.1]}, "mass": 1)"),
          "a body with two shapes");
    fails(mesh("box.obj", R"(, "density": 0)"), "bodies[0].density");
    std::filesystem::remove_all(dir);
    try {
        parseScene(R"({"fluid": {"model": "paper"}, )" + tank +
                       R"("bodies": [{"sphere": {"center": [0.5, 0.5, 0.5], "radius": 0.1},
                                      "density": 500}]})",
                   "<test bodies>");
        ADD_FAILURE() << "the paper model took bodies";
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("delta-sph"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace weir
