// Periodic boundaries (container.periodic, solver/periodic_ghosts.h): neighbours across the faces
// equal brute-force minimum-image neighbours, a periodic channel at rest stays at rest, particles
// that leave through a face come back through the other with momentum kept, and a periodic axis
// too short for the kernel is refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "core/check.h"
#include "core/exec_cpu.h"
#include "solver/neighbour_search.h"
#include "solver/periodic_ghosts.h"
#include "solver/solver_test_support.h"

namespace weir {
namespace {

using namespace weir::testing;

// Neighbour ids within h of each owned particle (by id), found through the search with the ghost
// copies of the periodic faces.
std::vector<std::vector<Index>> neighboursWithGhosts(NeighbourMode mode, const HostParticles& host,
                                                     const SphParams& params,
                                                     const GridSpec& grid) {
    CpuExec exec;
    ParticleStore<CpuExec> store;
    store.upload(exec, host, {});
    NeighbourSearch<CpuExec> search(mode, periodicGrid(grid, params), Index(host.size()),
                                    params.kernel.h);
    store.fitScratch(search.reorders());
    PeriodicGhosts<CpuExec> periodic(params);
    periodic.add(exec, store);
    EXPECT_GT(store.ghostCount(), 0);
    search.update(exec, store, [] {});
    std::vector<std::vector<Index>> found(host.size());
    const Real h2 = params.kernel.h2;
    const Real4* pos = store.pos();
    const Index* id = store.id();
    search.visit(pos, store.count(), [&](const auto& nb) {
        for (Index i = 0; i < store.count(); ++i) {
            if (isGhost(pos[i])) {
                continue;
            }
            nb.forEachCandidate(i, [&](Index j) {
                const Real r2 = lengthSquared(pos[i].xyz() - pos[j].xyz());
                if (j != i && r2 < h2) {
                    found[std::size_t(id[i])].push_back(id[j]);
                }
            });
        }
    });
    periodic.drop(exec, store);
    EXPECT_EQ(store.count(), Index(host.size()));
    for (auto& list : found) {
        std::sort(list.begin(), list.end());
    }
    return found;
}

TEST(Periodic, NeighboursAcrossFacesEqualMinimumImageNeighbours) {
    // Random particles in a box periodic along x and z (and, second, along all three), with
    // an axis exactly two radii long: every mode finds the neighbours that the minimum image
    // gives, no more (no particle meets its own image) and no fewer.
    for (const int axes : {0b101, 0b111}) {
        SphParams params;
        const double h = 0.05;
        params.kernel = KernelCoefficients::forRadius(Real(h));
        params.boxMin = Vec3(0, 0, 0);
        params.boxMax = Vec3(0.3, 0.25, 0.1);  // z: exactly 2 h
        params.periodicAxes = axes;
        const GridSpec grid = makeGridSpec(Vec3d(params.boxMin), Vec3d(params.boxMax), h);
        std::mt19937 random(7);
        std::uniform_real_distribution<double> unit(0.0, 1.0);
        HostParticles host;
        for (int k = 0; k < 1500; ++k) {
            Vec3d p;
            for (int a = 0; a < 3; ++a) {
                p[a] = params.boxMin[a] + unit(random) * (params.boxMax[a] - params.boxMin[a]);
            }
            host.push(p, Vec3d());
        }
        std::vector<std::vector<Index>> want(host.size());
        for (std::size_t i = 0; i < host.size(); ++i) {
            for (std::size_t j = 0; j < host.size(); ++j) {
                const Real d[3] = {host.x[i] - host.x[j], host.y[i] - host.y[j],
                                   host.z[i] - host.z[j]};
                Real r2 = 0;
                for (int a = 0; a < 3; ++a) {
                    Real da = d[a];
                    if (isPeriodic(params, a)) {
                        const Real length = params.boxMax[a] - params.boxMin[a];
                        da -= length * std::round(da / length);
                    }
                    r2 += da * da;
                }
                if (j != i && r2 < params.kernel.h2) {
                    want[i].push_back(Index(j));
                }
            }
        }
        std::size_t across = 0;
        for (std::size_t i = 0; i < host.size(); ++i) {
            for (Index j : want[i]) {
                across += std::abs(host.x[i] - host.x[std::size_t(j)]) > h ? 1 : 0;
            }
        }
        EXPECT_GT(across, 100u);  // the test does cross the faces
        for (NeighbourMode mode :
             {NeighbourMode::Dense, NeighbourMode::Grid, NeighbourMode::Brute}) {
            const auto got = neighboursWithGhosts(mode, host, params, grid);
            for (std::size_t i = 0; i < host.size(); ++i) {
                ASSERT_EQ(got[i], want[i])
                    << neighbourModeName(mode) << ", axes " << axes << ", particle " << i;
            }
        }
    }
}

// A channel of water at rest: periodic along x and z, walls of boundary particles at +-y,
// gravity -y, the fluid filling it.
// "dfsph" stands for delta-SPH under the DFSPH solver: the scene's "solver" field, if any.
std::string solverField(const std::string& model) {
    return model == "dfsph" ? R"("solver": "dfsph",)" : "";
}
std::string fluidModel(const std::string& model) { return model == "dfsph" ? "delta-sph" : model; }

Scene restingChannel(const std::string& model) {
    return parseScene("{" + solverField(model) + R"(
        "name": "periodic_channel_at_rest",
        "container": {"min": [0, 0, 0], "max": [0.16, 0.1, 0.08],
                      "periodic": [true, false, true]},
        "blocks": [{"min": [0, 0, 0], "max": [0.16, 0.1, 0.08]}],
        "fluid": {"preset": "water", "restDensity": 1000)" +
                          std::string(R"(, "model": ")") + fluidModel(model) + "\"" +
                          R"(},
        "particles": {"spacing": 0.01},
        "walls": {"model": "particles"}
    })",
                      "<test periodic channel at rest>");
}

double rmsSpeed(const HostParticles& p) {
    double sum = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        sum += double(p.vx[i]) * p.vx[i] + double(p.vy[i]) * p.vy[i] + double(p.vz[i]) * p.vz[i];
    }
    return std::sqrt(sum / double(p.size()));
}

void expectInside(const HostParticles& p, const Scene& scene) {
    for (std::size_t i = 0; i < p.size(); ++i) {
        const Vec3d x(p.x[i], p.y[i], p.z[i]);
        for (int a = 0; a < 3; ++a) {
            ASSERT_GE(x[a], scene.container.min[a]) << "particle " << i;
            ASSERT_LE(x[a], scene.container.max[a]) << "particle " << i;
        }
    }
}

class PeriodicModels : public ::testing::TestWithParam<std::string> {};

TEST_P(PeriodicModels, ChannelAtRestStaysAtRest) {
    const Scene scene = restingChannel(GetParam());
    auto sim = start(scene, Backend::Cpu, NeighbourMode::Auto);
    const Index count = sim->particleCount();
    ASSERT_EQ(count, 16 * 10 * 8);
    sim->advanceTo(1.0);
    ASSERT_EQ(sim->fault().code, 0) << describeFault(sim->fault(), sim->params());
    EXPECT_EQ(sim->particleCount(), count);
    HostParticles out;
    sim->download(out);
    ASSERT_EQ(out.size(), std::size_t(count));
    expectInside(out, scene);
    // Measured (RMS, max): delta-SPH 0.23, 0.41 mm/s (0.09, 0.22 with walls all round); the
    // paper's model 12, 38 mm/s (7, 55 with walls all round: its tank at rest is as restless);
    // DFSPH 24, 58 mm/s, the stir its tanks at rest keep with walls all round too (issue 15,
    // docs/dfsph.md), and no worse at the faces (below).
    const bool delta = GetParam() == "delta-sph", dfsph = GetParam() == "dfsph";
    EXPECT_LT(rmsSpeed(out), delta ? 0.001 : (dfsph ? 0.035 : 0.02));
    EXPECT_LT(maxSpeed(out), delta ? 0.003 : (dfsph ? 0.09 : 0.07));
    // No seam: the fluid near the periodic faces is as much at rest as the rest of it.
    double seam = 0, inside = 0;
    int seamCount = 0, insideCount = 0;
    for (std::size_t i = 0; i < out.size(); ++i) {
        const double speed2 = double(out.vx[i]) * out.vx[i] + double(out.vy[i]) * out.vy[i] +
                              double(out.vz[i]) * out.vz[i];
        const bool nearFace =
            out.x[i] < 0.02 || out.x[i] > 0.14 || out.z[i] < 0.02 || out.z[i] > 0.06;
        (nearFace ? seam : inside) += speed2;
        ++(nearFace ? seamCount : insideCount);
    }
    EXPECT_LT(std::sqrt(seam / seamCount), 1.3 * std::sqrt(inside / insideCount));
}

INSTANTIATE_TEST_SUITE_P(Models, PeriodicModels, ::testing::Values("paper", "delta-sph", "dfsph"),
                         [](const auto& info) {
                             return info.param == "paper"       ? std::string("Paper")
                                    : info.param == "delta-sph" ? std::string("DeltaSph")
                                                                : std::string("Dfsph");
                         });

// A box of fluid periodic along all three axes, without gravity, every particle moving.
Scene periodicBox(const std::string& velocityBelow, const std::string& velocityAbove,
                  const std::string& model) {
    return parseScene("{" + solverField(model) + R"(
        "name": "periodic_box",
        "container": {"min": [0, 0, 0], "max": [0.1, 0.1, 0.1], "periodic": [true, true, true]},
        "blocks": [{"min": [0, 0, 0], "max": [0.1, 0.05, 0.1], "velocity": )" +
                          velocityBelow + R"(},
                   {"min": [0, 0.05, 0], "max": [0.1, 0.1, 0.1], "velocity": )" +
                          velocityAbove + R"(}],
        "gravity": [0, 0, 0],
        "fluid": {"preset": "water", "restDensity": 1000)" +
                          std::string(R"(, "model": ")") + fluidModel(model) + "\"" +
                          R"(},
        "particles": {"spacing": 0.01}
    })",
                      "<test periodic box>");
}

TEST_P(PeriodicModels, ParticlesLeaveThroughOneFaceAndComeBackThroughTheOther) {
    // The whole fluid moves at 1 m/s along x and 0.5 m/s along z: after 0.15 s, 1.5 box lengths
    // along x, every particle has left through the upper x face and come back through the lower
    // one at least once, and sits where the motion puts it, inside the box (a uniform flow feels
    // no force).
    const Scene scene = periodicBox("[1, 0, 0.5]", "[1, 0, 0.5]", GetParam());
    auto sim = start(scene, Backend::Cpu, NeighbourMode::Auto);
    HostParticles before;
    sim->download(before);
    sim->advanceTo(0.15);
    ASSERT_EQ(sim->fault().code, 0) << describeFault(sim->fault(), sim->params());
    HostParticles after;
    sim->download(after);
    ASSERT_EQ(after.size(), before.size());
    expectInside(after, scene);
    const double t = sim->time(), length = 0.1;
    // The distance along a periodic axis (a particle on a face is on both).
    auto apart = [&](double a, double b) {
        const double d = a - b;
        return std::abs(d - length * std::round(d / length));
    };
    for (std::size_t i = 0; i < after.size(); ++i) {
        ASSERT_LT(apart(after.x[i], before.x[i] + 1.0 * t), 1e-4) << "particle " << i;
        ASSERT_LT(apart(after.y[i], before.y[i]), 1e-4) << "particle " << i;
        ASSERT_LT(apart(after.z[i], before.z[i] + 0.5 * t), 1e-4) << "particle " << i;
        ASSERT_NEAR(after.vx[i], 1.0, 1e-3) << "particle " << i;
    }
}

TEST_P(PeriodicModels, MomentumIsKeptAcrossTheFaces) {
    // Two layers sliding past each other and across every face: the pair forces across the faces
    // cancel as those inside do.
    const Scene scene = periodicBox("[0.5, 0, 0.2]", "[-0.3, 0.1, 0]", GetParam());
    auto sim = start(scene, Backend::Cpu, NeighbourMode::Auto);
    auto momentum = [&](Vec3d& total, double& scale) {
        HostParticles p;
        sim->download(p);
        total = Vec3d();
        scale = 0;
        for (std::size_t i = 0; i < p.size(); ++i) {
            total += Vec3d(p.vx[i], p.vy[i], p.vz[i]);
            scale += std::sqrt(double(p.vx[i]) * p.vx[i] + double(p.vy[i]) * p.vy[i] +
                               double(p.vz[i]) * p.vz[i]);
        }
    };
    Vec3d before, after;
    double scaleBefore, scaleAfter;
    momentum(before, scaleBefore);
    sim->advanceTo(0.2);
    ASSERT_EQ(sim->fault().code, 0) << describeFault(sim->fault(), sim->params());
    momentum(after, scaleAfter);
    EXPECT_EQ(sim->particleCount(), Index(1000));
    // The layers did exchange momentum (the flow is not frozen) ...
    EXPECT_LT(scaleAfter, 0.99 * scaleBefore);
    // ... and the whole kept its own.
    EXPECT_LT(length(after - before), 1e-4 * scaleBefore) << GetParam();
}

// Honey between no-slip walls at y = 0 and H, periodic along x and z, driven by a body force f
// along x (as gravity): after a few viscous times H^2 / nu the profile is
// u(y) = f y (H - y) / (2 nu); each layer of the ten within `tolerance` (+ 1 mm/s). `model`:
// "delta-sph" (WCSPH) or "dfsph".
void expectPoiseuilleProfile(const std::string& model, double tolerance) {
    const Scene scene = parseScene("{" + solverField(model) + R"(
        "container": {"min": [0, 0, 0], "max": [0.024, 0.04, 0.016],
                      "periodic": [true, false, true]},
        "blocks": [{"min": [0, 0, 0], "max": [0.024, 0.04, 0.016]}],
        "fluid": {"preset": "honey", "model": "delta-sph"},
        "particles": {"spacing": 0.004, "smoothingRatio": 2},
        "gravity": [2, 0, 0],
        "walls": {"model": "particles"}
    })",
                                   "<test Poiseuille channel>");
    auto sim = start(scene, Backend::Cpu, NeighbourMode::Auto);
    sim->advanceTo(0.5);
    ASSERT_EQ(sim->fault().code, 0) << describeFault(sim->fault(), sim->params());
    HostParticles out;
    sim->download(out);
    const double f = 2, H = 0.04, nu = 6.0 / 1420, d = 0.004;
    std::vector<double> sum(10, 0.0);
    std::vector<int> count(10, 0);
    for (std::size_t i = 0; i < out.size(); ++i) {
        const int layer = std::clamp(int(out.y[i] / d), 0, 9);
        sum[std::size_t(layer)] += out.vx[i];
        ++count[std::size_t(layer)];
    }
    for (int layer = 0; layer < 10; ++layer) {
        const double y = (layer + 0.5) * d, want = f * y * (H - y) / (2 * nu);
        ASSERT_GT(count[std::size_t(layer)], 0);
        const double got = sum[std::size_t(layer)] / count[std::size_t(layer)];
        EXPECT_NEAR(got, want, tolerance * want + 0.001)
            << model << ": layer " << layer << " at y = " << y;
    }
}

TEST(Periodic, DeltaSphChannelReachesThePoiseuilleProfile) {
    // Measured at d = H / 10: 2.2% above it mid-channel, 5% at the wall layers (the no-slip walls
    // act a little beyond the container); at d = H / 20, 1.3% (0.0958 against 0.0944 m/s
    // mid-channel), 4% at the wall layers.
    expectPoiseuilleProfile("delta-sph", 0.06);
}

TEST(Periodic, DfsphChannelReachesThePoiseuilleProfile) {
    // The same channel under DFSPH: the ghosts across the faces take their owners' velocities
    // after every sweep (solver/dfsph/dfsph.h), and the profile comes out symmetric. Measured
    // (2026-12-05): 2.8% above it mid-channel, 7% at the worst layer (the next to the walls).
    // Before the viscous forces took the lattice-corrected gradient (dfsphForceParams) the fluid's
    // viscosity read 5% low: 8.3% mid-channel, 12.8% at the worst layer. The wall layer still
    // sits a little closer to the wall than WCSPH's (0.47 d on average against 0.50 d).
    expectPoiseuilleProfile("dfsph", 0.10);
}

TEST(Periodic, AxisShorterThanTwoRadiiIsRefused) {
    // h = 2 d = 0.02 m by default: a periodic z of 0.03 m would let particles meet their images.
    const Scene scene = parseScene(R"({
        "container": {"min": [0, 0, 0], "max": [0.2, 0.1, 0.03], "periodic": [true, false, true]},
        "blocks": [{"min": [0, 0, 0], "max": [0.2, 0.05, 0.03]}],
        "particles": {"spacing": 0.01}
    })",
                                   "<test short periodic axis>");
    try {
        start(scene, Backend::Cpu, NeighbourMode::Auto);
        FAIL() << "a periodic axis shorter than 2 h was accepted";
    } catch (const SimulationError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("container.periodic"), std::string::npos) << what;
        EXPECT_NE(what.find("along z"), std::string::npos) << what;
        EXPECT_NE(what.find("0.03"), std::string::npos) << what;
    }
}

}  // namespace
}  // namespace weir
