// A simulation driven from a script (the Python module, src/python/module.cpp): a scene made
// runnable with the same choices as `weir run`, stepping that stops with the CLI's diagnosis, and
// the particles read back at most once per state. Plain C++: the bindings only convert.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "core/backend.h"
#include "io/frame_writer.h"
#include "scene/scene.h"
#include "scene/setup.h"
#include "solver/particles.h"
#include "solver/simulation.h"
#include "surface/surface.h"

namespace weir {

// The simulation blew up; the message is describeFault's diagnosis (what `weir run` prints
// before it exits with code 3).
class BlowUpError : public std::runtime_error {
   public:
    using std::runtime_error::runtime_error;
};

// A call on a simulation that another thread is stepping (stepping releases the GIL): one call
// at a time, else the engine's buffers would be read while they are rewritten.
class BusyError : public std::runtime_error {
   public:
    using std::runtime_error::runtime_error;
};

// What `weir run` takes besides the scene, with the same names and defaults.
struct ScriptedOptions {
    std::string backend = "auto";           // auto | cpu | cuda
    std::string neighbours = "auto";        // auto | dense | grid | brute
    std::string solver;                     // wcsph | dfsph; "" the scene's own
    std::string model;                      // paper | delta-sph; "" the scene's own
    std::optional<std::int64_t> particles;  // about this many particles; unset: the scene's
};

class ScriptedSimulation {
   public:
    // Builds the setup as `weir run` does (SceneError, SimulationError, std::invalid_argument for
    // bad names), makes the simulation and computes frame 0's density.
    ScriptedSimulation(const Scene& scene, const ScriptedOptions& options);

    // `steps` time steps in one call of Simulation::advance (steps >= 0, else
    // std::invalid_argument), then one read of the fault record: BlowUpError on a fault.
    void step(std::int64_t steps);
    // Steps until the simulated time is `time` (not before the current time, else
    // std::invalid_argument); BlowUpError on a fault.
    void advanceTo(double time);
    // The first fault's diagnosis, "" while there is none. Every call below, and simulation(),
    // throws BusyError while another thread is in one of them on this simulation.
    std::string faultText();

    // The particles in their original order (index = id), with pressure from the density;
    // downloaded on the first call after a step, then kept.
    const HostParticles& particles();
    // The particle arrays where they live, in cell order, after waiting for queued work; valid
    // until the next step. Until then particles() downloads afresh on every call, as the
    // caller may write to them.
    ParticleArrays deviceArrays();
    // The fluid's surface by marching cubes; a spacing of 0 takes the run's lattice spacing.
    TriangleMesh surface(Backend backend, SurfaceOptions options);
    // Writes the current state as frame `index` at the current time; the first write of a writer
    // records the run (frames.json: scene, particle count, spacing), as `weir run` does.
    void writeFrame(FrameWriter& writer, int index);

    const Scene& scene() const { return scene_; }
    const SetupReport& report() const { return report_; }
    NeighbourMode neighbourMode() const { return mode_; }
    // The engine's simulation; throws BusyError while another thread steps this one.
    Simulation& simulation();
    // Bumped by every step: a consumer's copy of the particles is stale when it differs.
    std::uint64_t stateVersion() const { return version_; }

   private:
    // Marks the simulation busy for one call; BusyError if it already is.
    class Busy {
       public:
        explicit Busy(ScriptedSimulation& s);
        ~Busy() { flag_ = false; }
        Busy(const Busy&) = delete;
        Busy& operator=(const Busy&) = delete;

       private:
        std::atomic<bool>& flag_;
    };
    void checkFault();
    std::string diagnosis();               // faultText() without the busy check
    const HostParticles& hostParticles();  // particles() without the busy check

    Scene scene_;
    SetupReport report_;
    NeighbourMode mode_ = NeighbourMode::Dense;
    std::unique_ptr<Simulation> sim_;
    HostParticles host_;
    std::uint64_t version_ = 0;
    std::uint64_t hostVersion_ = ~std::uint64_t(0);
    bool viewsShared_ = false;  // particle views handed out since the last step
    std::atomic<bool> busy_{false};
};

}  // namespace weir
