// From a scene to a runnable setup: particle spacing, mass, smoothing radius, stiffness,
// viscosity and time step derived from physics (paper §5.2), and the initial particles.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/backend.h"
#include "physics/kernels.h"
#include "scene/scene.h"
#include "solver/simulation_setup.h"

namespace weir {

struct SetupOptions {
    std::optional<std::int64_t> particleCount;  // overrides the scene's resolution
    // Leave the particles to be seeded by the simulation on its own backend (on the GPU for a
    // CUDA run): setup.seeder instead of setup.particles, for runs too large to seed on the host.
    bool seedOnDevice = false;
    // The backend the run will use, when known: a CPU run also needs its simulation's arrays in
    // host memory (unset: only the seeded arrays are checked against host memory before seeding;
    // makeSimulation checks the backend's memory in full).
    std::optional<Backend> backend;
    // Free host memory in bytes (unset: measured; tests set it).
    std::optional<std::size_t> hostFreeBytes;
    // A CUDA run: the device's free memory in bytes (cudaFreeMemoryBytes()), so that particles
    // the GPU cannot hold are refused before the host seeds them.
    std::optional<std::size_t> deviceFreeBytes;
};

// What was chosen and why, for logs, --explain and benchmarks.
struct SetupReport {
    double spacing = 0;           // particle spacing d, m
    double smoothingRadius = 0;   // h, m
    double fluidVolume = 0;       // m^3
    double fluidHeight = 0;       // deepest fluid column along gravity, m
    double expectedSpeed = 0;     // largest speed expected from the fall height and initial speeds
    double speedOfSound = 0;      // sqrt(k), m/s
    double latticeKernelSum = 0;  // sum of W d^3 over a full lattice (1 for an exact kernel)
    double gradientMoment = 1;    // delta-SPH: the kernel gradient's lattice moment it divides by
    int stepsPerFrame = 0;
    double frameInterval = 0;           // s
    std::int64_t frames = 0;            // frames after frame 0
    std::vector<std::string> lines;     // one per decision, human-readable
    std::vector<std::string> warnings;  // settings likely to make the fluid misbehave
};

// Builds the setup; throws SceneError for a scene that cannot be run (no particles, grid too big,
// more particles or boundary particles than host memory holds: counted or estimated before any
// is seeded, naming the most that fit; derived parameters that overflow).
SimulationSetup buildSetup(const Scene& scene, const SetupOptions& options, SetupReport* report);

// Initial particles on a cubic lattice of spacing d filling the scene's blocks and spheres.
HostParticles seedParticles(const Scene& scene, double spacing);

}  // namespace weir
