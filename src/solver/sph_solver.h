// The SPH step as a short list of stages over one backend's primitives (CpuExec or CudaExec):
// grid build and reorder, density and pressure, force, integration with walls.
#pragma once

#include <algorithm>
#include <cstdlib>
#include <numeric>
#include <string>
#include <type_traits>
#include <utility>

#include "cluster/slab.h"
#include "core/atomics.h"
#include "core/check.h"
#include "grid/dense_grid.h"
#include "grid/neighbour_grid.h"
#include "physics/stages.h"
#include "solver/simulation.h"

namespace weir {

template <class Exec>
class SphSolver final : public RankPart {
   public:
    template <class T>
    using Buffer = typename Exec::template Buffer<T>;

    SphSolver(NeighbourMode mode, SimulationSetup setup)
        : mode_(mode),
          params_(setup.params),
          sparse_(mode == NeighbourMode::Grid ? setup.grid : GridSpec{}),
          dense_(denseGridSpec(setup.grid, denseReach(setup)), denseReach(setup)),
          denseFull_(denseGridSpec(setup.grid, denseReach(setup))) {
        if (setup.particles.size() == 0 && !setup.seeds.empty()) {
            seed(setup.seeds, setup.share);
        } else {
            const HostParticles& host = setup.particles;
            n_ = Index(host.size());
            std::vector<Real4> pos(n_), vel(n_);
            std::vector<Index> ids(n_);
            for (Index i = 0; i < n_; ++i) {
                pos[i] = {host.x[i], host.y[i], host.z[i], 0};
                vel[i] = {host.vx[i], host.vy[i], host.vz[i], 0};
                ids[i] = setup.particleIds.empty() ? i : setup.particleIds[std::size_t(i)];
            }
            exec_.upload(pos_, pos.data(), n_);
            exec_.upload(vel_, vel.data(), n_);
            exec_.upload(id_, ids.data(), n_);
        }
        fitScratch();
        const BoundaryParticles& walls = setup.boundary;
        if (walls.size() > 0) {
            exec_.upload(boundaryPos_, walls.pos.data(), walls.pos.size());
            exec_.upload(boundaryStart_, walls.cellStart.data(), walls.cellStart.size());
            exec_.upload(boundaryNear_, walls.near.data(), walls.near.size());
            boundary_.origin = walls.origin;
            boundary_.invCellSize = Real(1) / walls.cellSize;
            boundary_.nx = walls.dims[0];
            boundary_.ny = walls.dims[1];
            boundary_.nz = walls.dims[2];
            boundary_.count = Index(walls.size());
        }
        exec_.upload(boxes_, setup.obstacleBoxes.data(), setup.obstacleBoxes.size());
        exec_.upload(spheres_, setup.obstacleSpheres.data(), setup.obstacleSpheres.size());
        FaultRecord none{0, 0, 0, 0.0f, 0.0f};
        exec_.upload(fault_, &none, 1);
        // The first step's dt sees the initial speeds and gravity (the lattice starts in balance).
        double maxSpeed2 = 0;
        const HostParticles& host = setup.particles;
        for (std::size_t i = 0; i < host.size(); ++i) {
            maxSpeed2 = std::max(maxSpeed2, double(host.vx[i]) * host.vx[i] +
                                                double(host.vy[i]) * host.vy[i] +
                                                double(host.vz[i]) * host.vz[i]);
        }
        for (const SeedLattice& lattice : setup.seeds.lattices) {  // particles seeded here
            maxSpeed2 = std::max(maxSpeed2, lengthSquared(lattice.velocity));
        }
        StepClock clock{};
        clock.time = 0;
        clock.target = kNoTarget;
        clock.maxSpeed2 = floatBits(float(maxSpeed2));
        clock.maxAccel2 = floatBits(float(lengthSquared(params_.gravity)));
        exec_.upload(clock_, &clock, 1);
        typicalStep_ = double(params_.timeStep);
    }

    // Steps until the clock reaches `target`: batches of the steps the last batches' mean dt
    // predicts, the clock read back after each (one host round trip per batch, not per step).
    // Steps past the target inside a batch are no-ops that cost only the grid build.
    void advanceTo(double target) override {
        StepClock clock = exec_.readOne(clock_, 0);
        clock.target = target;
        exec_.writeOne(clock_, 0, clock);
        targetSet_ = true;
        while (clock.time < target) {
            const double wanted = std::ceil((target - clock.time) / typicalStep_ - 1e-6);
            const int batch = int(std::clamp(wanted, 1.0, 1e6));
            const double before = clock.time;
            const int stepsBefore = clock.step;
            advanceSteps(batch);
            clock = exec_.readOne(clock_, 0);
            if (exec_.readOne(fault_, 0).code != 0 || !(clock.time > before)) {
                break;  // blown up (reported by fault()), or a step that cannot advance
            }
            if (!clock.landing || clock.step - stepsBefore > 1) {
                typicalStep_ = (clock.time - before) / double(clock.step - stepsBefore);
            }
        }
    }

    void advance(int steps) override {
        if (targetSet_) {  // plain steps: no output time to stop on
            StepClock clock = exec_.readOne(clock_, 0);
            clock.target = kNoTarget;
            exec_.writeOne(clock_, 0, clock);
            targetSet_ = false;
        }
        advanceSteps(steps);
    }

    void advanceSteps(int steps) {
        if constexpr (Exec::isDevice) {
            // With no host round trip inside a step, a pair of steps replays as one CUDA graph.
            if (mode_ != NeighbourMode::Grid && !exec_.timing && steps >= 4) {
                if (!graph_.ready()) {
                    step();  // allocates every buffer: a capture cannot allocate
                    --steps;
                    graphParity_ = int(calls_ & 1);
                    exec_.capture(graph_, [&] {
                        step();
                        step();
                    });
                    calls_ -= 2;  // capturing does not run the steps
                }
                if (int(calls_ & 1) != graphParity_) {  // the graph holds buffer swaps of a pair
                    step();
                    --steps;
                }
                for (; steps >= 2; steps -= 2) {
                    exec_.launch(graph_);
                    calls_ += 2;
                }
            }
        }
        for (; steps > 0; --steps) {
            step();
        }
    }

    void computeDensity() override {
        switch (mode_) {
            case NeighbourMode::Grid:
                buildGrid();
                computeDensityPressure(sparse_.view());
                break;
            case NeighbourMode::Dense:
                buildGrid();
                computeDensityPressure(denseView());
                break;
            default:
                computeDensityPressure(BruteNeighbours{n_});
        }
    }

    // One step, paper §5-6: separate stages launched in sequence, bracketed by the one-thread
    // stages that choose dt and move the clock on (physics/time_step.h; the dense path runs the
    // first inside its grid build).
    void step() {
        switch (mode_) {
            case NeighbourMode::Grid:
                buildGrid();
                beginStep();
                computeDensityPressure(sparse_.view(), clock_.data());
                computeAcceleration(sparse_.view());
                break;
            case NeighbourMode::Dense:
                buildGrid(true);  // begins the step in its first pass: one launch fewer
                computeDensityPressure(denseView(), clock_.data());
                accelerateAndIntegrate(denseView());
                break;
            default:
                beginStep();
                computeDensityPressure(BruteNeighbours{n_}, clock_.data());
                computeAcceleration(BruteNeighbours{n_});
        }
        if (mode_ != NeighbourMode::Dense) {
            integrate();
        }
        endStep();
        ++calls_;
        if (exec_.timing) {
            exec_.collectTimes(times_);
        }
    }

    void runStage(Stage stage) override {
        switch (stage) {
            case Stage::Grid:
                if (mode_ != NeighbourMode::Brute) {
                    buildGrid();
                }
                break;
            case Stage::Density:
                withNeighbours([&](const auto& nb) { computeDensityPressure(nb); });
                break;
            case Stage::Force:
                if (mode_ == NeighbourMode::Dense) {
                    accelerateAndIntegrate(denseView());
                } else {
                    withNeighbours([&](const auto& nb) { computeAcceleration(nb); });
                }
                break;
            case Stage::Integrate:
                if (mode_ != NeighbourMode::Dense) {
                    integrate();
                }
                break;
        }
    }

    DenseGridNeighbours denseView() const { return dense_.view(pos_.data(), params_.kernel.h); }

    template <class F>
    void withNeighbours(F&& f) {
        switch (mode_) {
            case NeighbourMode::Grid:
                f(sparse_.view());
                break;
            case NeighbourMode::Dense:
                f(denseView());
                break;
            default:
                f(BruteNeighbours{n_});
        }
    }

    // beginsStep: the dense build also runs beginStep() (in a pass it makes anyway).
    void buildGrid(bool beginsStep = false) {
        exec_.stageBegin("grid");
        if (mode_ == NeighbourMode::Grid) {
            sparse_.build(exec_, pos_.data(), n_);
            reorderByCell(sparse_.permutation());
        } else {
            // The counting sort places each particle's data as it finds its place: no separate
            // reorder pass.
            const Real4 *pos = pos_.data(), *vel = vel_.data();
            const Index* id = id_.data();
            Real4 *newPos = sortedPos_.data(), *newVel = sortedVel_.data();
            Index* newId = sortedId_.data();
            // A distributed run's rank also drops last step's ghosts and the particles that
            // left its slab (handed over already), and arriving ghosts become this step's.
            const bool distributed = distributed_;
            const Slab share = share_;
            StepClock* clock = beginsStep ? clock_.data() : nullptr;
            const SphParams params = params_;
            dense_.build(
                exec_, pos, n_,
                [=] WEIR_HD(Index from, Index to) {
                    Real4 p = pos[from];
                    p.w = p.w == kArrivingGhostMark ? kGhostMark : p.w;
                    newPos[to] = p;
                    newVel[to] = vel[from];
                    newId[to] = id[from];
                },
                [=] WEIR_HD(Index i) {
                    return distributed &&
                           (pos[i].w == kGhostMark ||
                            (pos[i].w == Real(0) && !share.contains(share.coordinate(pos[i]))));
                },
                [=] WEIR_HD() {
                    if (clock != nullptr) {
                        weir::beginStep(*clock, params);
                    }
                });
            pos_.swap(sortedPos_);
            vel_.swap(sortedVel_);
            id_.swap(sortedId_);
            if (distributed) {
                // Known on the host (no round trip that would stall the step's launches).
                n_ -= discardPending_;
                heldGhosts_ = arrivingGhosts_;
                arrivingGhosts_ = 0;
                discardPending_ = 0;
                // Checked where reading the count back costs nothing (CPU) or in debug builds.
#ifdef NDEBUG
                constexpr bool check = !Exec::isDevice;
#else
                constexpr bool check = true;
#endif
                if constexpr (check) {
                    const Index kept = dense_.keptCount(exec_);
                    WEIR_REQUIRE(n_ == kept,
                                 "the grid build kept " << kept << " particles, not " << n_);
                }
            }
        }
        exec_.stageEnd("grid");
    }

    // Gathers every particle attribute into cell order, so that neighbours sit close in memory.
    void reorderByCell(const Index* order) {
        const Real4 *pos = pos_.data(), *vel = vel_.data();
        const Index* id = id_.data();
        Real4 *newPos = sortedPos_.data(), *newVel = sortedVel_.data();
        Index* newId = sortedId_.data();
        exec_.forEach(n_, [=] WEIR_HD(Index i) {
            const Index from = order[i];
            newPos[i] = pos[from];
            newVel[i] = vel[from];
            newId[i] = id[from];
        });
        pos_.swap(sortedPos_);
        vel_.swap(sortedVel_);
        id_.swap(sortedId_);
    }

    void beginStep() {
        StepClock* clock = clock_.data();
        const SphParams params = params_;
        exec_.forEach(1, [=] WEIR_HD(Index) { weir::beginStep(*clock, params); });
    }
    void endStep() {
        StepClock* clock = clock_.data();
        exec_.forEach(1, [=] WEIR_HD(Index) { weir::endStep(*clock); });
    }

    // Density of every particle; skipped in a no-op step when `clock` is given.
    template <class Neighbours>
    void computeDensityPressure(const Neighbours& nb, const StepClock* clock = nullptr) {
        exec_.stageBegin("density");
        const ParticleView pv = view();
        const SphParams params = params_;
        exec_.forEach(n_, [=] WEIR_HD(Index i) {
            if (clock == nullptr || clock->dt != Real(0)) {
                densityPressureAt(i, pv, nb, params);
            }
        });
        exec_.stageEnd("density");
    }

    template <class Neighbours>
    void computeAcceleration(const Neighbours& nb) {
        exec_.stageBegin("force");
        const ParticleView pv = view();
        const SphParams params = params_;
        const StepClock* clock = clock_.data();
        exec_.forEach(n_, [=] WEIR_HD(Index i) {
            if (clock->dt != Real(0) && !isGhost(pv.pos[i])) {
                accelerationAt(i, pv, nb, params);
            }
        });
        exec_.stageEnd("force");
    }

    // Force and displacement in one pass (dense path): timed as "force".
    template <class Neighbours>
    void accelerateAndIntegrate(const Neighbours& nb) {
        exec_.stageBegin("force");
        if constexpr (teamsFit<Neighbours>()) {
            if (teamSize() == 2) {
                accelerateAndIntegratePass<2>(nb);
            } else {
                accelerateAndIntegratePass<1>(nb);
            }
        } else {
            accelerateAndIntegratePass<1>(nb);
        }
        pos_.swap(sortedPos_);
        vel_.swap(sortedVel_);
        exec_.stageEnd("force");
    }

    template <int TeamSize, class Neighbours>
    void accelerateAndIntegratePass(const Neighbours& nb) {
        const ParticleView pv = view();
        const SphParams params = params_;
        const ObstacleView obstacles{boxes_.data(), int(boxes_.size()), spheres_.data(),
                                     int(spheres_.size())};
        FaultRecord* fault = fault_.data();
        StepClock* clock = clock_.data();
        Real4 *newPos = sortedPos_.data(), *newVel = sortedVel_.data();
        exec_.template forEachTeam<TeamSize>(n_, [=] WEIR_HD(Index i, Team<TeamSize> team) {
            accelerateAndIntegrateAt(i, pv, nb, params, obstacles, fault, clock, newPos, newVel,
                                     team);
        });
    }

    void integrate() {
        exec_.stageBegin("integrate");
        const ParticleView pv = view();
        const SphParams params = params_;
        const ObstacleView obstacles{boxes_.data(), int(boxes_.size()), spheres_.data(),
                                     int(spheres_.size())};
        FaultRecord* fault = fault_.data();
        StepClock* clock = clock_.data();
        // The step number and dt live on the device, so a replayed graph uses the right ones.
        exec_.forEach(n_, [=] WEIR_HD(Index i) {
            if (clock->dt != Real(0)) {
                integrateAt(i, pv, params, obstacles, fault, clock);
            }
        });
        exec_.stageEnd("integrate");
    }

    ParticleView view() {
        BoundaryView walls = boundary_;
        walls.pos = boundaryPos_.data();
        walls.cellStart = boundaryStart_.data();
        walls.near = boundaryNear_.data();
        return {pos_.data(), vel_.data(), acc_.data(), pressureTerm_.data(), n_, walls};
    }

    void download(HostParticles& out) override {
        out.resize(n_);
        std::vector<Index> ids(n_);
        std::vector<Real4> pos(n_), vel(n_);
        exec_.download(id_, ids.data(), n_);
        exec_.download(pos_, pos.data(), n_);
        exec_.download(vel_, vel.data(), n_);
        for (Index i = 0; i < n_; ++i) {
            const Index k = ids[i];
            out.x[k] = pos[i].x;
            out.y[k] = pos[i].y;
            out.z[k] = pos[i].z;
            out.vx[k] = vel[i].x;
            out.vy[k] = vel[i].y;
            out.vz[k] = vel[i].z;
            out.rho[k] = vel[i].w;
            out.p[k] = pressureFromDensity(params_, vel[i].w);
        }
    }

    FaultRecord fault() override { return exec_.readOne(fault_, 0); }
    void synchronize() override { exec_.synchronize(); }

    void setTiming(bool on) override { exec_.timing = on; }
    const StageTimes& stageTimes() const override { return times_; }
    void clearStageTimes() override { times_.clear(); }

    Backend backend() const override { return Exec::isDevice ? Backend::Cuda : Backend::Cpu; }
    NeighbourMode neighbourMode() const override { return mode_; }
    std::string deviceName() const override { return exec_.deviceName(); }
    std::size_t bytesHeld() const override {
        std::size_t bytes =
            (pos_.size() + vel_.size() + acc_.size() + sortedPos_.size() + sortedVel_.size()) *
                sizeof(Real4) +
            pressureTerm_.size() * sizeof(Real) +
            (id_.size() + sortedId_.size() + boundaryStart_.size()) * sizeof(Index) +
            boundaryPos_.size() * sizeof(Real4) + boundaryNear_.size() +
            // distributed runs only: selection flags and particles staged for other ranks
            (flags_.size() + stageId_.size() + binCounts_.size()) * sizeof(Index) +
            (stagePos_.size() + stageVel_.size()) * sizeof(Real4);
        return bytes + (mode_ == NeighbourMode::Grid ? sparse_.bytesHeld() : 0) +
               (mode_ == NeighbourMode::Dense ? dense_.bytesHeld() : 0);
    }
    Index occupiedCells() const override {
        return mode_ == NeighbourMode::Grid ? sparse_.numCells() : 0;
    }
    const SphParams& params() const override { return params_; }
    Index particleCount() const override { return n_; }
    long long stepCount() const override { return exec_.readOne(clock_, 0).step; }
    double time() const override { return exec_.readOne(clock_, 0).time; }

    // Creates the particles of `seeds` inside `share` on this backend, in the order of the host's
    // seeding, with their index in that order as id: per lattice, in chunks, a keep flag per
    // point and a prefix sum of the flags (the global order), a second flag and sum for the
    // points in the share (their place here), and each kept point written at its place. A first
    // pass counts the share. (Public only because CUDA lambdas need a public enclosing function.)
    void seed(const SceneSeeds& seeds, const Slab& share) {
        Buffer<Box> fluidBoxes, obstacleBoxes;
        Buffer<SphereShape> fluidSpheres, obstacleSpheres;
        exec_.upload(fluidBoxes, seeds.fluidBoxes.data(), seeds.fluidBoxes.size());
        exec_.upload(obstacleBoxes, seeds.obstacleBoxes.data(), seeds.obstacleBoxes.size());
        exec_.upload(fluidSpheres, seeds.fluidSpheres.data(), seeds.fluidSpheres.size());
        exec_.upload(obstacleSpheres, seeds.obstacleSpheres.data(), seeds.obstacleSpheres.size());
        const SeedShapes shapes{fluidBoxes.data(),      int(fluidBoxes.size()),
                                fluidSpheres.data(),    int(fluidSpheres.size()),
                                obstacleBoxes.data(),   int(obstacleBoxes.size()),
                                obstacleSpheres.data(), int(obstacleSpheres.size())};
        const bool whole = share.everything();
        constexpr std::int64_t kChunk = std::int64_t(1) << 26;
        Buffer<Index> kept, mine;
        Index placed = 0, counted = 0;
        for (int pass = whole ? 1 : 0; pass < 2; ++pass) {
            if (pass == 1) {
                n_ = whole ? Index(seeds.count) : counted;
                // A share gets ghosts and arrivals every step: room for them from the start,
                // so that the arrays need not grow (and be held twice) later.
                const std::size_t room = std::size_t(n_) + (whole ? 0 : std::size_t(n_) / 8);
                for (std::size_t size : {room, std::size_t(n_)}) {
                    pos_.resize(size);
                    vel_.resize(size);
                    id_.resize(size);
                }
            }
            Real4 *pos = pos_.data(), *vel = vel_.data();
            Index* id = id_.data();
            Index global = 0;
            placed = 0;
            for (const SeedLattice& lattice : seeds.lattices) {
                for (std::int64_t start = 0; start < lattice.points(); start += kChunk) {
                    const Index count = Index(std::min(kChunk, lattice.points() - start));
                    kept.resize(std::size_t(std::min(kChunk, lattice.points())));
                    mine.resize(whole ? 0 : kept.size());
                    Index* flag = kept.data();
                    Index* local = whole ? flag : mine.data();
                    exec_.forEach(count, [=] WEIR_HD(Index k) {
                        const Vec3d p = lattice.point(start + k);
                        const bool keep = keepSeed(shapes, lattice, p);
                        flag[k] = keep ? 1 : 0;
                        if (!whole) {
                            local[k] = keep && share.contains(share.coordinate(p)) ? 1 : 0;
                        }
                    });
                    if (pass == 0) {
                        exec_.inclusiveScan(local, local, count);
                        counted += exec_.readOne(mine, std::size_t(count - 1));
                        continue;
                    }
                    exec_.inclusiveScan(flag, flag, count);
                    if (!whole) {
                        exec_.inclusiveScan(local, local, count);
                    }
                    const Index globalBase = global, localBase = placed, limit = n_;
                    exec_.forEach(count, [=] WEIR_HD(Index k) {
                        const Index before = k > 0 ? local[k - 1] : 0;
                        const Index at = localBase + before;
                        if (local[k] > before && at < limit) {
                            const Vec3d p = lattice.point(start + k);
                            pos[at] = {Real(p.x), Real(p.y), Real(p.z), 0};
                            vel[at] = {Real(lattice.velocity.x), Real(lattice.velocity.y),
                                       Real(lattice.velocity.z), 0};
                            id[at] = globalBase + (k > 0 ? flag[k - 1] : 0);
                        }
                    });
                    global += exec_.readOne(kept, std::size_t(count - 1));
                    placed += whole ? exec_.readOne(kept, std::size_t(count - 1))
                                    : exec_.readOne(mine, std::size_t(count - 1));
                }
            }
            if (pass == 1 && global != Index(seeds.count)) {
                throw SimulationError("seeding placed " + std::to_string(global) +
                                      " particles where the host counted " +
                                      std::to_string(seeds.count));
            }
        }
        if (placed != n_) {
            throw SimulationError("seeding placed " + std::to_string(placed) +
                                  " particles where the count pass found " + std::to_string(n_));
        }
    }

    // ---- Distributed runs (cluster/): one rank's share, exchanged between steps ----

    // Drops the ghost copies and takes out the owned particles outside `share` (into `leaving`).
    void takeLeavers(const Slab& share, ParticleBatch& leaving) override {
        if (mode_ == NeighbourMode::Dense) {
            // The next grid build drops the ghosts and leavers: only copy the leavers out.
            distributed_ = true;
            share_ = share;
            const Index n = n_;
            flags_.resize(std::size_t(n));
            Index* leave = flags_.data();
            const Real4* pos = pos_.data();
            exec_.forEach(n, [=] WEIR_HD(Index i) {
                leave[i] = !isGhost(pos[i]) && !share.contains(share.coordinate(pos[i])) ? 1 : 0;
            });
            discardPending_ = heldGhosts_ + gather(leave, leaving);
            return;
        }
        const Index n = n_;
        flags_.resize(std::size_t(n) * 2);
        Index *stay = flags_.data(), *leave = flags_.data() + n;
        const Real4* pos = pos_.data();
        exec_.forEach(n, [=] WEIR_HD(Index i) {
            const bool owned = !isGhost(pos[i]);
            const bool inside = share.contains(share.coordinate(pos[i]));
            stay[i] = owned && inside ? 1 : 0;
            leave[i] = owned && !inside ? 1 : 0;
        });
        const Index stays = compactInto(stay, sortedPos_, sortedVel_, sortedId_, 0);
        gather(leave, leaving);
        pos_.swap(sortedPos_);
        vel_.swap(sortedVel_);
        id_.swap(sortedId_);
        n_ = stays;
        fitScratch();
    }

    // Copies of the owned particles within `width` of the borders of `share`, onto the host.
    void copyBorderParticles(const Slab& share, double width, ParticleBatch& out) override {
        const Index n = n_;
        flags_.resize(std::size_t(n));
        Index* near = flags_.data();
        const Real4* pos = pos_.data();
        exec_.forEach(n, [=] WEIR_HD(Index i) {
            const Real c = share.coordinate(pos[i]);
            near[i] = !isGhost(pos[i]) && share.contains(c) && share.nearBorder(c, width) ? 1 : 0;
        });
        gather(near, out);
    }

    // Appends particles: arrivals (owned) or ghost copies (pos.w = kArrivingGhostMark).
    void append(const ParticleBatch& batch) override {
        const Index m = Index(batch.size());
        if (m == 0) {
            return;
        }
        const std::size_t total = std::size_t(n_) + std::size_t(m);
        growKeeping(pos_, total);
        growKeeping(vel_, total);
        growKeeping(id_, total);
        exec_.uploadAtAsync(pos_, std::size_t(n_), batch.pos.data(), std::size_t(m));
        exec_.uploadAtAsync(vel_, std::size_t(n_), batch.vel.data(), std::size_t(m));
        exec_.uploadAtAsync(id_, std::size_t(n_), batch.id.data(), std::size_t(m));
        exec_.synchronize();  // one wait for the three
        for (const Real4& p : batch.pos) {
            arrivingGhosts_ += isGhost(p) ? 1 : 0;
        }
        n_ = Index(total);
        fitScratch();
    }

    // The owned particles (ghosts left out), in the current order.
    void downloadOwned(ParticleBatch& out) override {
        const Index n = n_;
        flags_.resize(std::size_t(n));
        Index* owned = flags_.data();
        const Real4* pos = pos_.data();
        exec_.forEach(n, [=] WEIR_HD(Index i) { owned[i] = isGhost(pos[i]) ? 0 : 1; });
        gather(owned, out);
    }

    // counts[b] += owned particles with coordinate in [lo + b w, lo + (b + 1) w) along `axis`
    // (clamped into the first and last bins).
    void histogram(int axis, double lo, double binWidth, std::vector<Index>& counts) override {
        const Index bins = Index(counts.size());
        binCounts_.resize(std::size_t(bins));  // kept: no allocation per rebalance check
        Index* b = binCounts_.data();
        exec_.forEach(bins, [=] WEIR_HD(Index k) { b[k] = 0; });
        const Real4* pos = pos_.data();
        const Slab along{axis, 0, 0};
        const double inverse = 1.0 / binWidth;
        exec_.forEach(n_, [=] WEIR_HD(Index i) {
            if (!isGhost(pos[i])) {
                const double at = (double(along.coordinate(pos[i])) - lo) * inverse;
                const Index k = at < 0 ? 0 : (at >= double(bins) ? bins - 1 : Index(at));
                atomicFetchAdd(&b[k], Index(1));
            }
        });
        std::vector<Index> here(static_cast<std::size_t>(bins));
        exec_.download(binCounts_, here.data(), here.size());
        for (std::size_t k = 0; k < counts.size(); ++k) {
            counts[k] += here[k];
        }
    }

    ParticleSpans stageWindows(const Slab& share, const std::vector<Slab>& windows,
                               std::vector<std::int64_t>& counts) override {
        counts.assign(windows.size(), 0);
        Index staged = 0;
        for (std::size_t k = 0; k < windows.size(); ++k) {
            const Index n = n_;
            flags_.resize(std::size_t(n));
            Index* inside = flags_.data();
            const Real4* pos = pos_.data();
            const Slab window = windows[k];
            exec_.forEach(n, [=] WEIR_HD(Index i) {
                const Real c = window.coordinate(pos[i]);
                inside[i] = !isGhost(pos[i]) && share.contains(c) && window.contains(c) ? 1 : 0;
            });
            const Index count = compactInto(inside, stagePos_, stageVel_, stageId_, staged);
            Real4* marked = stagePos_.data() + staged;
            exec_.forEach(count, [=] WEIR_HD(Index i) { marked[i].w = kArrivingGhostMark; });
            counts[k] = count;
            staged += count;
        }
        return {stagePos_.data(), stageVel_.data(), stageId_.data()};
    }

    ParticleSpans appendSpace(std::size_t count) override {
        const std::size_t at = std::size_t(n_), total = at + count;
        arrivingGhosts_ += Index(count);
        growKeeping(pos_, total);
        growKeeping(vel_, total);
        growKeeping(id_, total);
        n_ = Index(total);
        fitScratch();
        return {pos_.data() + at, vel_.data() + at, id_.data() + at};
    }

    void* deviceStream() override {
        if constexpr (Exec::isDevice) {
            return static_cast<void*>(exec_.stream());
        } else {
            return nullptr;
        }
    }

    // The dense table over the cells of `share` widened by `margin` only (particles outside are
    // clamped into its end cells, still found), so a rank's table grows with its share, not
    // with the whole domain. The paper's grid keeps the whole domain.
    void restrictGrid(const Slab& share, double margin) override {
        if (mode_ == NeighbourMode::Dense) {
            dense_.setSpec(sliceOf(denseFull_, share.axis, share.lo - margin, share.hi + margin));
        }
    }

    StepClock clock() override { return exec_.readOne(clock_, 0); }
    StepClock clockAndFault(FaultRecord& fault) override {
        StepClock clock;
        exec_.downloadFromAsync(clock_, 0, &clock, 1);
        exec_.downloadFromAsync(fault_, 0, &fault, 1);
        exec_.synchronize();
        return clock;
    }
    void setClock(const StepClock& clock) override { exec_.writeOne(clock_, 0, clock); }
    void stepOnce() override { step(); }

    // Moves the particles whose flag is 1 into (pos, vel, id) from `offset` on, in order; returns
    // how many. Turns `flag` into its prefix sum.
    Index compactInto(Index* flag, Buffer<Real4>& toPos, Buffer<Real4>& toVel, Buffer<Index>& toId,
                      Index offset) {
        const Index n = n_;
        if (n == 0) {
            return 0;
        }
        exec_.inclusiveScan(flag, flag, n);
        const Index count = exec_.readOne(flags_, std::size_t(flag - flags_.data()) + n - 1);
        growKeeping(toPos, std::size_t(offset + count));
        growKeeping(toVel, std::size_t(offset + count));
        growKeeping(toId, std::size_t(offset + count));
        const Real4 *pos = pos_.data(), *vel = vel_.data();
        const Index* id = id_.data();
        Real4 *outPos = toPos.data(), *outVel = toVel.data();
        Index* outId = toId.data();
        exec_.forEach(n, [=] WEIR_HD(Index i) {
            const Index before = i > 0 ? flag[i - 1] : 0;
            if (flag[i] > before) {
                outPos[offset + before] = pos[i];
                outVel[offset + before] = vel[i];
                outId[offset + before] = id[i];
            }
        });
        return count;
    }

    // Copies the particles whose flag is 1 to the host, appended to `out`; returns how many.
    Index gather(Index* flag, ParticleBatch& out) {
        const Index count = compactInto(flag, stagePos_, stageVel_, stageId_, 0);
        const std::size_t at = out.size();
        out.resize(at + std::size_t(count));
        exec_.downloadFromAsync(stagePos_, 0, out.pos.data() + at, std::size_t(count));
        exec_.downloadFromAsync(stageVel_, 0, out.vel.data() + at, std::size_t(count));
        exec_.downloadFromAsync(stageId_, 0, out.id.data() + at, std::size_t(count));
        exec_.synchronize();  // one wait for the three
        return count;
    }

    // Resizes `buffer` to n elements keeping its first min(size, n) (a quarter spare on growth).
    template <class T>
    void growKeeping(Buffer<T>& buffer, std::size_t n) {
        if (n <= buffer.capacity()) {
            buffer.resize(n);
            return;
        }
        Buffer<T> bigger;
        bigger.resize(n + n / 16);  // both held while copying: spare little at a billion
        const T* from = buffer.data();
        T* to = bigger.data();
        exec_.forEach(Index(buffer.size()), [=] WEIR_HD(Index i) { to[i] = from[i]; });
        bigger.resize(n);
        buffer.swap(bigger);
    }

    // Sizes the scratch arrays of the step to the particle count.
    void fitScratch() {
        pressureTerm_.resize(std::size_t(n_));
        if (mode_ != NeighbourMode::Dense) {
            acc_.resize(std::size_t(n_));  // the dense path fuses force and displacement
        }
        if (mode_ == NeighbourMode::Brute) {
            return;  // no reordering (a distributed run's compaction sizes them as it needs)
        }
        sortedPos_.resize(std::size_t(n_));
        sortedVel_.resize(std::size_t(n_));
        sortedId_.resize(std::size_t(n_));
    }

   private:
    // Cells per smoothing radius of the dense table (1 where even the grid of h cells is too big
    // for it: the dense table is then unused).
    static int denseReach(const SimulationSetup& setup) {
        return std::max(1, denseCellsPerRadius(setup.grid, setup.particleCount()));
    }

    // Lanes per particle in the dense path's force pass on the GPU (core/team.h): two where one
    // thread per particle would leave the GPU half idle (at most half its resident threads;
    // bench/NOTES.md #12), else one. WEIR_TEAM=1 or 2 sets it (speed experiments). The paper's
    // grid and brute force keep one thread per particle.
    int teamSize() const {
        if (teamOverride_ > 0) {
            return teamOverride_;
        }
        return 2 * std::int64_t(n_) <= exec_.residentThreads() ? 2 : 1;
    }

    // Teams serve the dense path on the GPU; elsewhere a thread works alone.
    template <class Neighbours>
    static constexpr bool teamsFit() {
        return Exec::isDevice && std::is_same_v<Neighbours, DenseGridNeighbours>;
    }

    static int teamOverride() {
        const char* text = std::getenv("WEIR_TEAM");
        const int wanted = text != nullptr ? std::atoi(text) : 0;
        return wanted >= 2 ? 2 : (wanted == 1 ? 1 : 0);
    }

    static constexpr double kNoTarget = 1e300;
    mutable Exec exec_;  // mutable: reading the device clock back is not a change
    NeighbourMode mode_;
    SphParams params_;
    NeighbourGrid<Exec> sparse_;
    DenseGrid<Exec> dense_;
    GridSpec denseFull_;        // the dense table's cells over the whole container
    bool distributed_ = false;  // one rank's part: the dense build drops ghosts and leavers
    Slab share_;                // that rank's slab
    Index heldGhosts_ = 0;      // ghosts of this step (mark 1)
    Index arrivingGhosts_ = 0;  // ghosts appended for the next step (mark 2)
    Index discardPending_ = 0;  // particles the next dense build drops: ghosts and leavers
    Index n_ = 0;
    long long calls_ = 0;     // step() calls, no-op steps included (graph parity)
    double typicalStep_ = 0;  // mean dt of the last batch, to size the next
    bool targetSet_ = false;
    Buffer<Real4> pos_, vel_, acc_, sortedPos_, sortedVel_;
    Buffer<Real> pressureTerm_;  // the density stage's pressureTermOf, for the force stage
    Buffer<Index> id_, sortedId_;
    Buffer<Index> flags_;                // distributed runs: selection flags and their sums
    Buffer<Real4> stagePos_, stageVel_;  // distributed runs: particles on their way to the host
    Buffer<Index> stageId_;
    Buffer<Index> binCounts_;  // distributed runs: histogram along the decomposition axis
    Buffer<ObstacleBox> boxes_;
    Buffer<ObstacleSphere> spheres_;
    Buffer<FaultRecord> fault_;
    Buffer<StepClock> clock_;
    BoundaryView boundary_;  // geometry of the static wall grid; pointers filled by view()
    Buffer<Real4> boundaryPos_;
    Buffer<Index> boundaryStart_;
    Buffer<unsigned char> boundaryNear_;
    typename Exec::Graph graph_;
    int graphParity_ = 0;
    StageTimes times_;
    int teamOverride_ = teamOverride();  // 0: chosen by size
};

}  // namespace weir
