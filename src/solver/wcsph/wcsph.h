// Weakly compressible SPH, the paper's method (§5-6; Müller et al. 2003): density, pressure by an
// equation of state, pressure and viscous forces, displacement; separate stages launched in
// sequence, one thread per particle.
#pragma once

#include <cstdint>
#include <cstdlib>
#include <type_traits>

#include "core/team.h"
#include "grid/dense_grid.h"
#include "solver/pressure_solver.h"
#include "solver/wcsph/wcsph_stages.h"

namespace weir {

template <class Exec>
class Wcsph final : public PressureSolver<Exec> {
   public:
    template <class T>
    using Buffer = typename Exec::template Buffer<T>;
    using Context = StepContext<Exec>;

    static constexpr const char* kName = "wcsph";
    static constexpr const char* kDescription =
        "weakly compressible SPH (the paper's: an equation of state, a speed of sound ten times "
        "the flow's)";

    explicit Wcsph(const SphParams&) {}

    // Paper §6: grid, density and pressure, force, displacement. The dense table's path runs the
    // force and displacement as one pass (no acceleration array); the paper's grid and brute
    // force keep the paper's separate stages, so that Tables 1-3 reproduce stage for stage.
    void step(Context& s) override {
        if (s.params.model == FluidModel::DeltaSph) {
            deltaStep(s);
            return;
        }
        StepClock* clock = s.clock;
        const SphParams params = s.params;
        s.search.update(s.exec, s.store, [=] WEIR_HD() { beginStep(*clock, params); });
        fit(s);
        s.search.visit(s.store.pos(), s.store.count(), [&](const auto& nb) {
            computeDensityPressure(s, nb, true);
            if constexpr (fusesForceAndDisplacement<decltype(nb)>()) {
                accelerateAndIntegrate(s, nb);
            } else {
                computeAcceleration(s, nb);
                integrate(s);
            }
        });
        s.exec.forEach(1, [=] WEIR_HD(Index) { endStep(*clock); });
    }

    // delta-SPH: the density is part of the state (continuity equation): nothing to compute, but
    // the pressure terms follow from it.
    void computeDensity(Context& s) override {
        if (s.params.model == FluidModel::DeltaSph) {
            fit(s);
            s.search.update(
                s.exec, s.store, [] WEIR_HD() {}, keptDensities(s));
            return;
        }
        s.search.update(s.exec, s.store, [] WEIR_HD() {});
        fit(s);
        s.search.visit(s.store.pos(), s.store.count(),
                       [&](const auto& nb) { computeDensityPressure(s, nb, false); });
    }

    void runStage(Context& s, Stage stage) override {
        fit(s);
        if (s.params.model == FluidModel::DeltaSph) {  // grid, then the force and density passes
            if (stage == Stage::Grid) {
                s.search.update(
                    s.exec, s.store, [] WEIR_HD() {}, keptDensities(s));
            } else if (stage == Stage::Force) {
                s.search.visit(s.store.pos(), s.store.count(),
                               [&](const auto& nb) { deltaForces(s, nb); });
            } else if (stage == Stage::Density) {
                s.search.visit(s.store.pos(), s.store.count(),
                               [&](const auto& nb) { deltaDensities(s, nb); });
            }
            return;
        }
        switch (stage) {
            case Stage::Grid:
                if (s.search.reorders()) {
                    s.search.update(s.exec, s.store, [] WEIR_HD() {});
                }
                break;
            case Stage::Density:
                s.search.visit(s.store.pos(), s.store.count(),
                               [&](const auto& nb) { computeDensityPressure(s, nb, false); });
                break;
            case Stage::Force:
                s.search.visit(s.store.pos(), s.store.count(), [&](const auto& nb) {
                    if constexpr (fusesForceAndDisplacement<decltype(nb)>()) {
                        accelerateAndIntegrate(s, nb);
                    } else {
                        computeAcceleration(s, nb);
                    }
                });
                break;
            case Stage::Integrate:
                if (s.search.mode() != NeighbourMode::Dense) {
                    integrate(s);
                }
                break;
        }
    }

    std::size_t bytesHeld() const override {
        return (pressureTerm_.size() + density_.size() + kernelSum_.size()) * sizeof(Real) +
               (acc_.size() + wallState_.size()) * sizeof(Real4);
    }

    // ---- The stages (public only because CUDA lambdas need a public enclosing function) ----

    // delta-SPH (physics/delta_sph.h): the grid build keeps every particle's density and
    // pressure term as it moves it; a force pass gives the new velocities, a density pass the
    // new densities (wcsph_stages.h: a symplectic Euler step).
    void deltaStep(Context& s) {
        StepClock* clock = s.clock;
        const SphParams params = s.params;
        fit(s);
        s.search.update(
            s.exec, s.store, [=] WEIR_HD() { beginStep(*clock, params); }, keptDensities(s));
        s.search.visit(s.store.pos(), s.store.count(), [&](const auto& nb) {
            deltaWalls(s, nb);
            deltaBodyLoads(s, nb);
            deltaForces(s, nb);
            deltaDensities(s, nb);
        });
        s.store.commitMotion();
        s.exec.forEach(1, [=] WEIR_HD(Index) { endStep(*clock); });
    }

    // As the grid build moves particle `from` to `to`: its density and p / rho^2 into the
    // method's arrays (in the new order).
    struct KeptDensities {
        const Real4* vel;
        Real *density, *term;
        SphParams params;
        WEIR_HD void operator()(Index from, Index to) const {
            const Real rho = vel[from].w;
            density[to] = rho;
            term[to] = pressureTermOf(params, rho);
        }
    };
    KeptDensities keptDensities(Context& s) {
        return {s.store.vel(), density_.data(), pressureTerm_.data(), s.params};
    }

    // Each boundary particle's pressure and velocity, extrapolated from the fluid near it.
    template <class Neighbours>
    void deltaWalls(Context& s, const Neighbours& nb) {
        const Index walls = s.boundary.count;
        if (s.params.walls != WallKind::Particles || walls == 0) {
            return;
        }
        s.exec.stageBegin("walls");
        const ParticleView pv = view(s);
        const SphParams params = s.params;
        Real4* state = wallState_.data();
        s.exec.forEach(walls, [=] WEIR_HD(Index b) { deltaWallAt(b, pv, nb, params, state); });
        s.exec.stageEnd("walls");
    }

    // The fluid's force and torque on each rigid body's boundary particles, from the same state
    // the force pass reads (before it moves anything).
    template <class Neighbours>
    void deltaBodyLoads(Context& s, const Neighbours& nb) {
        if (s.bodies.count == 0 || s.boundary.count == 0) {
            return;
        }
        s.exec.stageBegin("bodies");
        const ParticleView pv = view(s);
        const SphParams params = s.params;
        const RigidBodyView bodies = s.bodies;
        s.exec.forEach(s.boundary.count,
                       [=] WEIR_HD(Index b) { deltaBodyLoadAt(b, pv, nb, params, bodies); });
        s.exec.stageEnd("bodies");
    }

    template <class Neighbours>
    void deltaForces(Context& s, const Neighbours& nb) {
        s.exec.stageBegin("force");
        if constexpr (Exec::isDevice && fusesForceAndDisplacement<Neighbours>()) {
            if (teamSize(s) == 2) {
                deltaForcePass<2>(s, nb);
            } else {
                deltaForcePass<1>(s, nb);
            }
        } else {
            deltaForcePass<1>(s, nb);
        }
        s.exec.stageEnd("force");
    }

    template <int TeamSize, class Neighbours>
    void deltaForcePass(Context& s, const Neighbours& nb) {
        const ParticleView pv = view(s);
        const SphParams params = s.params;
        const ObstacleView obstacles = s.obstacles;
        FaultRecord* fault = s.fault;
        StepClock* clock = s.clock;
        Real4 *newPos = s.store.nextPos(), *newVel = s.store.nextVel();
        Real* kernelSum = shiftingSums(s);
        s.exec.template forEachTeam<TeamSize>(pv.count, [=] WEIR_HD(Index i, Team<TeamSize> team) {
            deltaForceAt(i, pv, nb, params, obstacles, fault, clock, newPos, newVel, kernelSum,
                         team);
        });
    }

    template <class Neighbours>
    void deltaDensities(Context& s, const Neighbours& nb) {
        s.exec.stageBegin("density");
        const ParticleView pv = view(s);
        const SphParams params = s.params;
        const Real* density = density_.data();
        Real4* moved = s.store.nextVel();
        Real4* movedPos = s.store.nextPos();
        const Real* kernelSum = shiftingSums(s);
        const ObstacleView obstacles = s.obstacles;
        FaultRecord* fault = s.fault;
        const StepClock* clock = s.clock;
        s.exec.forEach(pv.count, [=] WEIR_HD(Index i) {
            deltaDensityAt(i, pv, nb, params, density, moved, movedPos, kernelSum, obstacles, fault,
                           clock);
        });
        s.exec.stageEnd("density");
    }

    // Density and pressure term of every particle; skipped in a no-op step when `inStep`.
    template <class Neighbours>
    void computeDensityPressure(Context& s, const Neighbours& nb, bool inStep) {
        s.exec.stageBegin("density");
        const ParticleView pv = view(s);
        const SphParams params = s.params;
        const StepClock* clock = inStep ? s.clock : nullptr;
        s.exec.forEach(pv.count, [=] WEIR_HD(Index i) {
            if (clock == nullptr || clock->dt != Real(0)) {
                densityPressureAt(i, pv, nb, params);
            }
        });
        s.exec.stageEnd("density");
    }

    template <class Neighbours>
    void computeAcceleration(Context& s, const Neighbours& nb) {
        s.exec.stageBegin("force");
        const ParticleView pv = view(s);
        const SphParams params = s.params;
        const StepClock* clock = s.clock;
        s.exec.forEach(pv.count, [=] WEIR_HD(Index i) {
            if (clock->dt != Real(0) && !isGhost(pv.pos[i])) {
                accelerationAt(i, pv, nb, params);
            }
        });
        s.exec.stageEnd("force");
    }

    // The paper's displacement stage.
    void integrate(Context& s) {
        s.exec.stageBegin("integrate");
        const ParticleView pv = view(s);
        const SphParams params = s.params;
        const ObstacleView obstacles = s.obstacles;
        FaultRecord* fault = s.fault;
        StepClock* clock = s.clock;
        // The step number and dt live on the device, so a replayed graph uses the right ones.
        s.exec.forEach(pv.count, [=] WEIR_HD(Index i) {
            if (clock->dt != Real(0)) {
                integrateAt(i, pv, params, obstacles, fault, clock);
            }
        });
        s.exec.stageEnd("integrate");
    }

    // Force and displacement in one pass (dense path): timed as "force".
    template <class Neighbours>
    void accelerateAndIntegrate(Context& s, const Neighbours& nb) {
        s.exec.stageBegin("force");
        if constexpr (Exec::isDevice) {
            if (teamSize(s) == 2) {
                accelerateAndIntegratePass<2>(s, nb);
            } else {
                accelerateAndIntegratePass<1>(s, nb);
            }
        } else {
            accelerateAndIntegratePass<1>(s, nb);
        }
        s.store.commitMotion();
        s.exec.stageEnd("force");
    }

    template <int TeamSize, class Neighbours>
    void accelerateAndIntegratePass(Context& s, const Neighbours& nb) {
        const ParticleView pv = view(s);
        const SphParams params = s.params;
        const ObstacleView obstacles = s.obstacles;
        FaultRecord* fault = s.fault;
        StepClock* clock = s.clock;
        Real4 *newPos = s.store.nextPos(), *newVel = s.store.nextVel();
        s.exec.template forEachTeam<TeamSize>(pv.count, [=] WEIR_HD(Index i, Team<TeamSize> team) {
            accelerateAndIntegrateAt(i, pv, nb, params, obstacles, fault, clock, newPos, newVel,
                                     team);
        });
    }

   private:
    // The dense table's path fuses force and displacement; the paper's grid and brute force keep
    // the paper's stages.
    template <class Neighbours>
    static constexpr bool fusesForceAndDisplacement() {
        return std::is_same_v<std::decay_t<Neighbours>, DenseGridNeighbours>;
    }

    // Particle shifting's kernel sums (force pass to density pass), or null when it is off.
    Real* shiftingSums(Context& s) {
        return s.params.shifting > Real(0) ? kernelSum_.data() : nullptr;
    }

    // Sizes the method's arrays to the particle count (no allocation unless it grew).
    void fit(Context& s) {
        pressureTerm_.resize(std::size_t(s.store.count()));
        if (s.params.model == FluidModel::DeltaSph) {
            density_.resize(std::size_t(s.store.count()));
            wallState_.resize(std::size_t(s.boundary.count));
            if (s.params.shifting > Real(0)) {
                kernelSum_.resize(std::size_t(s.store.count()));
            }
        }
        if (s.search.mode() != NeighbourMode::Dense && s.params.model == FluidModel::Paper) {
            acc_.resize(std::size_t(s.store.count()));  // the dense path fuses force and motion
        }
    }

    ParticleView view(Context& s) {
        BoundaryView walls = s.boundary;
        walls.state = wallState_.data();
        return {s.store.pos(),        s.store.vel(),   acc_.data(),
                pressureTerm_.data(), s.store.count(), walls};
    }

    // Lanes per particle in the dense path's force pass on the GPU (core/team.h): two where one
    // thread per particle would leave the GPU half idle (at most half its resident threads;
    // bench/NOTES.md #12), else one. WEIR_TEAM=1 or 2 sets it (speed experiments).
    int teamSize(Context& s) const {
        if (teamOverride_ > 0) {
            return teamOverride_;
        }
        return 2 * std::int64_t(s.store.count()) <= s.exec.residentThreads() ? 2 : 1;
    }
    static int teamOverride() {
        const char* text = std::getenv("WEIR_TEAM");
        const int wanted = text != nullptr ? std::atoi(text) : 0;
        return wanted >= 2 ? 2 : (wanted == 1 ? 1 : 0);
    }

    Buffer<Real> pressureTerm_;  // the density stage's pressureTermOf, for the force stage
    Buffer<Real> density_;       // delta-SPH: each particle's density at the step's start
    Buffer<Real4> wallState_;    // delta-SPH: each boundary particle's velocity and p / rho^2
    Buffer<Real> kernelSum_;     // delta-SPH with shifting: each particle's kernel sum
    Buffer<Real4> acc_;          // the paper's stages: force stage to displacement stage
    int teamOverride_ = teamOverride();
};

}  // namespace weir
