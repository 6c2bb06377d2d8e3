// The simulation interface that the CLI and tests drive, independent of backend.
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "core/backend.h"
#include "core/stage_timer.h"
#include "grid/cell_id.h"
#include "physics/faults.h"
#include "physics/sph_params.h"
#include "solver/neighbour_search.h"
#include "solver/particles.h"
#include "solver/pressure_solver.h"
#include "solver/simulation_setup.h"

namespace weir {

// A rigid body's pose (physics/rigid_body.h) as frames record it (solver/particles.h).
inline BodyPose poseOf(const RigidBody& b) {
    BodyPose pose;
    pose.position = Vec3d(b.x);
    pose.velocity = Vec3d(b.v);
    pose.angularVelocity = Vec3d(b.omega);
    pose.orientation[0] = b.q.x;
    pose.orientation[1] = b.q.y;
    pose.orientation[2] = b.q.z;
    pose.orientation[3] = b.q.w;
    return pose;
}

// A simulation's particle arrays where they live (device memory for CUDA), in the current
// (cell) order, for zero-copy consumers: the viewer's CUDA-OpenGL interop, DLPack.
struct ParticleArrays {
    const Real4* pos = nullptr;  // x, y, z, mark
    const Real4* vel = nullptr;  // vx, vy, vz, density
    const Index* id = nullptr;   // the particle's id (its index in the initial order)
    Index count = 0;
    bool onDevice = false;  // CUDA device memory, else host memory
};

// A diagnosis of a blown-up state, made from the first fault recorded on the device.
std::string describeFault(const FaultRecord& fault, const SphParams& params);

class Simulation {
   public:
    virtual ~Simulation() = default;

    // Advances `steps` time steps (adaptive or fixed dt). Does not synchronize with the host.
    virtual void advance(int steps) = 0;
    // Advances until the simulated time is exactly `time` (the last step cut to land on it),
    // reading the device clock back once per batch of steps.
    virtual void advanceTo(double time) = 0;
    // Computes density and pressure of the current state without stepping (for frame 0).
    virtual void computeDensity() = 0;
    // Copies the particles back, in their original (initial) order.
    virtual void download(HostParticles& out) = 0;
    // The first fault recorded since the start (code None if there was none).
    virtual FaultRecord fault() = 0;
    // Waits for queued device work.
    virtual void synchronize() = 0;
    // Runs one stage of the step alone (for stage benchmarks); asynchronous like advance().
    using Stage = weir::Stage;
    virtual void runStage(Stage stage) = 0;

    // Per-stage timing; when on, each step's stage times are recorded (this synchronizes).
    virtual void setTiming(bool on) = 0;
    virtual const StageTimes& stageTimes() const = 0;
    virtual void clearStageTimes() = 0;

    virtual Backend backend() const = 0;
    virtual NeighbourMode neighbourMode() const = 0;
    virtual std::string deviceName() const = 0;
    // Bytes of device (CUDA) or host (CPU) memory held for particles, grid and scratch.
    virtual std::size_t bytesHeld() const = 0;
    // Occupied grid cells after the last grid build (0 in brute-force mode).
    virtual Index occupiedCells() const = 0;

    virtual const SphParams& params() const = 0;
    // The pressure solver's name (solver/methods.h).
    virtual std::string method() const = 0;
    // The particle arrays in the backend's memory, valid until the next step.
    virtual ParticleArrays particleArrays() = 0;
    virtual Index particleCount() const = 0;
    virtual long long stepCount() const = 0;
    // Simulated time, s (read back from the device clock).
    virtual double time() const = 0;
    // What an iterative pressure solver did since the last call (none for WCSPH); a host round
    // trip, read once a frame.
    virtual SolverReport takeSolverReport() { return {}; }
    // The rigid bodies (physics/rigid_body.h) as they are now; none by default.
    virtual std::vector<RigidBody> rigidBodies() { return {}; }
    // What the emitters and sinks (physics/emitter.h) have done since the start: a host round
    // trip; all zero without them.
    virtual FlowCounters flowCounters() { return {}; }
};

// Creates a simulation on a backend with the setup's pressure solver; throws SimulationError if
// the particles do not fit in memory or the solver is unknown.
std::unique_ptr<Simulation> makeSimulation(Backend backend, NeighbourMode mode,
                                           SimulationSetup setup);

// Bytes of memory one particle needs (arrays, sort scratch, grid tables), an upper estimate;
// cellIdBytes: the width of the sparse grid's cell ids (cellIdBytesFor(grid)).
std::size_t bytesPerParticleEstimate(NeighbourMode mode, std::size_t cellIdBytes = sizeof(CellKey));

// Throws SimulationError naming how many particles would fit if `count` do not fit in `freeBytes`.
void checkMemoryFits(Index count, NeighbourMode mode, std::size_t freeBytes,
                     const std::string& where, std::size_t cellIdBytes = sizeof(CellKey));

}  // namespace weir
