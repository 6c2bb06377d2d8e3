// The distributed step: exchange, agree on dt, step each slab, rebalance now and then.
#include "cluster/distributed_simulation.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <set>
#include <stdexcept>

#include "cluster/particle_routing.h"
#include "core/check.h"
#include "physics/eos.h"

namespace weir {

namespace {

constexpr double kNoTarget = 1e300;

std::string hostName() {
    char name[256] = {};
    gethostname(name, sizeof name - 1);
    return name;
}

// Bins of a histogram over [lo, lo + extent) along an axis.
AxisHistogram emptyHistogram(const SphParams& params, int axis, int bins) {
    AxisHistogram h;
    h.axis = axis;
    h.lo = double(params.boxMin[axis]);
    h.binWidth = std::max(1e-12, double(params.boxMax[axis] - params.boxMin[axis]) / bins);
    h.counts.assign(std::size_t(bins), 0);
    return h;
}

void addToHistogram(AxisHistogram& h, double c, std::int64_t weight) {
    const double at = (c - h.lo) / h.binWidth;
    const std::int64_t bins = std::int64_t(h.counts.size());
    const std::int64_t b = at < 0 ? 0 : std::min(bins - 1, std::int64_t(at));
    h.counts[std::size_t(b)] += weight;
}

// The setup's particles inside `share`, with their global ids (a seeder: restricted to the
// share; `expected` of them, about, for its memory check).
SimulationSetup shareOf(const SimulationSetup& whole, const Slab& share, std::int64_t expected) {
    SimulationSetup part;
    part.params = whole.params;
    part.grid = whole.grid;
    part.method = whole.method;
    part.obstacleBoxes = whole.obstacleBoxes;
    part.obstacleSpheres = whole.obstacleSpheres;
    part.boundary = whole.boundary;
    if (whole.particles.size() == 0) {
        if (whole.seeder) {
            part.seeder = whole.seeder->within(share, expected);  // seeded by the backend
        }
        return part;
    }
    const HostParticles& p = whole.particles;
    for (std::size_t i = 0; i < p.size(); ++i) {
        const Vec3d x(p.x[i], p.y[i], p.z[i]);
        if (share.contains(share.coordinate(x))) {
            part.particles.push(x, Vec3d(p.vx[i], p.vy[i], p.vz[i]));
            // The density too: delta-SPH carries it from the hydrostatic start by the
            // continuity equation (the paper's model recomputes it from positions).
            part.particles.rho.back() = p.rho[i];
            part.particles.p.back() = p.p[i];
            part.particleIds.push_back(Index(i));
        }
    }
    return part;
}

}  // namespace

HaloTransport parseHaloTransport(const std::string& name) {
    if (name == "auto") {
        return HaloTransport::Auto;
    }
    if (name == "host") {
        return HaloTransport::Host;
    }
    if (name == "nccl") {
        return HaloTransport::Nccl;
    }
    throw std::invalid_argument("unknown halo transport '" + name +
                                "': allowed are auto, host, nccl");
}

AxisHistogram setupHistogram(const SimulationSetup& setup, int axis, int bins) {
    AxisHistogram h = emptyHistogram(setup.params, axis, bins);
    const HostParticles& p = setup.particles;
    if (p.size() > 0) {
        const std::vector<Real>& c = axis == 0 ? p.x : (axis == 1 ? p.y : p.z);
        for (Real v : c) {
            addToHistogram(h, double(v), 1);
        }
        return h;
    }
    // A seeder: a sample of the particles; the first rebalance corrects what sampling misses.
    if (setup.seeder) {
        setup.seeder->sample(axis,
                             [&](double c, std::int64_t weight) { addToHistogram(h, c, weight); });
    }
    return h;
}

// The axis the slabs split: the container's longest that has walls. The ghost copies of periodic
// boundaries (solver/periodic_ghosts.h) work within each rank's particles, so the slab borders
// must not cross a periodic face.
static int slabAxis(const SphParams& params) {
    int best = -1;
    for (int a = 0; a < 3; ++a) {
        const Real length = params.boxMax[a] - params.boxMin[a];
        if (!isPeriodic(params, a) &&
            (best < 0 || length > params.boxMax[best] - params.boxMin[best])) {
            best = a;
        }
    }
    if (best < 0) {
        throw SimulationError(
            "container.periodic: a distributed run splits the container into slabs along an axis "
            "with walls, and all three axes are periodic here; run this scene as one process "
            "(without mpirun), or give one axis walls");
    }
    return best;
}

DistributedSimulation::DistributedSimulation(Communicator& comm, Backend backend,
                                             NeighbourMode mode, SimulationSetup setup,
                                             DistributedOptions options)
    : comm_(comm), options_(options), decomposition_(0, {}) {
    // Each sweep of DFSPH's solves needs its neighbours' new velocities and stiffnesses from
    // the other ranks: not exchanged yet.
    if (setup.method == "dfsph") {
        throw SimulationError(
            "solver \"dfsph\" does not run across ranks yet (its solves would need an exchange "
            "per sweep): run it on one GPU or the CPU without mpirun, or use solver \"wcsph\"");
    }
    if (setup.bodies.size() > 0) {
        throw SimulationError(
            "rigid bodies (scene field \"bodies\") do not run across ranks yet (a body's loads "
            "would be summed over every rank): run the scene on one GPU or the CPU without mpirun");
    }
    if (setup.flow.active()) {
        throw SimulationError(
            "emitters and sinks (scene fields \"emitters\", \"sinks\") do not run across ranks "
            "yet (the live count and fresh ids are kept on one backend): run the scene on one GPU "
            "or the CPU without mpirun");
    }
    total_ = setup.particleCount();
    const int axis = setup.params.periodicAxes != 0
                         ? slabAxis(setup.params)
                         : longestAxis(setup.params.boxMin, setup.params.boxMax);
    const AxisHistogram histogram = setupHistogram(setup, axis, options.histogramBins);
    decomposition_ = balancedDecomposition(histogram, comm.size());
    haloWidth_ = 2.0 * double(setup.params.kernel.h);
    boxLo_ = double(setup.params.boxMin[axis]);
    boxExtent_ = double(setup.params.boxMax[axis] - setup.params.boxMin[axis]);
    // Every rank takes the same neighbour mode, the one a single run of the whole scene takes.
    mode = resolveNeighbourMode(mode, setup.grid, total_);
    const std::int64_t expected =
        countsPerRank(histogram, decomposition_)[std::size_t(comm_.rank())];
    local_ =
        makeRankPart(backend, mode, shareOf(setup, decomposition_.slab(comm_.rank()), expected));
    // NCCL wants one GPU per rank: ranks that share one (more ranks than GPUs) stage ghosts
    // through the host.
    bool gpuPerRank = true;
    if (backend == Backend::Cuda && comm_.size() > 1) {
        const std::string mine = hostName() + ":" + std::to_string(currentCudaDevice());
        std::set<std::string> seen;
        for (const Bytes& theirs : comm_.allGather(Bytes(mine.begin(), mine.end()))) {
            gpuPerRank =
                seen.insert(std::string(theirs.begin(), theirs.end())).second && gpuPerRank;
        }
    }
    const bool gpu = backend == Backend::Cuda && comm_.size() > 1 && gpuPerRank;
    if (options.transport == HaloTransport::Nccl && !(gpu && NcclTransport::available())) {
        throw std::invalid_argument(
            "the nccl halo transport needs the cuda backend, more than one rank, a GPU of its "
            "own for each rank and a weir built with NCCL");
    }
    if (gpu && options.transport != HaloTransport::Host && NcclTransport::available()) {
        nccl_ = std::make_unique<NcclTransport>(comm_);
    }
    stats_.transport = nccl_ ? "nccl" : "host";
    fitGrid();
}

std::string DistributedSimulation::deviceName() const {
    return local_->simulation().deviceName() + ", " + std::to_string(comm_.size()) + " ranks";
}

void DistributedSimulation::exchange() {
    const auto start = std::chrono::steady_clock::now();
    const int self = comm_.rank();
    const Slab share = decomposition_.slab(self);
    std::int64_t sent = 0;
    auto send = [&](const std::vector<ParticleBatch>& batches) {
        std::vector<Bytes> messages(batches.size());
        for (std::size_t r = 0; r < batches.size(); ++r) {
            if (int(r) != self && batches[r].size() > 0) {
                messages[r] = packParticles(batches[r]);
                sent += std::int64_t(messages[r].size());
            }
        }
        ParticleBatch received = batches[std::size_t(self)];  // kept here (NaN positions)
        for (const Bytes& message : comm_.exchange(messages)) {
            unpackParticles(message, received);
        }
        return received;
    };
    ParticleBatch leaving;
    local_->takeLeavers(share, leaving);
    const ParticleBatch arrivals = send(routeLeavers(leaving, decomposition_, self));
    local_->append(arrivals);
    if (nccl_) {
        stats_.ghosts = exchangeGhostsOnDevice(share, &sent);
    } else {
        ParticleBatch nearBorders;
        if (comm_.size() > 1) {
            local_->copyBorderParticles(share, haloWidth_, nearBorders);
        }
        ParticleBatch ghosts = send(routeGhosts(nearBorders, decomposition_, self, haloWidth_));
        local_->append(ghosts);
        stats_.ghosts = std::int64_t(ghosts.size());
    }
    stats_.arrivals = std::int64_t(arrivals.size());
    stats_.owned = std::int64_t(local_->simulation().particleCount()) - stats_.ghosts;
    stats_.bytesSent = sent;
    stats_.exchangeSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::int64_t DistributedSimulation::exchangeGhostsOnDevice(const Slab& share,
                                                           std::int64_t* bytesSent) {
    const int self = comm_.rank();
    std::vector<Slab> windows;
    std::vector<int> toRanks;
    for (int r = 0; r < comm_.size(); ++r) {
        const Slab theirs = decomposition_.slab(r);
        Slab window{theirs.axis, theirs.lo - haloWidth_, theirs.hi + haloWidth_};
        if (r != self && window.lo < share.hi && window.hi > share.lo) {
            windows.push_back(window);
            toRanks.push_back(r);
        }
    }
    std::vector<std::int64_t> sendCounts;
    const ParticleSpans staged = local_->stageWindows(share, windows, sendCounts);
    std::vector<Bytes> told(std::size_t(comm_.size()));
    for (std::size_t k = 0; k < toRanks.size(); ++k) {
        Bytes& message = told[std::size_t(toRanks[k])];
        message.resize(sizeof(std::int64_t));
        std::memcpy(message.data(), &sendCounts[k], sizeof(std::int64_t));
        *bytesSent += sendCounts[k] * std::int64_t(2 * sizeof(Real4) + sizeof(Index));
    }
    const std::vector<Bytes> heard = comm_.exchange(told);
    std::vector<std::int64_t> receiveCounts(heard.size(), 0);
    std::int64_t total = 0;
    for (std::size_t r = 0; r < heard.size(); ++r) {
        if (heard[r].size() == sizeof(std::int64_t)) {
            std::memcpy(&receiveCounts[r], heard[r].data(), sizeof(std::int64_t));
        }
        total += receiveCounts[r];
    }
    const ParticleSpans into = local_->appendSpace(std::size_t(total));
    nccl_->exchange(staged, toRanks, sendCounts, into, receiveCounts, local_->deviceStream());
    return total;
}

bool DistributedSimulation::agreeOnClock() {
    FaultRecord fault;
    StepClock clock = local_->clockAndFault(fault);
    std::vector<double> values{double(bitsFloat(clock.maxSpeed2)),
                               double(bitsFloat(clock.maxAccel2)), double(fault.code != 0)};
    comm_.maxInPlace(values);
    clock.maxSpeed2 = floatBits(float(values[0]));
    clock.maxAccel2 = floatBits(float(values[1]));
    local_->setClock(clock);
    faulted_ = values[2] > 0;
    // Where the clock will be after this step: the device's own one-thread stages, run here on
    // the same inputs (so the host needs no read-back to know when a frame time is reached).
    predicted_ = clock;
    weir::beginStep(predicted_, local_->simulation().params());
    weir::endStep(predicted_);
    return faulted_;
}

void DistributedSimulation::stepOnce() {
    exchange();
    if (agreeOnClock()) {
        return;  // some rank blew up: fault() tells which and how
    }
    local_->stepOnce();
    if (++stepsSinceBalance_ >= options_.rebalanceEvery) {
        rebalance();
    }
}

void DistributedSimulation::advanceTo(double target) {
    StepClock clock = local_->clock();
    clock.target = target;
    local_->setClock(clock);
    predicted_ = clock;
    while (!faulted_) {
        if (predicted_.time >= target) {
            // The prediction says the frame time is reached: confirm on the device (once a
            // frame), in case host and device rounding chose the landing step differently.
            predicted_ = local_->clock();
            if (predicted_.time >= target) {
                break;
            }
        }
        stepOnce();
    }
}

void DistributedSimulation::advance(int steps) {
    StepClock clock = local_->clock();
    clock.target = kNoTarget;
    local_->setClock(clock);
    for (int s = 0; s < steps && !faulted_; ++s) {
        stepOnce();
    }
}

void DistributedSimulation::computeDensity() {
    exchange();
    local_->simulation().computeDensity();
}

void DistributedSimulation::rebalance() {
    stepsSinceBalance_ = 0;
    if (comm_.size() == 1) {
        return;
    }
    const int bins = options_.histogramBins;
    std::vector<Index> local(std::size_t(bins), 0);
    local_->histogram(decomposition_.axis(), boxLo_, boxExtent_ / bins, local);
    AxisHistogram h;
    h.axis = decomposition_.axis();
    h.lo = boxLo_;
    h.binWidth = boxExtent_ / bins;
    h.counts.assign(local.begin(), local.end());
    comm_.sumInPlace(h.counts);
    if (imbalance(countsPerRank(h, decomposition_)) > options_.rebalanceAbove) {
        decomposition_ = balancedDecomposition(h, comm_.size());
        fitGrid();
        ++stats_.rebalances;
    }
}

void DistributedSimulation::setDecomposition(const Decomposition& decomposition) {
    if (decomposition.ranks() != comm_.size()) {
        throw std::invalid_argument("a decomposition of " + std::to_string(decomposition.ranks()) +
                                    " slabs for " + std::to_string(comm_.size()) + " ranks");
    }
    decomposition_ = decomposition;
    fitGrid();
}

void DistributedSimulation::fitGrid() {
    // Ghosts reach 2h past the borders; a radius more covers a step's moves before the next
    // exchange (particles past it would still be found, clamped into the end cells).
    local_->restrictGrid(decomposition_.slab(comm_.rank()),
                         haloWidth_ + double(local_->simulation().params().kernel.h));
}

FaultRecord DistributedSimulation::fault() {
    const FaultRecord mine = local_->simulation().fault();
    Bytes bytes(sizeof mine);
    std::memcpy(bytes.data(), &mine, sizeof mine);
    for (const Bytes& theirs : comm_.allGather(bytes)) {
        FaultRecord record;
        std::memcpy(&record, theirs.data(), sizeof record);
        if (record.code != 0) {
            return record;  // the lowest rank's first fault
        }
    }
    return mine;
}

void DistributedSimulation::download(HostParticles& out) {
    ParticleBatch mine;
    local_->downloadOwned(mine);
    const std::vector<Bytes> all = comm_.gatherToRoot(packParticles(mine));
    out.resize(0);
    if (comm_.rank() != 0) {
        return;
    }
    ParticleBatch every;
    for (const Bytes& message : all) {
        unpackParticles(message, every);
    }
    if (std::int64_t(every.size()) != total_) {
        throw SimulationError("the ranks hold " + std::to_string(every.size()) +
                              " particles in all, not the " + std::to_string(total_) +
                              " the run started with");
    }
    out.resize(every.size());
    const SphParams& params = local_->simulation().params();
    for (std::size_t k = 0; k < every.size(); ++k) {
        const std::size_t i = std::size_t(every.id[k]);
        if (i >= every.size()) {
            throw SimulationError("a rank sent particle id " + std::to_string(i) +
                                  ", past the run's " + std::to_string(total_));
        }
        out.x[i] = every.pos[k].x;
        out.y[i] = every.pos[k].y;
        out.z[i] = every.pos[k].z;
        out.vx[i] = every.vel[k].x;
        out.vy[i] = every.vel[k].y;
        out.vz[i] = every.vel[k].z;
        out.rho[i] = every.vel[k].w;
        out.p[i] = pressureFromDensity(params, every.vel[k].w);
    }
}

}  // namespace weir
