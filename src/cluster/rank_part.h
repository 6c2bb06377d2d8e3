// One rank's part of a distributed run (cluster/distributed_simulation.h): a simulation on one
// backend whose particles are exchanged between steps. The operations on its particles (who
// leaves, who is a ghost for a neighbour, what arrives) work on the simulation's particle store
// (solver/particle_store.h); the simulation itself knows nothing of ranks.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "core/backend.h"
#include "core/slab.h"
#include "physics/faults.h"
#include "physics/time_step.h"
#include "solver/particles.h"
#include "solver/simulation.h"

namespace weir {

class RankPart {
   public:
    virtual ~RankPart() = default;

    // The rank's simulation (its particles: the owned ones and this step's ghosts).
    virtual Simulation& simulation() = 0;

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

// A rank's part on a backend; throws SimulationError as makeSimulation does.
std::unique_ptr<RankPart> makeRankPart(Backend backend, NeighbourMode mode, SimulationSetup setup);

}  // namespace weir
