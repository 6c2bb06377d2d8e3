// One simulation over several ranks (paper §9's future work: fluid too large for one GPU): each
// rank steps the particles of its slab on its own backend; between steps it hands the particles
// that left its slab to their new owners and takes ghost copies of its neighbours' particles
// within two smoothing radii of its borders (the ghosts within one radius then have their whole
// neighbourhood, so their density is exact and the owned particles' forces match a single-rank
// run). The ranks agree on each step's dt by one reduction; borders move to balance the counts.
#pragma once

#include <memory>

#include "cluster/communicator.h"
#include "cluster/decomposition.h"
#include "cluster/nccl_transport.h"
#include "cluster/rank_part.h"
#include "solver/simulation.h"

namespace weir {

// How ghost copies travel: staged through host memory and MPI (any backend), or GPU to GPU by
// NCCL (CUDA runs; the default there when weir has NCCL).
enum class HaloTransport { Auto, Host, Nccl };
HaloTransport parseHaloTransport(const std::string& name);  // auto, host, nccl

struct DistributedOptions {
    HaloTransport transport = HaloTransport::Auto;
    int rebalanceEvery = 20;       // steps between load checks
    double rebalanceAbove = 1.02;  // max/mean particles per rank that moves the borders
    int histogramBins = 4096;      // resolution of the border placement along the axis
};

// What the last exchange moved, for logs and `weir bench`.
struct ExchangeStats {
    std::int64_t owned = 0;     // this rank's particles
    std::int64_t ghosts = 0;    // ghost copies received
    std::int64_t arrivals = 0;  // particles handed over to this rank
    std::int64_t bytesSent = 0;
    double exchangeSeconds = 0;  // host time of the last exchange (selection, transfer, append)
    std::string transport;       // "host" or "nccl"
    int rebalances = 0;          // border moves so far
};

// The histogram of a setup's particles along `axis` of its container (seeds: sampled).
AxisHistogram setupHistogram(const SimulationSetup& setup, int axis, int bins);

class DistributedSimulation final : public Simulation {
   public:
    // Every rank passes the same whole-scene setup; each keeps its share. `comm` must outlive
    // this object.
    DistributedSimulation(Communicator& comm, Backend backend, NeighbourMode mode,
                          SimulationSetup setup, DistributedOptions options = {});

    void advance(int steps) override;
    void advanceTo(double time) override;
    void computeDensity() override;
    // Collective: rank 0 receives every particle, in the original order; the others get none.
    void download(HostParticles& out) override;
    // Collective: the first fault of any rank.
    FaultRecord fault() override;
    void synchronize() override { local_->simulation().synchronize(); }
    void runStage(Stage stage) override { local_->simulation().runStage(stage); }
    void setTiming(bool on) override { local_->simulation().setTiming(on); }
    const StageTimes& stageTimes() const override { return local_->simulation().stageTimes(); }
    void clearStageTimes() override { local_->simulation().clearStageTimes(); }
    Backend backend() const override { return local_->simulation().backend(); }
    NeighbourMode neighbourMode() const override { return local_->simulation().neighbourMode(); }
    std::string deviceName() const override;
    std::size_t bytesHeld() const override { return local_->simulation().bytesHeld(); }
    Index occupiedCells() const override { return local_->simulation().occupiedCells(); }
    const SphParams& params() const override { return local_->simulation().params(); }
    std::string method() const override { return local_->simulation().method(); }
    // This rank's arrays (its owned particles and ghosts).
    ParticleArrays particleArrays() override { return local_->simulation().particleArrays(); }
    Index particleCount() const override { return Index(total_); }
    long long stepCount() const override { return local_->simulation().stepCount(); }
    double time() const override { return local_->simulation().time(); }

    // One step on every rank: exchange, agree on dt, step each slab (collective).
    void stepOnce();
    // This rank's own particles (no ghosts), in its current order.
    void downloadOwned(ParticleBatch& out) { local_->downloadOwned(out); }

    const Decomposition& decomposition() const { return decomposition_; }
    const ExchangeStats& exchangeStats() const { return stats_; }
    Communicator& communicator() { return comm_; }
    // Moves the borders now if the counts are out of balance (collective).
    void rebalance();
    // Sets the borders (the same on every rank); particles move at the next exchange.
    void setDecomposition(const Decomposition& decomposition);

   private:
    void exchange();
    // The rank's neighbour table over its slab and halo only.
    void fitGrid();
    // The ghosts' part of exchange() by NCCL: staged, counted, sent and received on the GPU.
    std::int64_t exchangeGhostsOnDevice(const Slab& share, std::int64_t* bytesSent);
    // Shares each rank's largest speed and acceleration (the dt is the same everywhere) and
    // whether any rank has faulted; returns true if one has.
    bool agreeOnClock();

    Communicator& comm_;
    DistributedOptions options_;
    std::unique_ptr<RankPart> local_;
    std::unique_ptr<NcclTransport> nccl_;  // null: ghosts staged through the host
    Decomposition decomposition_;
    std::int64_t total_ = 0;
    double haloWidth_ = 0;
    double boxLo_ = 0, boxExtent_ = 0;
    int stepsSinceBalance_ = 0;
    bool faulted_ = false;
    StepClock predicted_{};  // the clock after the step in flight, as the device will have it
    ExchangeStats stats_;
};

}  // namespace weir
