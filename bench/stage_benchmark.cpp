// Google Benchmark of the step's stages (grid build, density, force, integrate) at fixed sizes,
// on the CPU and, where a GPU is visible, on CUDA. Each iteration runs one stage and waits for it.
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <tuple>

#include "scene/scene.h"
#include "scene/setup.h"
#include "solver/simulation.h"

namespace weir {
namespace {

// One settled dam break per (backend, neighbour search, size), kept across benchmarks; the
// paper's fluid model, whose stages these are (as `weir bench` times them).
Simulation& simulationFor(Backend backend, NeighbourMode mode, std::int64_t size) {
    static std::map<std::tuple<int, int, std::int64_t>, std::unique_ptr<Simulation>> cache;
    auto& slot = cache[{int(backend), int(mode), size}];
    if (!slot) {
        SetupOptions options;
        options.particleCount = size;
        SimulationSetup setup =
            buildSetup(withFluidModel(builtinScene("dam_break"), "paper"), options, nullptr);
        slot = makeSimulation(backend, mode, std::move(setup));
        slot->advance(int(0.05 / slot->params().timeStep));  // a fluid in motion
        slot->synchronize();
    }
    return *slot;
}

void stageBenchmark(benchmark::State& state, Backend backend, NeighbourMode mode,
                    Simulation::Stage stage) {
    if (backend == Backend::Cuda && !cudaDeviceAvailable()) {
        state.SkipWithError("no CUDA device visible");
        return;
    }
    Simulation& sim = simulationFor(backend, mode, state.range(0));
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
    // dense: weir's default; grid: the paper's cell and neighbour tables (section 6.2).
    const std::pair<const char*, NeighbourMode> modes[] = {{"dense", NeighbourMode::Dense},
                                                           {"grid", NeighbourMode::Grid}};
    for (auto [modeName, mode] : modes) {
        for (auto [name, stage] : stages) {
            benchmark::RegisterBenchmark((std::string("cpu/") + modeName + "/" + name).c_str(),
                                         stageBenchmark, Backend::Cpu, mode, stage)
                ->Arg(10000)
                ->Arg(100000)
                ->Unit(benchmark::kMillisecond)
                ->UseRealTime();
            benchmark::RegisterBenchmark((std::string("cuda/") + modeName + "/" + name).c_str(),
                                         stageBenchmark, Backend::Cuda, mode, stage)
                ->Arg(100000)
                ->Arg(1000000)
                ->Arg(10000000)
                ->Unit(benchmark::kMillisecond)
                ->UseRealTime();
        }
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
