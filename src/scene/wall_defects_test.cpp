// The simple walls' defects and the seeding next to boundaries (issue 14): a box standing on the
// floor holds the particles on the floor, a tank at rest settles, and fluid starts at rest
// density next to every wall and obstacle.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <tuple>
#include <vector>

#include "physics/collision.h"
#include "physics/kernels.h"
#include "scene/scene.h"
#include "scene/seeding.h"
#include "scene/setup.h"
#include "solver/simulation.h"

namespace weir {
namespace {

SphParams tankParams() {
    SphParams p;
    p.boxMin = Vec3(0, 0, 0);
    p.boxMax = Vec3(0.8f, 0.4f, 0.2f);
    return p;
}

// A box standing on the floor and spanning the tank's depth: its bottom, front and back faces
// lie on container walls.
const ObstacleBox kStep{Vec3(0.4f, 0, 0), Vec3(0.5f, 0.1f, 0.2f)};

bool insideClosed(const Vec3& x, const ObstacleBox& b, Real margin) {
    return x.x > b.min.x + margin && x.x < b.max.x - margin && x.y >= b.min.y &&
           x.y < b.max.y - margin && x.z >= b.min.z && x.z <= b.max.z;
}

TEST(WallDefects, CollisionSendsParticlesOutThroughAnOpenFace) {
    const SphParams params = tankParams();
    const ObstacleView obstacles{&kStep, 1, nullptr, 0};
    // On the floor, just past the box's upstream face, running into it: back out upstream (it
    // was sent on along the floor through the box).
    Vec3 x(0.401f, 0, 0.1f), v(1, 0, 0);
    collide(x, v, params, obstacles);
    EXPECT_FLOAT_EQ(x.x, 0.4f);
    EXPECT_EQ(x.y, 0);
    EXPECT_LE(v.x, 0);
    // A hair above the floor: the bottom face is nearest, but it is on the floor (it was sent out
    // through it, onto the floor under the box).
    x = Vec3(0.403f, 0.0001f, 0.1f);
    v = Vec3(1, -0.1f, 0);
    collide(x, v, params, obstacles);
    EXPECT_FLOAT_EQ(x.x, 0.4f);
    EXPECT_FLOAT_EQ(x.y, 0.0001f);
    // On the back wall (z = 0, a blocked face too): out through the top, the nearest open face.
    x = Vec3(0.45f, 0.095f, 0);
    v = Vec3(0, -1, 0);
    collide(x, v, params, obstacles);
    EXPECT_FLOAT_EQ(x.y, 0.1f);
    EXPECT_EQ(v.y, 0);
    // A box in mid-tank keeps the nearest face, bottom included.
    const ObstacleBox floating{Vec3(0.4f, 0.1f, 0.05f), Vec3(0.5f, 0.2f, 0.15f)};
    const ObstacleView mid{&floating, 1, nullptr, 0};
    x = Vec3(0.45f, 0.101f, 0.1f);
    v = Vec3(0, 1, 0);
    collide(x, v, params, mid);
    EXPECT_FLOAT_EQ(x.y, 0.1f);
    // A periodic axis has no wall: a face on its bound stays open.
    SphParams periodic = params;
    periodic.periodicAxes = 1 << 2;
    x = Vec3(0.45f, 0.05f, 0.0005f);
    v = Vec3(0, 0, -1);
    collide(x, v, periodic, obstacles);
    EXPECT_FLOAT_EQ(x.z, 0);
    EXPECT_FLOAT_EQ(x.y, 0.05f);
}

Scene sceneText(const std::string& fluidModel, const std::string& walls, const std::string& body) {
    return parseScene(R"({"fluid": {"restDensity": 1000, "model": ")" + fluidModel +
                          R"("}, "walls": {"model": ")" + walls +
                          R"("}, "gravity": [0, -9.81, 0], )" + body + "}",
                      "<wall defects " + fluidModel + " " + walls + ">");
}

using Models = std::tuple<std::string, std::string>;  // fluid model, wall model
std::string modelsName(const ::testing::TestParamInfo<Models>& info) {
    std::string name = std::get<0>(info.param) + "_" + std::get<1>(info.param);
    std::replace(name.begin(), name.end(), '-', '_');
    return name;
}

class BoxOnTheFloor : public ::testing::TestWithParam<Models> {};

TEST_P(BoxOnTheFloor, HoldsTheFluidBack) {
    // A dam break runs along the floor into a box standing on it, spanning the tank's depth: no
    // particle may be inside the box (on the floor under it included) at any frame.
    const auto& [fluid, walls] = GetParam();
    const Scene scene = sceneText(fluid, walls, R"(
        "container": {"min": [0, 0, 0], "max": [0.8, 0.4, 0.2]},
        "blocks": [{"min": [0, 0, 0], "max": [0.2, 0.3, 0.2]}],
        "obstacles": {"boxes": [{"min": [0.4, 0, 0], "max": [0.5, 0.1, 0.2]}]},
        "particles": {"count": 1500},
        "time": {"duration": 0.6, "frameRate": 50})");
    SetupReport report;
    auto sim = makeSimulation(Backend::Cpu, NeighbourMode::Auto, buildSetup(scene, {}, &report));
    HostParticles p;
    std::size_t worst = 0, reached = 0;
    for (std::int64_t frame = 1; frame <= report.frames; ++frame) {
        sim->advanceTo(double(frame) * report.frameInterval);
        ASSERT_EQ(sim->fault().code, 0) << describeFault(sim->fault(), sim->params());
        sim->download(p);
        std::size_t inside = 0;
        for (std::size_t i = 0; i < p.size(); ++i) {
            const Vec3 x(p.x[i], p.y[i], p.z[i]);
            inside += insideClosed(x, kStep, Real(1e-6)) ? 1 : 0;
            reached += x.x > 0.35f && x.y < 0.05f ? 1 : 0;
        }
        worst = std::max(worst, inside);
    }
    EXPECT_GT(reached, 0u) << "the front never reached the box";
    EXPECT_EQ(worst, 0u) << "particles inside the box standing on the floor";
}

// delta-SPH with simple walls failed this while particle shifting was on by default (it moved
// particles after the collision response, up to 1.8 mm into the box: 23 particles at 0.6 s).
INSTANTIATE_TEST_SUITE_P(Models, BoxOnTheFloor,
                         ::testing::Values(Models{"paper", "simple"}, Models{"paper", "particles"},
                                           Models{"delta-sph", "particles"},
                                           Models{"delta-sph", "simple"}),
                         modelsName);

class TankAtRest : public ::testing::TestWithParam<Models> {};

TEST_P(TankAtRest, Settles) {
    // A tank filled to H = 0.15 m and left alone. The lattice start is not the fluid's rest
    // state (the surface layer reads light and sinks, the column compresses by g H / c^2): the
    // pressure that takes up the weight arrives as a wave, with a speed of about
    // c (g H / c^2) = g H / c, U / 20 for the c = 10 U that weir derives (U = sqrt(2 g H), the
    // expected speed). Settled, nothing but that wave's remains may move: the mean speed over the
    // last half second under U / 100 (a fifth of the wave; measured: 0.004 m/s with boundary
    // particles, U / 450), and not growing from the half second after the start.
    const auto& [fluid, walls] = GetParam();
    // delta-SPH on the simple walls at h = 2 d, where they were measured to settle: at its
    // default 3 d the tank churned (mean speed 0.036 then 0.045 m/s, growing; CI at 63f2ae1),
    // one more reason set-up warns against that combination.
    const std::string ratio =
        fluid == "delta-sph" && walls == "simple" ? R"(, "smoothingRatio": 2)" : "";
    const Scene scene = sceneText(fluid, walls, R"(
        "container": {"min": [0, 0, 0], "max": [0.2, 0.3, 0.2]},
        "blocks": [{"min": [0, 0, 0], "max": [0.2, 0.15, 0.2]}],
        "particles": {"count": 1500)" + ratio + R"(},
        "time": {"duration": 2.0, "frameRate": 50})");
    SetupReport report;
    auto sim = makeSimulation(Backend::Cpu, NeighbourMode::Auto, buildSetup(scene, {}, &report));
    HostParticles p;
    double early = 0, late = 0, comEarly = 0, comLate = 0;
    int earlyFrames = 0, lateFrames = 0;
    for (std::int64_t frame = 1; frame <= report.frames; ++frame) {
        const double t = double(frame) * report.frameInterval;
        sim->advanceTo(t);
        ASSERT_EQ(sim->fault().code, 0) << describeFault(sim->fault(), sim->params());
        sim->download(p);
        double speed = 0, vy = 0;
        for (std::size_t i = 0; i < p.size(); ++i) {
            speed += std::sqrt(double(p.vx[i]) * p.vx[i] + double(p.vy[i]) * p.vy[i] +
                               double(p.vz[i]) * p.vz[i]);
            vy += p.vy[i];
        }
        speed /= double(p.size());
        vy /= double(p.size());
        if (t > 0.5 - 1e-9 && t < 1.0 + 1e-9) {
            early += speed;
            comEarly = std::max(comEarly, std::fabs(vy));
            ++earlyFrames;
        } else if (t > 1.5 - 1e-9) {
            late += speed;
            comLate = std::max(comLate, std::fabs(vy));
            ++lateFrames;
        }
    }
    early /= earlyFrames;
    late /= lateFrames;
    const double u = report.expectedSpeed;
    std::cout << fluid << " " << walls << ": mean speed " << early << " m/s (0.5-1 s), " << late
              << " m/s (1.5-2 s), U = " << u << " m/s; largest mean vertical velocity " << comEarly
              << ", " << comLate << " m/s\n";
    EXPECT_LT(late, u / 100);
    EXPECT_LE(late, early);
    EXPECT_LT(comLate, u / 100) << "the column bounces";
}

// The simple walls failed this until their push became the gradient of the density share they
// add (physics/wall_weight.h). With the spiky gradient's lattice sum (1.47x the share's gradient at
// the plane, 0.90x at d/2, 0.58x at d) the walls did net work and the column rang at c / 4H:
// paper model 0.042 m/s mean speed at 0.5-1 s and 0.041 m/s at 1.5-2 s, the column bouncing at
// 0.057 m/s; delta-SPH 0.043 and 0.031 m/s. The share's gradient alone settled the paper model
// (0.0044 m/s at 1.5-2 s) but let 72 of 3072 particles onto the planes in RestState, and
// delta-SPH still churned (0.033 m/s). With the barrier within d/2 of the planes as well
// (measured on the CPU): paper 0.010 and 0.0039 m/s, column 0.00016 m/s; delta-SPH 0.0079 and
// 0.0042 m/s, column 0.00021 m/s (U = 1.72 m/s, bound U / 100 = 0.017 m/s).
INSTANTIATE_TEST_SUITE_P(SimpleWalls, TankAtRest,
                         ::testing::Values(Models{"paper", "simple"},
                                           Models{"delta-sph", "simple"}),
                         modelsName);

class SeedsClearOfBoundaries : public ::testing::TestWithParam<Models> {};

TEST_P(SeedsClearOfBoundaries, StartAtRest) {
    // A tank with a box standing in the fluid and a sphere half in it, their faces off the fluid
    // lattice (0.0007 m past a lattice plane at d = 0.01): no particle starts closer than d/2 to
    // a wall or obstacle (the container's walls: d/2 by the block's lattice), none starts
    // overdense (the paper model's density sums, for particles a full neighbourhood under the
    // surface), and nothing leaves fast: in the first 0.02 s a fluid at rest gains g t from
    // gravity and the pressure wave of its lattice start, U / 20 (see TankAtRest); twice both
    // is the bound.
    const auto& [fluid, walls] = GetParam();
    const Scene scene = sceneText(fluid, walls, R"(
        "container": {"min": [0, 0, 0], "max": [0.3, 0.3, 0.2]},
        "blocks": [{"min": [0, 0, 0], "max": [0.3, 0.15, 0.2]}],
        "obstacles": {"boxes": [{"min": [0.0507, 0, 0.0507], "max": [0.1293, 0.0793, 0.1493]}],
                      "spheres": [{"center": [0.22, 0.15, 0.1], "radius": 0.0407}]},
        "particles": {"spacing": 0.01},
        "time": {"duration": 0.02, "frameRate": 50})");
    const double d = 0.01;
    SetupReport report;
    SimulationSetup setup = buildSetup(scene, {}, &report);
    const HostParticles& seeded = setup.particles;
    ASSERT_GT(seeded.size(), 0u);
    const Box& box = scene.obstacleBoxes[0];
    const SphereShape& sphere = scene.obstacleSpheres[0];
    double nearest = 1e30;
    for (std::size_t i = 0; i < seeded.size(); ++i) {
        const Vec3d x(seeded.x[i], seeded.y[i], seeded.z[i]);
        nearest = std::min(nearest, std::sqrt(distanceSquaredToBox(x, box)));
        nearest = std::min(nearest, length(x - sphere.center) - sphere.radius);
        for (int a = 0; a < 3; ++a) {
            nearest =
                std::min({nearest, x[a] - scene.container.min[a], scene.container.max[a] - x[a]});
        }
    }
    EXPECT_GE(nearest, 0.5 * d * (1 - 1e-4));

    auto sim = makeSimulation(Backend::Cpu, NeighbourMode::Auto, std::move(setup));
    if (fluid == "paper") {
        sim->computeDensity();
        HostParticles p;
        sim->download(p);
        double densest = 0;
        for (std::size_t i = 0; i < p.size(); ++i) {
            if (p.y[i] < 0.15 - report.smoothingRadius) {
                densest = std::max(densest, double(p.rho[i]));
            }
        }
        std::cout << fluid << " " << walls << ": densest " << densest << " kg/m^3 at t = 0\n";
        EXPECT_LT(densest, 1.02 * scene.restDensity);
    }
    sim->advanceTo(0.02);
    ASSERT_EQ(sim->fault().code, 0) << describeFault(sim->fault(), sim->params());
    HostParticles p;
    sim->download(p);
    double fastest = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        fastest =
            std::max(fastest, std::sqrt(double(p.vx[i]) * p.vx[i] + double(p.vy[i]) * p.vy[i] +
                                        double(p.vz[i]) * p.vz[i]));
    }
    const double bound = 2 * (9.81 * 0.02 + report.expectedSpeed / 20);
    std::cout << fluid << " " << walls << ": fastest " << fastest << " m/s at t = 0.02 s (bound "
              << bound << ")\n";
    EXPECT_LT(fastest, bound);
}

// delta-SPH with simple walls: fastest 0.67 m/s against the bound 0.56 m/s with the spiky push,
// 0.555 m/s with the share's gradient and the barrier (physics/wall_weight.h).
INSTANTIATE_TEST_SUITE_P(Models, SeedsClearOfBoundaries,
                         ::testing::Values(Models{"paper", "simple"}, Models{"paper", "particles"},
                                           Models{"delta-sph", "particles"},
                                           Models{"delta-sph", "simple"}),
                         modelsName);

}  // namespace
}  // namespace weir
