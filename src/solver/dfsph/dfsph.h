// Divergence-free SPH (Bender & Koschier 2015, 2017): an incompressible fluid whose time step is
// set by the flow's speed, not by a speed of sound. A step: the grid build; density by summation
// and each particle's factor alpha; the divergence-free solve (the velocity field made to keep
// the density constant); the non-pressure forces; the constant-density solve (the velocity made
// to bring the density predicted at the step's end back to rho0); the move. Each solve iterates
// Jacobi sweeps (dfsph_stages.h) until the mean error is under its tolerance; the test runs on
// the backend (a reduction and a one-thread check), every sweep's stages return at once after
// it, and the host only polls a flag to stop launching sweeps; in a step replayed as a CUDA graph
// the graph loops by itself (a conditional node), with no host round trip.
#pragma once

#include <cstddef>
#include <cstdlib>
#include <string>
#include <vector>

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

    explicit Dfsph(const SphParams& params)
        : pressureScale_(params.rawGradientMoment), pushingWalls_(pushingWallsChosen()) {}

    // WEIR_DFSPH_WALLS=extrapolated (experimental, 2026-12-05): walls that push back as the fluid
    // near them does in the density solve (dfsphWallStiffnessAt), one warm start for both solves
    // and the first from the seeded hydrostatic pressure. A tank at rest then passes every
    // hydrostatic check at 12, 24 and 48 particles over its depth (it failed them at every one),
    // but a periodic channel of honey blew up within 0.1 s, so it is not the default
    // (docs/dfsph.md).
    static bool pushingWallsChosen() {
        const char* setting = std::getenv("WEIR_DFSPH_WALLS");
        return setting != nullptr && std::string(setting) == "extrapolated";
    }

    void step(Context& s) override {
        StepClock* clock = s.clock;
        const SphParams params = s.params;
        fit(s);
        s.search.update(
            s.exec, s.store, [=] WEIR_HD() { beginStep(*clock, params); }, keptWarmStarts());
        for (int k = 0; k < 2; ++k) {
            warm_[k].swap(warmNext_[k]);
        }
        findOwners(s);
        s.search.visit(s.store.pos(), s.store.count(), [&](const auto& grid) {
            // The positions stay put until the move: one walk of the grid lists the neighbours
            // that every later pass, the solves' sweeps above all, reads.
            const auto nb = neighbours(s, grid, listed_);
            densityAndFactor(s, nb);
            wallVelocities(s, nb);
            solve(s, nb, s.store.vel(), true);
            nonPressure(s, nb);
            if (pushingWalls_) {
                takeOutWhatTheDivergenceSolveApplied(s);
            }
            solve(s, nb, s.store.nextVel(), false);
            keepPressureById(s);
            if (pushingWalls_) {
                joinTheWarmStarts(s);
            }
            keepWarmStartsById(s);
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

    // A step may be replayed as a CUDA graph whose solves loop on the device
    // (Exec::repeatUntilSet's conditional node), with no host round trip. WEIR_DFSPH_GRAPH=0 runs
    // every step directly, the host polling the solves' flags between sweeps (for benchmarks that
    // compare). On an H100 (2026-12-05, bench/results/h100-2026-12-05b) the graph's step took 1.56
    // ms against 1.66 ms at 98k particles and 3.18 against 3.19 ms at 1M, and its test passed.
    bool capturable() const override {
        const char* setting = std::getenv("WEIR_DFSPH_GRAPH");
        return !(setting != nullptr && std::string(setting) == "0");
    }

    std::size_t bytesHeld() const override {
        return list_.bytesHeld() +
               (factor_.size() + kappaOverRho_.size() + 2 * warm_[0].size() + 2 * warm_[1].size()) *
                   sizeof(Real) +
               taken_.size() * sizeof(Real) + error_.size() * sizeof(float) + interior_.size() +
               wallState_.size() * sizeof(Real4) +
               (wallShepardSum_.size() + wallStiffness_.size() + wallStiffnessChange_.size()) *
                   sizeof(Real) +
               monitor_.size() * sizeof(DfsphMonitor) + impulseById_.size() * sizeof(Real);
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
        const Real* wallShepardSum = nullptr;
        if (pushingWalls_ && wallsExtrapolated(s)) {
            Real* sums = wallShepardSum_.data();
            s.exec.forEach(s.boundary.count, [=] WEIR_HD(Index b) {
                dfsphWallShepardSumAt(b, pv, nb, params, sums);
            });
            wallShepardSum = sums;
        }
        s.exec.forEach(pv.count, [=] WEIR_HD(Index i) {
            dfsphDensityFactorAt(i, pv, nb, params, factor, interior, wallShepardSum);
        });
        if (periodic_) {
            const Index* owner = owner_.data();
            s.exec.forEach(pv.count, [=] WEIR_HD(Index i) {
                const Index o = owner[i];
                if (o != i) {
                    pv.vel[i].w = pv.vel[o].w;
                    factor[i] = factor[o];
                    interior[i] = interior[o];
                }
            });
        }
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
        const SphParams params = dfsphForceParams(s.params);
        const Real4* state = wallState_.size() > 0 ? wallState_.data() : nullptr;
        StepClock* clock = s.clock;
        Real4* predicted = s.store.nextVel();
        s.exec.forEach(pv.count, [=] WEIR_HD(Index i) {
            dfsphNonPressureAt(i, pv, nb, params, state, clock, predicted);
        });
        copyVelocitiesToGhosts(s, predicted);
        s.exec.stageEnd("force");
    }

    // One solve on velocities `vel` (in place): sweeps until the backend's check says done, at
    // most `sweeps` of them (default: the scene's limit). The host reads the flag after each
    // sweep on the CPU (free) and every second one on the GPU (a round trip each); a captured
    // step loops on the device (Exec::repeatUntilSet).
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
        // The mean error is over the owned particles: a ghost's error is its owner's, counted
        // once (copyStiffnessToGhosts gives it 0).
        const Index owned = periodic_ ? n - s.store.ghostCount() : n;
        const Real tolerance = divergence ? params.divergenceTolerance : params.densityTolerance;
        // The density solve also sweeps while one particle's error is past the scene's bound
        // (dfsph.worstDensityError): the mean over millions hides a few compressed particles (a
        // 10M dam break met the mean in 2 sweeps a step while its column's foot compressed, by
        // +2% to +10% over 30 ms, until it blew up; 2026-12-05, bench/results/h100-2026-12-05b).
        const Real worst = divergence ? Real(0) : params.worstDensityTolerance;
        const int minimum = divergence ? 1 : 2;
        const int maximum = sweeps > 0 ? sweeps : params.maxSolverIterations;
        Real* accumulated = warm_[divergence ? 1 : 0].data();
        const unsigned char* interior = interior_.data();
        const Real share =
            divergence ? (pushingWalls_ ? Real(0) : kDivergenceWarmShare) : kDensityWarmShare;
        const Real relaxation = dfsphRelaxation(params);
        // The density solve's walls push back as the fluid near them does (dfsphWallStiffnessAt):
        // after the warm start and after every prediction, each wall's stiffness from the sums.
        const bool walls = pushingWalls_ && !divergence && wallsExtrapolated(s);
        const Index boundaryCount = walls ? s.boundary.count : 0;
        Real* wallTotal = walls ? wallStiffness_.data() : nullptr;
        Real* wallChange = walls ? wallStiffnessChange_.data() : nullptr;
        const Real* wallShepardSum = walls ? wallShepardSum_.data() : nullptr;
        auto extrapolateToWalls = [&] {
            if (walls) {
                s.exec.forEach(boundaryCount, [=] WEIR_HD(Index b) {
                    dfsphWallStiffnessAt(b, pv, nb, params, accumulated, wallShepardSum, monitor,
                                         wallTotal, wallChange);
                });
            }
        };
        if (walls) {
            clear(s.exec, wallTotal, boundaryCount);
        }
        s.exec.forEach(1, [=] WEIR_HD(Index) { dfsphBeginSolve(monitor, clock); });
        s.exec.forEach(n, [=] WEIR_HD(Index i) {
            dfsphWarmStartAt(i, vel, divergence, share, clock, kappaOverRho, accumulated, interior);
        });
        if (share > Real(0)) {
            extrapolateToWalls();
            s.exec.forEach(n, [=] WEIR_HD(Index i) {
                dfsphUpdateAt(i, pv, nb, params, vel, kappaOverRho, clock, monitor, wallChange);
            });
            copyVelocitiesToGhosts(s, vel);
        }
        // Sweeps until dfsphCheck sets the monitor's flag (at the latest after `maximum`): on the
        // device, by a loop the host polls or, in a captured step, by the graph itself.
        s.exec.repeatUntilSet(&monitor->done, maximum + 1, minimum, [&] {
            s.exec.forEach(n, [=] WEIR_HD(Index i) {
                dfsphPredictAt(i, pv, nb, params, vel, factor, divergence, clock, monitor,
                               kappaOverRho, error, accumulated, interior, relaxation);
            });
            copyStiffnessToGhosts(s, kappaOverRho, accumulated, error);
            extrapolateToWalls();
            s.exec.sum(error, n, &monitor->errorSum);
            if (worst > Real(0)) {
                s.exec.max(error, n, &monitor->errorMax);
            }
            s.exec.forEach(1, [=] WEIR_HD(Index) {
                dfsphCheck(monitor, owned, tolerance, worst, minimum, maximum);
            });
            s.exec.forEach(n, [=] WEIR_HD(Index i) {
                dfsphUpdateAt(i, pv, nb, params, vel, kappaOverRho, clock, monitor, wallChange);
            });
            copyVelocitiesToGhosts(s, vel);
        });
        s.exec.stageEnd(divergence ? "divergence" : "pressure");
    }

    // Each owned particle's pressure for frames, by id: the mean over the steps since it was last
    // asked for of what the two solves applied. A sweep's velocity update is
    // -dt sum m (k_i / rho_i + k_j / rho_j) grad W, the pressure force's p_i / rho_i^2 = k_i /
    // rho_i, so a step's pressure impulse p dt is rho (K dt + K_v), K the density solve's summed k
    // and K_v the divergence solve's sum (kept as k dt). The divergence solve removes what the last
    // step left, so one step's share would depend on how short the step that lands on a frame is;
    // the frame's mean does not.
    void keepPressureById(Context& s) {
        const Index n = s.store.count();
        const Index owned = n - s.store.ghostCount();
        if (impulseById_.size() != std::size_t(owned)) {
            impulseById_.resize(std::size_t(owned));
            clear(s.exec, impulseById_.data(), owned);
            impulseTime_.resize(1);
            clear(s.exec, impulseTime_.data(), 1);
        }
        const Real4* pos = s.store.pos();
        const Real4* vel = s.store.vel();
        const Index* id = s.store.id();
        const Real* density = warm_[0].data();
        const Real* divergence = warm_[1].data();
        const bool divergenceSolved = s.params.divergenceTolerance > Real(0);
        const StepClock* clock = s.clock;
        Real* impulse = impulseById_.data();
        s.exec.forEach(n, [=] WEIR_HD(Index i) {
            if (!isGhost(pos[i]) && id[i] >= 0 && id[i] < owned) {
                const Real k =
                    density[i] * clock->dt + (divergenceSolved ? divergence[i] : Real(0));
                impulse[id[i]] += k * vel[i].w;
            }
        });
        Real* time = impulseTime_.data();
        s.exec.forEach(1, [=] WEIR_HD(Index) { time[0] += clock->dt; });
    }

    // The mean since the last time it was asked for, kept on the host until a step follows, so
    // that every download between two steps (the frame, the renderer, a script's arrays) gets
    // the same values. Reported times the raw gradient's lattice moment (pressureScale_): the
    // pressure that pushes as hard through the corrected gradient, the one that differentiates a
    // linear pressure exactly on the lattice (physics/kernels.h), i.e. the fluid's pressure.
    bool solvedPressure(Exec& exec, std::vector<Real>& byId) override {
        if (impulseTime_.size() == 0) {
            return false;
        }
        Real time = 0;
        exec.download(impulseTime_, &time, 1);
        if (time > Real(0)) {
            lastPressure_.resize(impulseById_.size());
            exec.download(impulseById_, lastPressure_.data(), lastPressure_.size());
            const Real scale = pressureScale_ / time;
            for (Real& p : lastPressure_) {
                p *= scale;
            }
            clear(exec, impulseById_.data(), Index(impulseById_.size()));
            clear(exec, impulseTime_.data(), 1);
        }
        if (lastPressure_.empty()) {
            return false;  // no step yet: the equation of state's
        }
        byId = lastPressure_;
        return true;
    }

    // ---- Periodic axes (solver/periodic_ghosts.h) ----
    // A ghost copy across a periodic face is its owner seen from the other side: after every pass
    // that changes a per-particle quantity of the solve, each ghost takes its owner's, so a sweep
    // sees across the face what it sees inside the fluid (a ghost's own sums, cut off at the
    // halo's edge, would creep inwards by h a pass). Owners are found by id: DFSPH runs without
    // emitters, sinks and ranks, so the owned particles' ids are 0 .. n - 1.
    void findOwners(Context& s) {
        periodic_ = s.params.periodicAxes != 0;
        if (!periodic_) {
            return;
        }
        const Index n = s.store.count();
        owner_.resize(std::size_t(n));
        indexOfId_.resize(std::size_t(n));
        const Real4* pos = s.store.pos();
        const Index* id = s.store.id();
        Index *owner = owner_.data(), *indexOfId = indexOfId_.data();
        s.exec.forEach(n, [=] WEIR_HD(Index i) {
            if (!isGhost(pos[i]) && id[i] >= 0 && id[i] < n) {
                indexOfId[id[i]] = i;
            }
        });
        s.exec.forEach(n, [=] WEIR_HD(Index i) {
            owner[i] = isGhost(pos[i]) && id[i] >= 0 && id[i] < n ? indexOfId[id[i]] : i;
        });
        // The warm starts, kept by id from the last step (its ghosts were dropped after it, which
        // moved the owned particles from where the grid build's reorder expects them).
        // (Sized once, at the first step: the owned count does not change under DFSPH.)
        const Index owned = n - s.store.ghostCount();
        if (warmById_[0].size() < std::size_t(owned)) {
            for (Buffer<Real>* b : {&warmById_[0], &warmById_[1]}) {
                b->resize(std::size_t(owned));
                clear(s.exec, b->data(), owned);
            }
            if (seedById_.size() >= std::size_t(owned)) {  // the seeded hydrostatic pressure
                Real* density = warmById_[0].data();
                const Real* seed = seedById_.data();
                s.exec.forEach(owned, [=] WEIR_HD(Index k) { density[k] = seed[k]; });
            }
        }
        for (int k = 0; k < 2; ++k) {
            Real* warm = warm_[k].data();
            const Real* byId = warmById_[k].data();
            const Index* ownerOf = owner;
            s.exec.forEach(n, [=] WEIR_HD(Index i) {
                const Index o = ownerOf[i];
                warm[i] = id[o] >= 0 && id[o] < owned ? byId[id[o]] : Real(0);
            });
        }
    }

    // Each ghost's velocity (xyz; its density is its own copy of the owner's) from its owner.
    void copyVelocitiesToGhosts(Context& s, Real4* vel) {
        if (!periodic_) {
            return;
        }
        const Index* owner = owner_.data();
        s.exec.forEach(s.store.count(), [=] WEIR_HD(Index i) {
            const Index o = owner[i];
            if (o != i) {
                vel[i] = Real4::from(vel[o].xyz(), vel[i].w);
            }
        });
    }

    // Each ghost's stiffness and summed stiffness from its owner, and no error of its own.
    void copyStiffnessToGhosts(Context& s, Real* kappaOverRho, Real* accumulated, float* error) {
        if (!periodic_) {
            return;
        }
        const Index* owner = owner_.data();
        s.exec.forEach(s.store.count(), [=] WEIR_HD(Index i) {
            const Index o = owner[i];
            if (o != i) {
                kappaOverRho[i] = kappaOverRho[o];
                accumulated[i] = accumulated[o];
                error[i] = 0.0f;
            }
        });
    }

    // The owned particles' summed stiffnesses, by id, for the next step's warm start.
    void keepWarmStartsById(Context& s) {
        if (!periodic_) {
            return;
        }
        const Real4* pos = s.store.pos();
        const Index* id = s.store.id();
        const Index n = s.store.count(), owned = Index(warmById_[0].size());
        for (int k = 0; k < 2; ++k) {
            const Real* warm = warm_[k].data();
            Real* byId = warmById_[k].data();
            s.exec.forEach(n, [=] WEIR_HD(Index i) {
                if (!isGhost(pos[i]) && id[i] >= 0 && id[i] < owned) {
                    byId[id[i]] = warm[i];
                }
            });
        }
    }

    // One warm start for both solves. The divergence solve starts from nothing each step, and what
    // it applied is taken out of the density solve's warm start, as far as the warm start goes;
    // after the density solve what was taken out goes back in, so the next step starts from the
    // whole of this step's support. (A divergence push past the warm start is not kept: adding it
    // back whole ratcheted the stiffness up where the fluid needs none, and a periodic channel
    // with no pressure to speak of blew up.) Measured (CPU, 2026-12-05, a tank 0.3 m deep at 48
    // particles over the depth, 0.5 s): with each solve warm-started from its own sum, the
    // divergence solve carried part of the column's weight within its loose tolerance (0.1% a step,
    // about one step's gravity), its warm start pushed on where the particle had already moved, and
    // the column gained energy: its centre of mass rose from 0.150 to 0.160 m, the interior read
    // 0.81-0.87 rho0 by 1 s (voids: nothing pulls), the top 5 d above its seeded surface. With one
    // warm start it stays at rho0 and the centre of mass at 0.150 m; the density solve then does
    // the work the divergence solve's tolerance hid (20-45 sweeps a step there, against 2).
    void takeOutWhatTheDivergenceSolveApplied(Context& s) {
        if (s.params.divergenceTolerance <= Real(0)) {
            return;
        }
        taken_.resize(std::size_t(s.store.count()));
        Real* density = warm_[0].data();
        Real* taken = taken_.data();
        const Real* divergence = warm_[1].data();
        const StepClock* clock = s.clock;
        s.exec.forEach(s.store.count(), [=] WEIR_HD(Index i) {
            const Real applied = clock->dt > Real(0) ? divergence[i] / clock->dt : Real(0);
            const Real out = Real(fmin(fmax(applied, Real(0)), density[i]));
            density[i] -= out;
            taken[i] = out;
        });
    }

    void joinTheWarmStarts(Context& s) {
        if (s.params.divergenceTolerance <= Real(0)) {
            return;
        }
        Real* density = warm_[0].data();
        Real* divergence = warm_[1].data();
        const Real* taken = taken_.data();
        s.exec.forEach(s.store.count(), [=] WEIR_HD(Index i) {
            density[i] += taken[i];
            divergence[i] = Real(0);
        });
    }

    // The first warm start: the seeded hydrostatic pressure. The seeding gives each particle
    // rho0 + rho0 g depth / c^2 (scene/setup.cpp), so g depth = (rho - rho0) |g| / |hydrostatic
    // gradient|, and the stiffness that holds it through the raw gradient is g depth / M (M the
    // lattice moment). Started from nothing, a column 48 particles deep fell for about 15 ms
    // while the Jacobi sweeps carried the floor's push up a few layers a sweep, landed at 0.11 m/s
    // RMS, and with the walls' extrapolated pressure blew up at 0.08 s (CPU, 2026-12-05). With
    // periodic axes the warm starts come by id (findOwners), so the seed is kept by id too.
    void seedWarmStart(Context& s, Index n) {
        const bool periodic = s.params.periodicAxes != 0;
        if (periodic) {
            seedById_.resize(std::size_t(n));
            clear(s.exec, seedById_.data(), n);
        }
        Real* warm = periodic ? seedById_.data() : warm_[0].data();
        const Real4* vel = s.store.vel();
        const Real4* pos = s.store.pos();
        const Index* id = s.store.id();
        const Real g = length(s.params.gravity), gradient = length(s.params.hydrostaticGradient);
        const Real rho0 = s.params.restDensity, moment = s.params.rawGradientMoment;
        if (!(gradient > Real(0))) {
            return;
        }
        s.exec.forEach(n, [=] WEIR_HD(Index i) {
            const Real excess = vel[i].w - rho0;
            const Real k = excess > Real(0) ? excess * g / gradient / moment : Real(0);
            if (!periodic) {
                warm[i] = k;
            } else if (!isGhost(pos[i]) && id[i] >= 0 && id[i] < n) {
                warm[id[i]] = k;
            }
        });
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
            // With periodic axes the count changes with the ghosts every step, and the warm
            // starts come by id (findOwners): no clearing.
            for (Buffer<Real>* b : {&warm_[0], &warm_[1], &warmNext_[0], &warmNext_[1]}) {
                b->resize(n);
                if (s.params.periodicAxes == 0) {
                    clear(s.exec, b->data(), Index(n));
                }
            }
            if (pushingWalls_ && !seeded_) {
                seeded_ = true;
                seedWarmStart(s, Index(n));
            }
        }
        factor_.resize(n);
        interior_.resize(n);
        kappaOverRho_.resize(n);
        error_.resize(n);
        if (s.params.walls == WallKind::Particles && s.params.noSlip) {
            wallState_.resize(std::size_t(s.boundary.count));
        }
        if (pushingWalls_ && wallsExtrapolated(s)) {
            for (Buffer<Real>* b : {&wallShepardSum_, &wallStiffness_, &wallStiffnessChange_}) {
                b->resize(std::size_t(s.boundary.count));
            }
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

    static bool wallsExtrapolated(const Context& s) {
        return s.params.walls == WallKind::Particles && s.boundary.count > 0;
    }

    ParticleView view(Context& s) {
        BoundaryView walls = s.boundary;
        walls.state = wallState_.size() > 0 ? wallState_.data() : nullptr;
        return {s.store.pos(), s.store.vel(), nullptr, nullptr, s.store.count(), walls};
    }

    // The share of the last step's summed stiffness a solve starts from.
    static constexpr Real kDensityWarmShare = Real(1);
    static constexpr Real kDivergenceWarmShare = Real(1);  // (0 with pushingWalls_: one warm start)

    Buffer<Real> warm_[2];  // per particle, the stiffness summed by the last step's [0] density,
                            // [1] divergence solve (the warm start)
    Buffer<Real> warmNext_[2];        // the same in the grid build's new order
    Buffer<Real> factor_;             // alpha_i of this step
    Buffer<unsigned char> interior_;  // 1: inside the fluid this step, 0: at a free surface
    Buffer<Real> kappaOverRho_;       // the current sweep's stiffness over density, kappa_i / rho_i
                                      // (kappa_i = p_i / rho_i)
    Buffer<float> error_;             // the current sweep's per-particle error, for the sum
    Buffer<Real4> wallState_;         // no-slip walls: each boundary particle's mirrored velocity
    Buffer<Real> seedById_;           // periodic: the first warm start by id, until findOwners
    bool seeded_ = false;             // the first warm start has been seeded
    Buffer<Real> taken_;              // per particle: what the divergence solve applied, taken
                                      // out of the density solve's warm start this step
    Buffer<Real> wallShepardSum_;     // per boundary particle: sum of W over the fluid near it
    Buffer<Real> wallStiffness_;      // per boundary particle: the density solve's kappa_b / rho0
    Buffer<Real> wallStiffnessChange_;  // ... and what the next velocity update adds
    Buffer<DfsphMonitor> monitor_;      // [0] the density solve, [1] the divergence solve
    bool periodic_ = false;             // periodic axes: ghosts take their owners' state
    Buffer<Index> owner_;               // periodic: each particle's owner (itself if owned)
    Buffer<Index> indexOfId_;           // periodic: an owned particle's index by its id
    Buffer<Real> warmById_[2];          // periodic: the warm starts by id between steps
    Real pressureScale_;        // the frames' pressure per solved pressure (see solvedPressure)
    bool pushingWalls_;         // WEIR_DFSPH_WALLS=extrapolated (pushingWallsChosen)
    Buffer<Real> impulseById_;  // per id, the solves' pressure impulse since the last frame
    Buffer<Real> impulseTime_;  // [0]: the time those impulses span
    std::vector<Real> lastPressure_;  // host: the last mean handed out, by id
    NeighbourList<Exec> list_;        // this step's neighbours, when listed_
    bool listed_ = false;             // whether the neighbours are listed (memory allowing)
    bool listDecided_ = false;
};

}  // namespace weir
