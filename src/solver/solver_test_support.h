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
