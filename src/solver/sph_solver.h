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
        exec_.upload(boxes_, setup.obstacleBoxes.data(), setup.obstacleBoxes.size());
        exec_.upload(spheres_, setup.obstacleSpheres.data(), setup.obstacleSpheres.size());
        FaultRecord none{0, 0, 0, 0.0f};
        exec_.upload(fault_, &none, 1);
        int zero = 0;
        exec_.upload(stepCounter_, &zero, 1);
    }

    void advance(int steps) override {
        if constexpr (Exec::isDevice) {
            // With no host round trip inside a step, a pair of steps replays as one CUDA graph.
            if (mode_ != NeighbourMode::Grid && !exec_.timing && steps >= 4) {
                if (!graph_.ready()) {
                    step();  // allocates every buffer: a capture cannot allocate
                    --steps;
                    graphParity_ = int(steps_ & 1);
                    exec_.capture(graph_, [&] {
                        step();
                        step();
                    });
                    steps_ -= 2;  // capturing does not run the steps
                }
                if (int(steps_ & 1) != graphParity_) {  // the graph holds buffer swaps of a pair
                    step();
                    --steps;
                }
                for (; steps >= 2; steps -= 2) {
                    exec_.launch(graph_);
                    steps_ += 2;
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

    // One step, paper §5-6: separate stages launched in sequence.
    void step() {
        switch (mode_) {
            case NeighbourMode::Grid:
                buildGrid();
                computeDensityPressure(sparse_.view());
                computeAcceleration(sparse_.view());
                break;
            case NeighbourMode::Dense:
                buildGrid();
                computeDensityPressure(denseView());
                accelerateAndIntegrate(denseView());
                break;
            default:
                computeDensityPressure(BruteNeighbours{n_});
                computeAcceleration(BruteNeighbours{n_});
        }
        if (mode_ != NeighbourMode::Dense) {
            integrate();
        }
        ++steps_;
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

    template <class Neighbours>
    void computeDensityPressure(const Neighbours& nb) {
        exec_.stageBegin("density");
        const ParticleView pv = view();
        const SphParams params = params_;
        exec_.forEach(n_, [=] WEIR_HD(Index i) { densityPressureAt(i, pv, nb, params); });
        exec_.stageEnd("density");
    }

    template <class Neighbours>
    void computeAcceleration(const Neighbours& nb) {
        exec_.stageBegin("force");
        const ParticleView pv = view();
        const SphParams params = params_;
        exec_.forEach(n_, [=] WEIR_HD(Index i) { accelerationAt(i, pv, nb, params); });
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
        int* counter = stepCounter_.data();
        Real4 *newPos = sortedPos_.data(), *newVel = sortedVel_.data();
        exec_.forEach(n_, [=] WEIR_HD(Index i) {
            accelerateAndIntegrateAt(i, pv, nb, params, obstacles, fault, *counter, newPos, newVel);
        });
        exec_.forEach(1, [=] WEIR_HD(Index) { ++*counter; });
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
        int* counter = stepCounter_.data();
        exec_.forEach(
            n_, [=] WEIR_HD(Index i) { integrateAt(i, pv, params, obstacles, fault, *counter); });
        // The step number lives on the device, so a replayed graph records the right one.
        exec_.forEach(1, [=] WEIR_HD(Index) { ++*counter; });
        exec_.stageEnd("integrate");
    }

    ParticleView view() { return {pos_.data(), vel_.data(), acc_.data(), n_}; }

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
            (id_.size() + sortedId_.size()) * sizeof(Index);
        return bytes + (mode_ == NeighbourMode::Grid ? sparse_.bytesHeld() : 0) +
               (mode_ == NeighbourMode::Dense ? dense_.bytesHeld() : 0);
    }
    Index occupiedCells() const override {
        return mode_ == NeighbourMode::Grid ? sparse_.numCells() : 0;
    }
    const SphParams& params() const override { return params_; }
    Index particleCount() const override { return n_; }
    long long stepCount() const override { return steps_; }

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

    Exec exec_;
    NeighbourMode mode_;
    SphParams params_;
    NeighbourGrid<Exec> sparse_;
    DenseGrid<Exec> dense_;
    Index n_ = 0;
    long long steps_ = 0;
    Buffer<Real4> pos_, vel_, acc_, sortedPos_, sortedVel_;
    Buffer<Index> id_, sortedId_;
    Buffer<ObstacleBox> boxes_;
    Buffer<ObstacleSphere> spheres_;
    Buffer<FaultRecord> fault_;
    Buffer<int> stepCounter_;
    typename Exec::Graph graph_;
    int graphParity_ = 0;
    StageTimes times_;
};

}  // namespace weir
