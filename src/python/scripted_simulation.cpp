// ScriptedSimulation: `weir run`'s set-up and fault handling for a simulation stepped by a script.
#include "python/scripted_simulation.h"

#include <algorithm>
#include <climits>
#include <cmath>

#include "io/frame_index.h"

namespace weir {

ScriptedSimulation::ScriptedSimulation(const Scene& scene, const ScriptedOptions& options)
    : scene_(scene) {
    if (!options.model.empty()) {
        scene_ = withFluidModel(scene_, options.model);
    }
    if (!options.solver.empty()) {
        scene_ = withSolver(scene_, options.solver);
    }
    const Backend backend = parseBackend(options.backend);
    const NeighbourMode asked = parseNeighbourMode(options.neighbours);
    SetupOptions setupOptions;
    setupOptions.particleCount = options.particles;
    setupOptions.backend = backend;
    if (backend == Backend::Cuda && cudaDeviceAvailable()) {
        setupOptions.deviceFreeBytes = cudaFreeMemoryBytes();  // checked before seeding
    }
    SimulationSetup setup = buildSetup(scene_, setupOptions, &report_);
    mode_ = resolveNeighbourMode(asked, setup.grid, setup.slotCount());
    sim_ = makeSimulation(backend, mode_, std::move(setup));
    sim_->computeDensity();  // frame 0's density and pressure, as `weir run` writes them
}

ScriptedSimulation::Busy::Busy(ScriptedSimulation& s) : flag_(s.busy_) {
    if (flag_.exchange(true)) {
        throw BusyError(
            "the simulation is busy in another thread (a step, or reading its particles): one "
            "call at a time on one simulation");
    }
}

Simulation& ScriptedSimulation::simulation() {
    Busy busy(*this);  // only checks: the caller's use is short and on this thread
    return *sim_;
}

void ScriptedSimulation::step(std::int64_t steps) {
    Busy busy(*this);
    if (steps < 0) {
        throw std::invalid_argument("step(n): n = " + std::to_string(steps) +
                                    " is not allowed; give n >= 0 steps");
    }
    ++version_;
    viewsShared_ = false;
    while (steps > 0) {
        const int batch = int(std::min<std::int64_t>(steps, INT_MAX));
        sim_->advance(batch);
        steps -= batch;
    }
    checkFault();
}

void ScriptedSimulation::advanceTo(double time) {
    Busy busy(*this);
    const double now = sim_->time();
    if (!std::isfinite(time) || time < now) {
        throw std::invalid_argument("advance_to(t): t = " + std::to_string(time) +
                                    " s is not allowed; give a finite time >= the current " +
                                    std::to_string(now) + " s");
    }
    ++version_;
    viewsShared_ = false;
    sim_->advanceTo(time);
    checkFault();
}

std::string ScriptedSimulation::faultText() {
    Busy busy(*this);
    return diagnosis();
}

std::string ScriptedSimulation::diagnosis() {
    const FaultRecord fault = sim_->fault();
    return fault.code == 0 ? std::string() : describeFault(fault, sim_->params());
}

void ScriptedSimulation::checkFault() {
    const std::string text = diagnosis();
    if (!text.empty()) {
        throw BlowUpError(text);
    }
}

const HostParticles& ScriptedSimulation::particles() {
    Busy busy(*this);
    return hostParticles();
}

const HostParticles& ScriptedSimulation::hostParticles() {
    if (hostVersion_ != version_ || viewsShared_) {
        sim_->download(host_);
        hostVersion_ = version_;
    }
    return host_;
}

ParticleArrays ScriptedSimulation::deviceArrays() {
    Busy busy(*this);
    sim_->synchronize();
    viewsShared_ = true;  // the caller may write to them: no host copy is current till a step
    return sim_->particleArrays();
}

TriangleMesh ScriptedSimulation::surface(Backend backend, SurfaceOptions options) {
    Busy busy(*this);
    if (options.spacing == 0) {
        options.spacing = report_.spacing;  // one scale for every frame of the run, as weir run
    }
    return reconstructSurface(backend, hostParticles(), options);
}

void ScriptedSimulation::writeFrame(FrameWriter& writer, int index) {
    Busy busy(*this);
    writer.setRecord(makeRunRecord(scene_.name, scene_.sourcePath, scene_.json,
                                   sim_->particleCount(), report_.spacing, WEIR_VERSION));
    writer.write(index, sim_->time(), hostParticles());
}

}  // namespace weir
