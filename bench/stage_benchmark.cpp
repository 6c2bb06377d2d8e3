// Google Benchmark of the step's stages (grid build, density, force, integrate) at fixed sizes,
// on the CPU and, where a GPU is visible, on CUDA. Each iteration runs one stage and waits for it.
#include <benchmark/benchmark.h>

#include <map>
#include <memory>

#include "scene/scene.h"
#include "scene/setup.h"

namespace weir {
namespace {

// One settled dam break per (backend, size), kept across benchmarks.
Simulation& simulationFor(Backend backend, std::int64_t size) {
    static std::map<std::pair<int, std::int64_t>, std::unique_ptr<Simulation>> cache;
    auto& slot = cache[{int(backend), size}];
    if (!slot) {
        SetupOptions options;
        options.particleCount = size;
        SimulationSetup setup = buildSetup(builtinScene("dam_break"), options, nullptr);
        slot = makeSimulation(backend, NeighbourMode::Grid, std::move(setup));
        slot->advance(int(0.05 / slot->params().timeStep));  // a fluid in motion
        slot->synchronize();
    }
    return *slot;
}

void stageBenchmark(benchmark::State& state, Backend backend, Simulation::Stage stage) {
    if (backend == Backend::Cuda && !cudaDeviceAvailable()) {
        state.SkipWithError("no CUDA device visible");
        return;
    }
    Simulation& sim = simulationFor(backend, state.range(0));
    sim.runStage(Simulation::Stage::Grid);
    sim.runStage(Simulation::Stage::Density);
    sim.synchronize();
    for (auto _ : state) {
        sim.runStage(stage);
        sim.synchronize();
    }
    state.SetItemsProcessed(state.iterations() * state.range(0));
    state.counters["particles"] = double(sim.particleCount());
}

void registerAll() {
    const std::pair<const char*, Simulation::Stage> stages[] = {
        {"grid", Simulation::Stage::Grid},
        {"density", Simulation::Stage::Density},
        {"force", Simulation::Stage::Force},
        {"integrate", Simulation::Stage::Integrate},
    };
    for (auto [name, stage] : stages) {
        benchmark::RegisterBenchmark((std::string("cpu/") + name).c_str(), stageBenchmark,
                                     Backend::Cpu, stage)
            ->Arg(10000)
            ->Arg(100000)
            ->Unit(benchmark::kMillisecond)
            ->UseRealTime();
        benchmark::RegisterBenchmark((std::string("cuda/") + name).c_str(), stageBenchmark,
                                     Backend::Cuda, stage)
            ->Arg(100000)
            ->Arg(1000000)
            ->Arg(10000000)
            ->Unit(benchmark::kMillisecond)
            ->UseRealTime();
    }
}

}  // namespace
}  // namespace weir

int main(int argc, char** argv) {
    weir::registerAll();
    benchmark::Initialize(&argc, argv);
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
