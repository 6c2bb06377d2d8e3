// What a pressure solver (a method: WCSPH, DFSPH, ...) is to the rest of weir: the stages of one
// step over the shared parts of a simulation. Each method lives in a folder of its own under
// solver/ with its stages and tests, and is registered by one line in solver/methods.h.
#pragma once

#include <cstddef>
#include <vector>

#include "physics/boundary.h"
#include "physics/collision.h"
#include "physics/faults.h"
#include "physics/particle_view.h"
#include "physics/rigid_body.h"
#include "physics/sph_params.h"
#include "physics/time_step.h"
#include "solver/neighbour_search.h"
#include "solver/particle_store.h"

namespace weir {

// The stages a stage benchmark can run one at a time (bench/, `weir bench`).
enum class Stage { Grid, Density, Force, Integrate };

// The parts of a simulation a method's step works on. The pointers are device memory on CUDA.
template <class Exec>
struct StepContext {
    Exec& exec;
    ParticleStore<Exec>& store;
    NeighbourSearch<Exec>& search;
    const SphParams& params;
    StepClock* clock;        // this step's dt and time (physics/time_step.h)
    FaultRecord* fault;      // the first fault of the run (physics/faults.h)
    BoundaryView boundary;   // static boundary particles (empty: none)
    ObstacleView obstacles;  // obstacles of the simple collision response
    RigidBodyView bodies{};  // rigid bodies among the boundary particles (count 0: none)
};

// What an iterative solver did since the last report (one frame's worth): per solve kind, the
// solves run, their velocity updates in all, the most one took, how many stopped at the limit
// unconverged, and the largest mean error one ended with (relative to rho0).
struct SolveReport {
    int solves = 0;
    long long iterations = 0;
    int maxIterations = 0;
    int unconverged = 0;
    double worstError = 0;
};
struct SolverReport {
    bool iterative = false;  // false: a method with no iterations (WCSPH), nothing below
    SolveReport density;     // the constant-density solve
    SolveReport divergence;  // the divergence-free solve
};

template <class Exec>
class PressureSolver {
   public:
    virtual ~PressureSolver() = default;

    // One step: the grid build, the method's stages and the move of every particle, bracketed
    // by the one-thread stages that choose dt and move the clock on (physics/time_step.h).
    virtual void step(StepContext<Exec>& context) = 0;
    // Density (and what the method derives from it) of the current state, without stepping
    // (frame 0).
    virtual void computeDensity(StepContext<Exec>& context) = 0;
    // One stage alone, for stage benchmarks; asynchronous like step().
    virtual void runStage(StepContext<Exec>& context, Stage stage) = 0;
    // Whether step() may be replayed as a CUDA graph (no host round trip inside a step).
    virtual bool capturable() const { return true; }
    // Bytes of the method's own per-particle arrays.
    virtual std::size_t bytesHeld() const = 0;
    // The iterations since the last call, and a fresh count from here (a host round trip).
    virtual SolverReport takeReport(Exec&) { return {}; }
    // The pressure the method solved for in its last step, by particle id (ids 0 .. n - 1), into
    // `byId`; false where the method has none of its own (the frames then carry the equation of
    // state's, from the density).
    virtual bool solvedPressure(Exec&, std::vector<Real>& /*byId*/) { return false; }
};

}  // namespace weir
