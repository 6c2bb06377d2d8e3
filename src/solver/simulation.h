// The simulation interface that the CLI and tests drive, independent of backend.
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "cluster/slab.h"
#include "core/backend.h"
#include "core/stage_timer.h"
#include "grid/cell_id.h"
#include "physics/boundary.h"
#include "physics/sph_params.h"
#include "physics/stages.h"
#include "scene/seeding.h"
#include "solver/particles.h"

namespace weir {

// Grid: the sorted grid with the paper's cell table and 26-neighbour table (§6.2).
// Dense: the same sort with a dense table over every cell (grid/dense_grid.h), faster.
// Brute: O(N^2). Auto: Dense where its table is small enough, else Grid.
enum class NeighbourMode { Grid, Dense, Brute, Auto };

NeighbourMode parseNeighbourMode(const std::string& name);
// Auto made concrete for a setup.
NeighbourMode resolveNeighbourMode(NeighbourMode mode, const GridSpec& grid, std::int64_t n);
const char* neighbourModeName(NeighbourMode mode);

// Everything a backend needs to start: parameters, grid, obstacles and the initial particles.
struct SimulationSetup {
    SphParams params;
    GridSpec grid;
    std::vector<ObstacleBox> obstacleBoxes;
    std::vector<ObstacleSphere> obstacleSpheres;
    BoundaryParticles boundary;  // walls.model "particles": static wall particles and their grid
    HostParticles particles;
    SceneSeeds seeds;  // instead of particles: seeded by the simulation itself (scene/seeding.h)
    // Distributed runs: `particles` are this rank's share with these global ids; `seeds` are
    // seeded only inside `share` (ids: the seed order). Single runs: empty ids, every slab.
    std::vector<Index> particleIds;
    Slab share;
    std::int64_t shareEstimate = 0;  // particles expected in `share` (for the memory check)

    std::int64_t particleCount() const {
        return particles.size() > 0 ? std::int64_t(particles.size()) : seeds.count;
    }
    // Particles this process will hold: all of them, or its share's.
    std::int64_t countHere() const {
        return share.everything() || particles.size() > 0 ? particleCount() : shareEstimate;
    }
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
    enum class Stage { Grid, Density, Force, Integrate };
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
    virtual Index particleCount() const = 0;
    virtual long long stepCount() const = 0;
    // Simulated time, s (read back from the device clock).
    virtual double time() const = 0;
};

// A simulation on one backend that can also be one rank's part of a distributed run
// (cluster/distributed_simulation.h): its particles are exchanged between steps. Every
// backend's solver is one.
class RankPart : public Simulation {
   public:
    // Copies the owned particles outside `share` into `leaving` and drops them and the ghosts
    // (at once, or, with the dense table, in the next grid build).
    virtual void takeLeavers(const Slab& share, ParticleBatch& leaving) = 0;
    // Appends copies of the owned particles within `width` of the borders of `share` to `out`.
    virtual void copyBorderParticles(const Slab& share, double width, ParticleBatch& out) = 0;
    // Adds particles: arrivals, or ghost copies (position w = 2, arriving).
    virtual void append(const ParticleBatch& batch) = 0;
    // Appends the owned particles (no ghosts) to `out`, in the current order.
    virtual void downloadOwned(ParticleBatch& out) = 0;
    // counts[b] += owned particles in bin b of width binWidth from lo along `axis` (clamped).
    virtual void histogram(int axis, double lo, double binWidth, std::vector<Index>& counts) = 0;
    // Stages ghost copies (arriving: position w = 2) of the owned particles of `share` inside each
    // window, window after window, in this backend's memory (device memory on CUDA, for NCCL to
    // send); counts[k] = particles of window k.
    virtual ParticleSpans stageWindows(const Slab& share, const std::vector<Slab>& windows,
                                       std::vector<std::int64_t>& counts) = 0;
    // Room for `count` more ghost copies at the end, in this backend's memory, to be written
    // there (by NCCL, arriving: position w = 2) before the next step.
    virtual ParticleSpans appendSpace(std::size_t count) = 0;
    // Neighbour tables over the cells of `share` widened by `margin` only.
    virtual void restrictGrid(const Slab& share, double margin) = 0;
    // The backend's CUDA stream (cudaStream_t), nullptr on the CPU.
    virtual void* deviceStream() = 0;
    virtual StepClock clock() = 0;
    // The clock and the first fault, read back in one wait.
    virtual StepClock clockAndFault(FaultRecord& fault) = 0;
    virtual void setClock(const StepClock& clock) = 0;
    // One step with the clock as it is (the caller set the shared dt inputs and target).
    virtual void stepOnce() = 0;
};

// Creates a simulation on a backend; throws SimulationError if the particles do not fit in memory.
std::unique_ptr<RankPart> makeSimulation(Backend backend, NeighbourMode mode,
                                         SimulationSetup setup);

// Bytes of memory one particle needs (arrays, sort scratch, grid tables), an upper estimate;
// cellIdBytes: the width of the sparse grid's cell ids (cellIdBytesFor(grid)).
std::size_t bytesPerParticleEstimate(NeighbourMode mode, std::size_t cellIdBytes = sizeof(CellKey));

// Throws SimulationError naming how many particles would fit if `count` do not fit in `freeBytes`.
void checkMemoryFits(Index count, NeighbourMode mode, std::size_t freeBytes,
                     const std::string& where, std::size_t cellIdBytes = sizeof(CellKey));

}  // namespace weir
