// The SPH step as a short list of stages over one backend's primitives (CpuExec or CudaExec):
// grid build and reorder, density and pressure, force, integration with walls.
#pragma once

#include <algorithm>
#include <numeric>
#include <utility>

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
        : mode_(mode), params_(setup.params), grid_(setup.grid) {
        const HostParticles& host = setup.particles;
        n_ = Index(host.size());
        std::vector<Index> ids(n_);
        std::iota(ids.begin(), ids.end(), Index(0));
        exec_.upload(x_, host.x.data(), n_);
        exec_.upload(y_, host.y.data(), n_);
        exec_.upload(z_, host.z.data(), n_);
        exec_.upload(vx_, host.vx.data(), n_);
        exec_.upload(vy_, host.vy.data(), n_);
        exec_.upload(vz_, host.vz.data(), n_);
        exec_.upload(id_, ids.data(), n_);
        for (auto* b : {&ax_, &ay_, &az_, &rho_, &p_}) {
            b->resize(n_);
        }
        if (mode_ == NeighbourMode::Grid) {
            for (auto& b : scratch_) {
                b.resize(n_);
            }
            scratchId_.resize(n_);
        }
        exec_.upload(boxes_, setup.obstacleBoxes.data(), setup.obstacleBoxes.size());
        exec_.upload(spheres_, setup.obstacleSpheres.data(), setup.obstacleSpheres.size());
        FaultRecord none{0, 0, 0, 0.0f};
        exec_.upload(fault_, &none, 1);
    }

    void advance(int steps) override {
        for (int s = 0; s < steps; ++s) {
            step();
        }
    }

    void computeDensity() override {
        if (mode_ == NeighbourMode::Grid) {
            buildGrid();
            computeDensityPressure(grid_.view());
        } else {
            computeDensityPressure(BruteNeighbours{n_});
        }
    }

    void runStage(Stage stage) override {
        switch (stage) {
            case Stage::Grid:
                if (mode_ == NeighbourMode::Grid) {
                    buildGrid();
                }
                break;
            case Stage::Density:
                if (mode_ == NeighbourMode::Grid) {
                    computeDensityPressure(grid_.view());
                } else {
                    computeDensityPressure(BruteNeighbours{n_});
                }
                break;
            case Stage::Force:
                if (mode_ == NeighbourMode::Grid) {
                    computeAcceleration(grid_.view());
                } else {
                    computeAcceleration(BruteNeighbours{n_});
                }
                break;
            case Stage::Integrate:
                integrate();
                break;
        }
    }

    // One step, paper §5-6: separate stages launched in sequence.
    void step() {
        if (mode_ == NeighbourMode::Grid) {
            buildGrid();
            computeDensityPressure(grid_.view());
            computeAcceleration(grid_.view());
        } else {
            computeDensityPressure(BruteNeighbours{n_});
            computeAcceleration(BruteNeighbours{n_});
        }
        integrate();
        ++steps_;
        if (exec_.timing) {
            exec_.collectTimes(times_);
        }
    }

    void buildGrid() {
        exec_.stageBegin("grid");
        grid_.build(exec_, x_.data(), y_.data(), z_.data(), n_);
        reorderByCell();
        exec_.stageEnd("grid");
    }

    // Gathers every particle attribute into cell order, so that neighbours sit close in memory.
    void reorderByCell() {
        const Index* order = grid_.permutation();
        Real* src[6] = {x_.data(), y_.data(), z_.data(), vx_.data(), vy_.data(), vz_.data()};
        Real* dst[6];
        for (int a = 0; a < 6; ++a) {
            dst[a] = scratch_[a].data();
        }
        const Index* id = id_.data();
        Index* newId = scratchId_.data();
        Real *s0 = src[0], *s1 = src[1], *s2 = src[2], *s3 = src[3], *s4 = src[4], *s5 = src[5];
        Real *d0 = dst[0], *d1 = dst[1], *d2 = dst[2], *d3 = dst[3], *d4 = dst[4], *d5 = dst[5];
        exec_.forEach(n_, [=] WEIR_HD(Index i) {
            Index from = order[i];
            d0[i] = s0[from];
            d1[i] = s1[from];
            d2[i] = s2[from];
            d3[i] = s3[from];
            d4[i] = s4[from];
            d5[i] = s5[from];
            newId[i] = id[from];
        });
        x_.swap(scratch_[0]);
        y_.swap(scratch_[1]);
        z_.swap(scratch_[2]);
        vx_.swap(scratch_[3]);
        vy_.swap(scratch_[4]);
        vz_.swap(scratch_[5]);
        id_.swap(scratchId_);
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

    void integrate() {
        exec_.stageBegin("integrate");
        const ParticleView pv = view();
        const SphParams params = params_;
        const ObstacleView obstacles{boxes_.data(), int(boxes_.size()), spheres_.data(),
                                     int(spheres_.size())};
        FaultRecord* fault = fault_.data();
        const int step = int(steps_);
        exec_.forEach(n_, [=] WEIR_HD(Index i) {
            integrateAt(i, pv, params, obstacles, fault, step);
        });
        exec_.stageEnd("integrate");
    }

    ParticleView view() {
        return {x_.data(),  y_.data(),  z_.data(),   vx_.data(), vy_.data(), vz_.data(),
                ax_.data(), ay_.data(), az_.data(), rho_.data(), p_.data(),  n_};
    }

    void download(HostParticles& out) override {
        out.resize(n_);
        std::vector<Index> ids(n_);
        exec_.download(id_, ids.data(), n_);
        std::vector<Real> tmp(n_);
        auto fetch = [&](const Buffer<Real>& src, std::vector<Real>& dst) {
            exec_.download(src, tmp.data(), n_);
            for (Index i = 0; i < n_; ++i) {
                dst[ids[i]] = tmp[i];
            }
        };
        fetch(x_, out.x);
        fetch(y_, out.y);
        fetch(z_, out.z);
        fetch(vx_, out.vx);
        fetch(vy_, out.vy);
        fetch(vz_, out.vz);
        fetch(rho_, out.rho);
        fetch(p_, out.p);
    }

    FaultRecord fault() override { return exec_.readOne(fault_, 0); }
    void synchronize() override { exec_.synchronize(); }

    void setTiming(bool on) override { exec_.timing = on; }
    const StageTimes& stageTimes() const override { return times_; }
    void clearStageTimes() override { times_.clear(); }

    Backend backend() const override {
        return Exec::isDevice ? Backend::Cuda : Backend::Cpu;
    }
    NeighbourMode neighbourMode() const override { return mode_; }
    std::string deviceName() const override { return exec_.deviceName(); }
    std::size_t bytesHeld() const override {
        std::size_t reals = 0;
        for (const auto* b : {&x_, &y_, &z_, &vx_, &vy_, &vz_, &ax_, &ay_, &az_, &rho_, &p_}) {
            reals += b->size();
        }
        for (const auto& b : scratch_) {
            reals += b.size();
        }
        return reals * sizeof(Real) + (id_.size() + scratchId_.size()) * sizeof(Index) +
               grid_.bytesHeld();
    }
    Index occupiedCells() const override {
        return mode_ == NeighbourMode::Grid ? grid_.numCells() : 0;
    }
    const SphParams& params() const override { return params_; }
    Index particleCount() const override { return n_; }
    long long stepCount() const override { return steps_; }

    // For tests: the grid as last built.
    const NeighbourGrid<Exec>& grid() const { return grid_; }

   private:
    Exec exec_;
    NeighbourMode mode_;
    SphParams params_;
    NeighbourGrid<Exec> grid_;
    Index n_ = 0;
    long long steps_ = 0;
    Buffer<Real> x_, y_, z_, vx_, vy_, vz_, ax_, ay_, az_, rho_, p_;
    Buffer<Real> scratch_[6];
    Buffer<Index> id_, scratchId_;
    Buffer<ObstacleBox> boxes_;
    Buffer<ObstacleSphere> spheres_;
    Buffer<FaultRecord> fault_;
    StageTimes times_;
};

}  // namespace weir
