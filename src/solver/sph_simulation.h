// A simulation on one backend (CpuExec or CudaExec), put together from its parts: the particle
// store, the neighbour search, the step driver, the static walls and obstacles, and a pressure
// solver (solver/methods.h). Instantiated for the CPU in solver_cpu.cpp and for CUDA in
// solver_cuda.cu; cluster/ wraps one per rank of a distributed run.
#pragma once

#include <algorithm>
#include <memory>
#include <string>
#include <utility>

#include "core/check.h"
#include "solver/inflow_outflow.h"
#include "solver/method_registry.h"
#include "solver/neighbour_search.h"
#include "solver/particle_store.h"
#include "solver/periodic_ghosts.h"
#include "solver/pressure_solver.h"
#include "solver/rigid_bodies.h"
#include "solver/simulation.h"
#include "solver/step_driver.h"

namespace weir {

template <class Exec>
class SphSimulation final : public Simulation {
   public:
    template <class T>
    using Buffer = typename Exec::template Buffer<T>;

    // mode: resolved already (not Auto).
    SphSimulation(NeighbourMode mode, SimulationSetup setup)
        : params_(setup.params),
          methodName_(checkPressureSolver(setup.method)),
          search_(mode, periodicGrid(setup.grid, setup.params), setup.slotCount(),
                  setup.params.kernel.h),
          method_(makePressureSolver<Exec>(methodName_, setup.params)),
          periodic_(setup.params) {
        checkPeriodicLengths(params_);
        for (int a = 0; a < 3; ++a) {
            if (isPeriodic(params_, a)) {
                // The pressure is periodic too: a body force along a periodic axis (a channel's
                // driving force) is not held by a hydrostatic pressure difference, so density
                // diffusion has no hydrostatic part to leave alone there.
                params_.hydrostaticGradient[a] = 0;
            }
        }
        if (setup.particles.size() == 0 && setup.seeder) {
            setup.seeder->seed(exec_, store_);  // on this backend, in the host's order
        } else {
            store_.upload(exec_, setup.particles, setup.particleIds);
        }
        store_.fitScratch(search_.reorders());
        if (setup.flow.active()) {
            WEIR_REQUIRE(mode == NeighbourMode::Dense && !periodic_.active(),
                         "emitters and sinks run with the dense cell table and no periodic axis");
            flow_.upload(exec_, setup.flow, store_);
        }
        uploadWalls(setup);
        bodies_.upload(exec_, setup.boundary, setup.bodies);
        FaultRecord none{0, 0, 0, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f};
        exec_.upload(fault_, &none, 1);
        // The first step's dt sees the initial speeds and gravity (the lattice starts in balance).
        double maxSpeed2 = 0;
        const HostParticles& host = setup.particles;
        for (std::size_t i = 0; i < host.size(); ++i) {
            maxSpeed2 = std::max(maxSpeed2, double(host.vx[i]) * host.vx[i] +
                                                double(host.vy[i]) * host.vy[i] +
                                                double(host.vz[i]) * host.vz[i]);
        }
        if (setup.seeder) {
            maxSpeed2 = std::max(maxSpeed2, setup.seeder->maxSpeed() * setup.seeder->maxSpeed());
        }
        for (const Emitter& e : setup.flow.emitters) {
            maxSpeed2 = std::max(maxSpeed2, double(e.speed) * double(e.speed));
        }
        driver_.start(exec_, maxSpeed2, double(lengthSquared(params_.gravity)),
                      double(params_.timeStep));
        if (bodies_.active()) {
            bodies_.place(exec_, driver_.clock());  // the wall grid holds them from the start
        }
    }

    // ---- Simulation ----

    void advanceTo(double target) override {
        driver_.advanceTo(
            exec_, target, [&] { stepNow(); }, capturable(),
            [&] { return exec_.readOne(fault_, 0).code != 0; });
    }
    void advance(int steps) override {
        driver_.advance(
            exec_, steps, [&] { stepNow(); }, capturable());
    }
    void computeDensity() override {
        StepContext<Exec> s = context();
        addPeriodicGhosts();
        method_->computeDensity(s);
        dropPeriodicGhosts();
    }
    void runStage(Stage stage) override {
        StepContext<Exec> s = context();
        method_->runStage(s, stage);
    }
    void download(HostParticles& out) override {
        store_.download(exec_, out, params_, flow_.active() ? flow_.counters(exec_).live : -1);
        if (method_->solvedPressure(exec_, solvedPressure_)) {
            for (std::size_t k = 0; k < out.size(); ++k) {
                const Index id = out.idOf(k);
                if (id >= 0 && std::size_t(id) < solvedPressure_.size()) {
                    out.p[k] = solvedPressure_[std::size_t(id)];
                }
            }
        }
        out.bodies.clear();
        if (bodies_.active()) {
            for (const RigidBody& b : bodies_.download(exec_)) {
                out.bodies.push_back(poseOf(b));
            }
        }
    }
    FaultRecord fault() override { return exec_.readOne(fault_, 0); }
    void synchronize() override { exec_.synchronize(); }

    void setTiming(bool on) override { exec_.timing = on; }
    const StageTimes& stageTimes() const override { return times_; }
    void clearStageTimes() override { times_.clear(); }

    Backend backend() const override { return Exec::isDevice ? Backend::Cuda : Backend::Cpu; }
    NeighbourMode neighbourMode() const override { return search_.mode(); }
    std::string deviceName() const override { return exec_.deviceName(); }
    std::size_t bytesHeld() const override {
        return store_.bytesHeld() + search_.bytesHeld() + method_->bytesHeld() +
               bodies_.bytesHeld() + flow_.bytesHeld() + boundaryStart_.size() * sizeof(Index) +
               (boundaryPos_.size() + boundaryVelocity_.size()) * sizeof(Real4) +
               boundaryNear_.size();
    }
    Index occupiedCells() const override { return search_.occupiedCells(); }
    const SphParams& params() const override { return params_; }
    std::string method() const override { return methodName_; }
    Index particleCount() const override {
        return flow_.active() ? flow_.counters(exec_).live : store_.count();
    }
    long long stepCount() const override { return driver_.read(exec_).step; }
    double time() const override { return driver_.read(exec_).time; }
    SolverReport takeSolverReport() override { return method_->takeReport(exec_); }
    std::vector<RigidBody> rigidBodies() override { return bodies_.download(exec_); }
    FlowCounters flowCounters() override {
        return flow_.active() ? flow_.counters(exec_) : FlowCounters{};
    }
    // With emitters or sinks, the live particles: the first slots after a step.
    ParticleArrays particleArrays() override {
        return {store_.pos(), store_.vel(), store_.id(), particleCount(), Exec::isDevice};
    }

    // ---- The parts, for cluster/'s rank of a distributed run ----

    Exec& exec() { return exec_; }
    ParticleStore<Exec>& store() { return store_; }
    NeighbourSearch<Exec>& search() { return search_; }
    StepClock clock() { return driver_.read(exec_); }
    void setClock(const StepClock& clock) { driver_.write(exec_, clock); }
    // The clock and the first fault, read back in one wait.
    StepClock clockAndFault(FaultRecord& fault) {
        StepClock clock;
        exec_.downloadFromAsync(driver_.buffer(), 0, &clock, 1);
        exec_.downloadFromAsync(fault_, 0, &fault, 1);
        exec_.synchronize();
        return clock;
    }
    // One step with the clock as it is (the caller set the shared dt inputs and target).
    void stepOnce() {
        driver_.run(
            exec_, 1, [&] { stepNow(); }, false);
    }

   private:
    // Periodic ghosts are counted on the host each step: no graph. Bodies sum their loads by
    // reductions launched per body: no graph either.
    bool capturable() const {
        return search_.capturable() && method_->capturable() && !periodic_.active() &&
               !bodies_.active();
    }

    // Ghost copies across the periodic faces for this step, and their removal after it, so that
    // between steps the store holds the owned particles only (solver/periodic_ghosts.h).
    void addPeriodicGhosts() {
        if (periodic_.active()) {
            periodic_.add(exec_, store_);
        }
    }
    void dropPeriodicGhosts() {
        if (periodic_.active()) {
            periodic_.drop(exec_, store_);
        }
    }

    StepContext<Exec> context() {
        const ObstacleView obstacles{boxes_.data(), int(boxes_.size()), spheres_.data(),
                                     int(spheres_.size())};
        return {exec_,         store_,         search_,   params_,       driver_.clock(),
                fault_.data(), boundaryView(), obstacles, bodies_.view()};
    }

    void stepNow() {
        if (flow_.active()) {
            flow_.apply(exec_, store_, driver_.clock());
        }
        if (bodies_.active()) {
            bodies_.place(exec_, driver_.clock());
        }
        StepContext<Exec> s = context();
        addPeriodicGhosts();
        method_->step(s);
        dropPeriodicGhosts();
        if (bodies_.active()) {
            bodies_.advance(exec_, driver_.clock(), params_);
        }
        if (exec_.timing) {
            exec_.collectTimes(times_);
        }
    }

    BoundaryView boundaryView() {
        if (bodies_.active()) {
            return bodies_.wallView();
        }
        BoundaryView walls = boundary_;
        walls.pos = boundaryPos_.data();
        walls.velocity = boundaryVelocity_.size() > 0 ? boundaryVelocity_.data() : nullptr;
        walls.cells.cellBound = boundaryStart_.data();
        walls.near = boundaryNear_.data();
        return walls;
    }

    void uploadWalls(const SimulationSetup& setup) {
        const BoundaryParticles& walls = setup.boundary;
        if (walls.size() > 0) {
            exec_.upload(boundaryPos_, walls.pos.data(), walls.pos.size());
            exec_.upload(boundaryVelocity_, walls.velocity.data(), walls.velocity.size());
            exec_.upload(boundaryStart_, walls.cellStart.data(), walls.cellStart.size());
            exec_.upload(boundaryNear_, walls.near.data(), walls.near.size());
            boundary_.cells.spec = walls.cellSpec();
            boundary_.count = Index(walls.size());
        }
        exec_.upload(boxes_, setup.obstacleBoxes.data(), setup.obstacleBoxes.size());
        exec_.upload(spheres_, setup.obstacleSpheres.data(), setup.obstacleSpheres.size());
    }

    mutable Exec exec_;  // mutable: reading the device clock back is not a change
    SphParams params_;
    std::string methodName_;
    ParticleStore<Exec> store_;
    NeighbourSearch<Exec> search_;
    StepDriver<Exec> driver_;
    std::unique_ptr<PressureSolver<Exec>> method_;
    PeriodicGhosts<Exec> periodic_;
    std::vector<Real> solvedPressure_;  // the method's own pressure by id, for frames
    RigidBodies<Exec> bodies_;
    InflowOutflow<Exec> flow_;
    Buffer<FaultRecord> fault_;
    Buffer<ObstacleBox> boxes_;
    Buffer<ObstacleSphere> spheres_;
    BoundaryView boundary_;  // geometry of the static wall grid; pointers filled by boundaryView()
    Buffer<Real4> boundaryPos_, boundaryVelocity_;
    Buffer<Index> boundaryStart_;
    Buffer<unsigned char> boundaryNear_;
    StageTimes times_;
};

}  // namespace weir
