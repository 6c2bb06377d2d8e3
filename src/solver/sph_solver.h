// The SPH step as a short list of stages over one backend's primitives (CpuExec or CudaExec):
// grid build and reorder, density and pressure, force, integration with walls.
#pragma once

#include <algorithm>
#include <cstdlib>
#include <numeric>
#include <string>
#include <utility>

#include "core/check.h"
#include "grid/dense_grid.h"
#include "grid/neighbour_grid.h"
#include "physics/stages.h"
#include "solver/simulation.h"

namespace weir {

template <class Exec>
class SphSolver final : public Simulation {
   public:
    template <class T>
    using Buffer = typename Exec::template Buffer<T>;

    SphSolver(NeighbourMode mode, SimulationSetup setup)
        : mode_(mode),
          params_(setup.params),
          sparse_(mode == NeighbourMode::Grid ? setup.grid : GridSpec{}),
          dense_(denseGridSpec(setup.grid, denseReach(setup)), denseReach(setup)) {
        if (setup.particles.size() == 0 && !setup.seeds.empty()) {
            seed(setup.seeds);
        } else {
            const HostParticles& host = setup.particles;
            n_ = Index(host.size());
            std::vector<Real4> pos(n_), vel(n_);
            std::vector<Index> ids(n_);
            for (Index i = 0; i < n_; ++i) {
                pos[i] = {host.x[i], host.y[i], host.z[i], 0};
                vel[i] = {host.vx[i], host.vy[i], host.vz[i], 0};
                ids[i] = i;
            }
            exec_.upload(pos_, pos.data(), n_);
            exec_.upload(vel_, vel.data(), n_);
            exec_.upload(id_, ids.data(), n_);
        }
        if (mode_ != NeighbourMode::Dense) {
            acc_.resize(n_);  // the dense path fuses force and displacement
        }
        if (mode_ != NeighbourMode::Brute) {
            sortedPos_.resize(n_);
            sortedVel_.resize(n_);
            sortedId_.resize(n_);
        }
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
    // stages that choose dt and move the clock on (physics/time_step.h).
    void step() {
        switch (mode_) {
            case NeighbourMode::Grid:
                buildGrid();
                beginStep();
                computeDensityPressure(sparse_.view(), clock_.data());
                computeAcceleration(sparse_.view());
                break;
            case NeighbourMode::Dense:
                buildGrid();
                beginStep();
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

    void buildGrid() {
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
            dense_.build(exec_, pos, n_, [=] WEIR_HD(Index from, Index to) {
                newPos[to] = pos[from];
                newVel[to] = vel[from];
                newId[to] = id[from];
            });
            pos_.swap(sortedPos_);
            vel_.swap(sortedVel_);
            id_.swap(sortedId_);
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
            if (clock->dt != Real(0)) {
                accelerationAt(i, pv, nb, params);
            }
        });
        exec_.stageEnd("force");
    }

    // Force and displacement in one pass (dense path): timed as "force".
    template <class Neighbours>
    void accelerateAndIntegrate(const Neighbours& nb) {
        exec_.stageBegin("force");
        const ParticleView pv = view();
        const SphParams params = params_;
        const ObstacleView obstacles{boxes_.data(), int(boxes_.size()), spheres_.data(),
                                     int(spheres_.size())};
        FaultRecord* fault = fault_.data();
        StepClock* clock = clock_.data();
        Real4 *newPos = sortedPos_.data(), *newVel = sortedVel_.data();
        exec_.forEach(n_, [=] WEIR_HD(Index i) {
            accelerateAndIntegrateAt(i, pv, nb, params, obstacles, fault, clock, newPos, newVel);
        });
        pos_.swap(sortedPos_);
        vel_.swap(sortedVel_);
        exec_.stageEnd("force");
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
        return {pos_.data(), vel_.data(), acc_.data(), n_, walls};
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
            (id_.size() + sortedId_.size() + boundaryStart_.size()) * sizeof(Index) +
            boundaryPos_.size() * sizeof(Real4) + boundaryNear_.size();
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

    // Creates the particles of `seeds` on this backend, in the order of the host's seeding: per
    // lattice, in chunks, a keep flag per point, a prefix sum of the flags, and each kept point
    // written at its place. (Public only because CUDA lambdas need a public enclosing function.)
    void seed(const SceneSeeds& seeds) {
        n_ = Index(seeds.count);
        pos_.resize(std::size_t(n_));
        vel_.resize(std::size_t(n_));
        id_.resize(std::size_t(n_));
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
        constexpr std::int64_t kChunk = std::int64_t(1) << 26;
        Buffer<Index> kept;
        Index placed = 0;
        Real4 *pos = pos_.data(), *vel = vel_.data();
        Index* id = id_.data();
        for (const SeedLattice& lattice : seeds.lattices) {
            for (std::int64_t start = 0; start < lattice.points(); start += kChunk) {
                const Index count = Index(std::min(kChunk, lattice.points() - start));
                kept.resize(std::size_t(std::min(kChunk, lattice.points())));
                Index* flag = kept.data();
                exec_.forEach(count, [=] WEIR_HD(Index k) {
                    flag[k] = keepSeed(shapes, lattice, lattice.point(start + k)) ? 1 : 0;
                });
                exec_.inclusiveScan(flag, flag, count);
                const Index base = placed;
                const Index limit = n_;
                exec_.forEach(count, [=] WEIR_HD(Index k) {
                    const Index before = k > 0 ? flag[k - 1] : 0;
                    const Index at = base + before;
                    if (flag[k] > before && at < limit) {
                        const Vec3d p = lattice.point(start + k);
                        pos[at] = {Real(p.x), Real(p.y), Real(p.z), 0};
                        vel[at] = {Real(lattice.velocity.x), Real(lattice.velocity.y),
                                   Real(lattice.velocity.z), 0};
                        id[at] = at;
                    }
                });
                placed += exec_.readOne(kept, std::size_t(count - 1));
            }
        }
        if (placed != n_) {
            throw SimulationError("seeding placed " + std::to_string(placed) +
                                  " particles where the host counted " + std::to_string(n_));
        }
    }

   private:
    // Cells per smoothing radius of the dense table (1 where even the grid of h cells is too big
    // for it: the dense table is then unused).
    static int denseReach(const SimulationSetup& setup) {
        return std::max(1, denseCellsPerRadius(setup.grid, setup.particleCount()));
    }

    static constexpr double kNoTarget = 1e300;
    mutable Exec exec_;  // mutable: reading the device clock back is not a change
    NeighbourMode mode_;
    SphParams params_;
    NeighbourGrid<Exec> sparse_;
    DenseGrid<Exec> dense_;
    Index n_ = 0;
    long long calls_ = 0;     // step() calls, no-op steps included (graph parity)
    double typicalStep_ = 0;  // mean dt of the last batch, to size the next
    bool targetSet_ = false;
    Buffer<Real4> pos_, vel_, acc_, sortedPos_, sortedVel_;
    Buffer<Index> id_, sortedId_;
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
};

}  // namespace weir
