// Helpers for solver tests: small scenes, running a simulation, comparing states.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>

#include "scene/scene.h"
#include "scene/setup.h"
#include "solver/simulation.h"

namespace weir::testing {

// A dam break of a few thousand particles, small enough for brute force in a test.
inline Scene smallDamBreak(int particles = 2000) {
    return parseScene(R"({
        "name": "small_dam_break",
        "container": {"min": [0, 0, 0], "max": [0.6, 0.4, 0.2]},
        "blocks": [{"min": [0, 0, 0], "max": [0.2, 0.25, 0.2]}],
        "particles": {"count": )" +
                          std::to_string(particles) + R"(}
    })",
                      "<test small_dam_break>");
}

// Blocks that overlap, a sphere across a block's corner, obstacles in the fluid and fluid moving:
// every rule of the seeding at work.
inline Scene seedingScene() {
    return parseScene(R"({
        "container": {"min": [0, 0, 0], "max": [0.4, 0.3, 0.3]},
        "blocks": [{"min": [0, 0, 0], "max": [0.1, 0.1, 0.1], "velocity": [1, 0, 0]},
                   {"min": [0.053, 0, 0], "max": [0.153, 0.1, 0.1]}],
        "spheres": [{"center": [0.1, 0.1, 0.1], "radius": 0.047, "velocity": [0, -1, 0]}],
        "obstacles": {"boxes": [{"min": [0.02, 0.02, 0.02], "max": [0.04, 0.05, 0.06]}],
                      "spheres": [{"center": [0.12, 0.05, 0.05], "radius": 0.02}]},
        "particles": {"spacing": 0.01}
    })",
                      "<test seeding>");
}

// The simulation seeds its particles on its backend exactly as the host would: same count,
// order, positions and velocities.
inline void expectBackendSeedingMatchesTheHost(Backend backend) {
    for (const Scene& scene : {seedingScene(), builtinScene("drop_into_pool")}) {
        SetupOptions onBackend;
        onBackend.seedOnDevice = true;
        SimulationSetup seeded = buildSetup(scene, onBackend, nullptr);
        SimulationSetup hosted = buildSetup(scene, {}, nullptr);
        ASSERT_EQ(seeded.particles.size(), 0u);
        ASSERT_EQ(seeded.particleCount(), std::int64_t(hosted.particles.size()));
        auto sim = makeSimulation(backend, NeighbourMode::Auto, std::move(seeded));
        HostParticles out;
        sim->download(out);
        const HostParticles& want = hosted.particles;
        ASSERT_EQ(out.size(), want.size()) << scene.name;
        for (std::size_t i = 0; i < want.size(); ++i) {
            ASSERT_EQ(out.x[i], want.x[i]) << scene.name << " particle " << i;
            ASSERT_EQ(out.y[i], want.y[i]) << scene.name << " particle " << i;
            ASSERT_EQ(out.z[i], want.z[i]) << scene.name << " particle " << i;
            ASSERT_EQ(out.vx[i], want.vx[i]) << scene.name << " particle " << i;
            ASSERT_EQ(out.vy[i], want.vy[i]) << scene.name << " particle " << i;
        }
    }
}

inline std::unique_ptr<Simulation> start(const Scene& scene, Backend backend, NeighbourMode mode,
                                         SetupReport* report = nullptr) {
    return makeSimulation(backend, mode, buildSetup(scene, {}, report));
}

inline HostParticles stateAfter(Simulation& sim, int steps) {
    sim.advance(steps);
    HostParticles out;
    sim.download(out);
    return out;
}

// Largest distance between the same particle in two states.
inline double maxPositionDifference(const HostParticles& a, const HostParticles& b) {
    double worst = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        double dx = a.x[i] - b.x[i], dy = a.y[i] - b.y[i], dz = a.z[i] - b.z[i];
        worst = std::max(worst, std::sqrt(dx * dx + dy * dy + dz * dz));
    }
    return worst;
}

// Root mean square distance between the same particle in two states.
inline double rmsPositionDifference(const HostParticles& a, const HostParticles& b) {
    double sumSquares = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        const double dx = a.x[i] - b.x[i], dy = a.y[i] - b.y[i], dz = a.z[i] - b.z[i];
        sumSquares += dx * dx + dy * dy + dz * dz;
    }
    return std::sqrt(sumSquares / double(a.size()));
}

inline double maxSpeed(const HostParticles& p) {
    double worst = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        worst = std::max(worst, std::sqrt(double(p.vx[i]) * p.vx[i] + double(p.vy[i]) * p.vy[i] +
                                          double(p.vz[i]) * p.vz[i]));
    }
    return worst;
}

inline double meanDensity(const HostParticles& p) {
    double sum = 0;
    for (Real r : p.rho) {
        sum += r;
    }
    return sum / double(p.size());
}

}  // namespace weir::testing
