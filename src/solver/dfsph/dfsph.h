// Divergence-free SPH (Bender & Koschier 2015, 2017): an incompressible fluid whose time step is
// set by the flow's speed, not by a speed of sound. A step: the grid build; density by summation
// and each particle's factor alpha; the divergence-free solve (the velocity field made to keep
// the density constant); the non-pressure forces; the constant-density solve (the velocity made
// to bring the density predicted at the step's end back to rho0); the move. Each solve iterates
// Jacobi sweeps (dfsph_stages.h) until the mean error is under its tolerance; the test runs on
// the backend (a reduction and a one-thread check), every sweep's stages return at once after
// it, and the host only polls a flag to stop launching sweeps.
#pragma once

#include <cstddef>
#include <cstdlib>
#include <string>

#include "core/team.h"
#include "grid/neighbour_list.h"
#include "solver/dfsph/dfsph_stages.h"
#include "solver/pressure_solver.h"

namespace weir {

template <class Exec>
class Dfsph final : public PressureSolver<Exec> {
   public:
    template <class T>
    using Buffer = typename Exec::template Buffer<T>;
    using Context = StepContext<Exec>;

    static constexpr const char* kName = "dfsph";
    static constexpr const char* kDescription =
        "divergence-free SPH (Bender & Koschier 2017: incompressible, a time step set by the "
        "flow's speed, density held within 0.01-0.1%)";

    explicit Dfsph(const SphParams&) {}

    void step(Context& s) override {
        StepClock* clock = s.clock;
        const SphParams params = s.params;
        fit(s);
        s.search.update(
            s.exec, s.store, [=] WEIR_HD() { beginStep(*clock, params); }, keptWarmStarts());
        for (int k = 0; k < 2; ++k) {
            warm_[k].swap(warmNext_[k]);
        }
        s.search.visit(s.store.pos(), s.store.count(), [&](const auto& grid) {
            // The positions stay put until the move: one walk of the grid lists the neighbours
            // that every later pass, the solves' sweeps above all, reads.
            const auto nb = neighbours(s, grid, listed_);
            densityAndFactor(s, nb);
            wallVelocities(s, nb);
            solve(s, nb, s.store.vel(), true);
            nonPressure(s, nb);
            solve(s, nb, s.store.nextVel(), false);
            advance(s);
        });
        s.store.commitMotion();
        s.exec.forEach(1, [=] WEIR_HD(Index) { endStep(*clock); });
    }

    void computeDensity(Context& s) override {
        fit(s);
        s.search.update(
            s.exec, s.store, [] WEIR_HD() {}, keptWarmStarts());
        for (int k = 0; k < 2; ++k) {
            warm_[k].swap(warmNext_[k]);
        }
        s.search.visit(s.store.pos(), s.store.count(),
                       [&](const auto& grid) { densityAndFactor(s, neighbours(s, grid, false)); });
    }

    // Stage benchmarks: the grid, the density and factor pass, the non-pressure forces with one
    // sweep of the density solve ("force"), the move.
    void runStage(Context& s, Stage stage) override {
        fit(s);
        switch (stage) {
            case Stage::Grid:
                s.search.update(s.exec, s.store, [] WEIR_HD() {});
                break;
            case Stage::Density:
                s.search.visit(s.store.pos(), s.store.count(), [&](const auto& grid) {
                    densityAndFactor(s, neighbours(s, grid, listed_));
                });
                break;
            case Stage::Force:
                s.search.visit(s.store.pos(), s.store.count(), [&](const auto& grid) {
                    const auto nb = neighbours(s, grid, listed_);
                    nonPressure(s, nb);
                    solve(s, nb, s.store.nextVel(), false, 1);
                });
                break;
            case Stage::Integrate:
                advance(s);
                s.store.commitMotion();
                break;
        }
    }

    // The host polls the solves' flags between sweeps: a step is not replayed as a graph.
    bool capturable() const override { return false; }

    std::size_t bytesHeld() const override {
        return list_.bytesHeld() +
               (factor_.size() + kappaOverRho_.size() + 2 * warm_[0].size() + 2 * warm_[1].size()) *
                   sizeof(Real) +
               error_.size() * sizeof(float) + interior_.size() +
               wallState_.size() * sizeof(Real4) + monitor_.size() * sizeof(DfsphMonitor);
    }

    SolverReport takeReport(Exec& exec) override {
        SolverReport report;
        report.iterative = true;
        if (monitor_.size() < 2) {
            return report;
        }
        DfsphMonitor m[2];
        exec.download(monitor_, m, 2);
        for (int k = 0; k < 2; ++k) {
            SolveReport& into = k == 0 ? report.density : report.divergence;
            into.solves = m[k].solves;
            into.iterations = m[k].totalIterations;
            into.maxIterations = m[k].maxIterations;
            into.unconverged = m[k].unconverged;
            into.worstError = m[k].worstError;
            m[k].solves = 0;
            m[k].totalIterations = 0;
            m[k].maxIterations = 0;
            m[k].unconverged = 0;
            m[k].worstError = 0;
        }
        exec.upload(monitor_, m, 2);
        return report;
    }

    // ---- The stages (public only because CUDA lambdas need a public enclosing function) ----

    // As the grid build moves particle `from` to `to`: its warm starts (the last step's summed
    // stiffnesses of both solves) into the new order.
    struct KeptWarmStarts {
        const Real *density, *divergence;
        Real *densityNext, *divergenceNext;
        WEIR_HD void operator()(Index from, Index to) const {
            densityNext[to] = density[from];
            divergenceNext[to] = divergence[from];
        }
    };
    KeptWarmStarts keptWarmStarts() {
        return {warm_[0].data(), warm_[1].data(), warmNext_[0].data(), warmNext_[1].data()};
    }

    template <class Neighbours>
    void densityAndFactor(Context& s, const Neighbours& nb) {
        s.exec.stageBegin("density");
        const ParticleView pv = view(s);
        const SphParams params = s.params;
        Real* factor = factor_.data();
        unsigned char* interior = interior_.data();
        s.exec.forEach(pv.count, [=] WEIR_HD(Index i) {
            dfsphDensityFactorAt(i, pv, nb, params, factor, interior);
        });
        s.exec.stageEnd("density");
    }

    template <class Neighbours>
    void wallVelocities(Context& s, const Neighbours& nb) {
        if (s.params.walls != WallKind::Particles || !s.params.noSlip || s.boundary.count == 0) {
            return;
        }
        s.exec.stageBegin("walls");
        const ParticleView pv = view(s);
        const SphParams params = s.params;
        Real4* state = wallState_.data();
        s.exec.forEach(s.boundary.count,
                       [=] WEIR_HD(Index b) { dfsphWallVelocityAt(b, pv, nb, params, state); });
        s.exec.stageEnd("walls");
    }

    template <class Neighbours>
    void nonPressure(Context& s, const Neighbours& nb) {
        s.exec.stageBegin("force");
        const ParticleView pv = view(s);
        const SphParams params = s.params;
        const Real4* state = wallState_.size() > 0 ? wallState_.data() : nullptr;
        StepClock* clock = s.clock;
        Real4* predicted = s.store.nextVel();
        s.exec.forEach(pv.count, [=] WEIR_HD(Index i) {
            dfsphNonPressureAt(i, pv, nb, params, state, clock, predicted);
        });
        s.exec.stageEnd("force");
    }

    // One solve on velocities `vel` (in place): sweeps until the backend's check says done, at
    // most `sweeps` of them (default: the scene's limit). The host reads the flag after each
    // sweep on the CPU (free) and every second one on the GPU (a round trip each).
    template <class Neighbours>
    void solve(Context& s, const Neighbours& nb, Real4* vel, bool divergence, int sweeps = 0) {
        const SphParams params = s.params;
        if (divergence && params.divergenceTolerance <= Real(0)) {
            return;
        }
        s.exec.stageBegin(divergence ? "divergence" : "pressure");
        const ParticleView pv = view(s);
        const StepClock* clock = s.clock;
        DfsphMonitor* monitor = monitor_.data() + (divergence ? 1 : 0);
        const Real* factor = factor_.data();
        Real* kappaOverRho = kappaOverRho_.data();
        float* error = error_.data();
        const Index n = pv.count;
        const Real tolerance = divergence ? params.divergenceTolerance : params.densityTolerance;
        const int minimum = divergence ? 1 : 2;
        const int maximum = sweeps > 0 ? sweeps : params.maxSolverIterations;
        Real* accumulated = warm_[divergence ? 1 : 0].data();
        const unsigned char* interior = interior_.data();
        const Real share = divergence ? kDivergenceWarmShare : kDensityWarmShare;
        s.exec.forEach(1, [=] WEIR_HD(Index) { dfsphBeginSolve(monitor, clock); });
        s.exec.forEach(n, [=] WEIR_HD(Index i) {
            dfsphWarmStartAt(i, vel, divergence, share, clock, kappaOverRho, accumulated, interior);
        });
        if (share > Real(0)) {
            s.exec.forEach(n, [=] WEIR_HD(Index i) {
                dfsphUpdateAt(i, pv, nb, params, vel, kappaOverRho, clock, monitor);
            });
        }
        for (int sweep = 0; sweep <= maximum; ++sweep) {
            s.exec.forEach(n, [=] WEIR_HD(Index i) {
                dfsphPredictAt(i, pv, nb, params, vel, factor, divergence, clock, monitor,
                               kappaOverRho, error, accumulated, interior);
            });
            s.exec.sum(error, n, &monitor->errorSum);
            s.exec.forEach(
                1, [=] WEIR_HD(Index) { dfsphCheck(monitor, n, tolerance, minimum, maximum); });
            s.exec.forEach(n, [=] WEIR_HD(Index i) {
                dfsphUpdateAt(i, pv, nb, params, vel, kappaOverRho, clock, monitor);
            });
            const bool poll = !Exec::isDevice || (sweep >= minimum && sweep % 2 == 0);
            if (poll && s.exec.readOne(monitor_, divergence ? 1 : 0).done != 0) {
                break;
            }
        }
        s.exec.stageEnd(divergence ? "divergence" : "pressure");
    }

    static void clear(Exec& exec, Real* data, Index n) {
        exec.forEach(n, [=] WEIR_HD(Index i) { data[i] = Real(0); });
    }

    // The move by the solved velocities (in nextVel), into nextPos and nextVel.
    void advance(Context& s) {
        s.exec.stageBegin("integrate");
        const ParticleView pv = view(s);
        const SphParams params = s.params;
        const ObstacleView obstacles = s.obstacles;
        FaultRecord* fault = s.fault;
        StepClock* clock = s.clock;
        Real4 *newPos = s.store.nextPos(), *newVel = s.store.nextVel();
        s.exec.forEach(pv.count, [=] WEIR_HD(Index i) {
            dfsphAdvanceAt(i, pv, params, obstacles, fault, clock, newVel, newPos, newVel);
        });
        s.exec.stageEnd("integrate");
    }

   private:
    // The neighbours of the current positions: listed (grid/neighbour_list.h) or the grid's walk.
    // Both give the stages one type, so each stage is compiled once per neighbour mode.
    template <class Grid>
    auto neighbours(Context& s, const Grid& grid, bool listed) {
        return list_.build(s.exec, grid, s.store.pos(), s.store.count(), s.params.wendland.h2,
                           listed);
    }

    // Sizes the method's arrays to the particle count (no allocation unless it grew).
    void fit(Context& s) {
        const std::size_t n = std::size_t(s.store.count());
        if (warm_[0].size() != n) {
            for (Buffer<Real>* b : {&warm_[0], &warm_[1], &warmNext_[0], &warmNext_[1]}) {
                b->resize(n);
                clear(s.exec, b->data(), Index(n));
            }
        }
        factor_.resize(n);
        interior_.resize(n);
        kappaOverRho_.resize(n);
        error_.resize(n);
        if (s.params.walls == WallKind::Particles && s.params.noSlip) {
            wallState_.resize(std::size_t(s.boundary.count));
        }
        if (!listDecided_) {
            listed_ = listFits(s.exec, n);
            listDecided_ = true;
        }
        if (monitor_.size() < 2) {
            const DfsphMonitor zero[2] = {};
            s.exec.upload(monitor_, zero, 2);
        }
    }

    // Whether n particles' neighbour lists fit in a quarter of the backend's free memory (the
    // rest is left to frames, meshes and the viewer); WEIR_NEIGHBOUR_LISTS=0 turns them off (for
    // benchmarks that compare).
    static bool listFits(Exec& exec, std::size_t n) {
        const char* setting = std::getenv("WEIR_NEIGHBOUR_LISTS");
        if (setting != nullptr && std::string(setting) == "0") {
            return false;
        }
        return n * NeighbourList<Exec>::bytesPerParticle() < exec.freeMemoryBytes() / 4;
    }

    ParticleView view(Context& s) {
        BoundaryView walls = s.boundary;
        walls.state = wallState_.size() > 0 ? wallState_.data() : nullptr;
        return {s.store.pos(), s.store.vel(), nullptr, nullptr, s.store.count(), walls};
    }

    // The share of the last step's summed stiffness a solve starts from.
    static constexpr Real kDensityWarmShare = Real(1);
    static constexpr Real kDivergenceWarmShare = Real(1);

    Buffer<Real> warm_[2];  // per particle, the stiffness summed by the last step's [0] density,
                            // [1] divergence solve (the warm start)
    Buffer<Real> warmNext_[2];        // the same in the grid build's new order
    Buffer<Real> factor_;             // alpha_i of this step
    Buffer<unsigned char> interior_;  // 1: inside the fluid this step, 0: at a free surface
    Buffer<Real> kappaOverRho_;       // the current sweep's stiffness over density, kappa_i / rho_i
                                      // (kappa_i = p_i / rho_i)
    Buffer<float> error_;             // the current sweep's per-particle error, for the sum
    Buffer<Real4> wallState_;         // no-slip walls: each boundary particle's mirrored velocity
    Buffer<DfsphMonitor> monitor_;    // [0] the density solve, [1] the divergence solve
    NeighbourList<Exec> list_;        // this step's neighbours, when listed_
    bool listed_ = false;             // whether the neighbours are listed (memory allowing)
    bool listDecided_ = false;
};

}  // namespace weir
