// `mpirun -n R weir bench --scaling`: weak and strong scaling of distributed runs. The baseline
// is the plain single-rank solver on rank 0 (CUDA graphs and all); weak scaling runs R times the
// particles on R ranks, strong scaling the same particles on R ranks. Medians over blocks of
// steps, the slowest rank's time each (every rank waits for it at the next exchange).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "cli/count_option.h"
#include "cluster/communicator.h"
#include "cluster/distributed_simulation.h"
#include "core/check.h"
#include "io/atomic_file.h"
#include "scene/scene.h"
#include "scene/setup.h"

namespace weir {

namespace {

struct Timing {
    double stepMs = 0;           // median over blocks, slowest rank
    double exchangeMs = 0;       // distributed: host time of the last exchange, slowest rank
    std::int64_t ghosts = 0;     // distributed: ghosts on the rank with most
    std::int64_t bytesSent = 0;  // distributed: bytes sent per step, all ranks
    std::int64_t particles = 0;
};

// Times `sim` over `blocks` blocks of `steps` steps after `warmup` steps; collective on `comm`.
Timing timeSteps(Simulation& sim, Communicator& comm, int warmup, int steps, int blocks) {
    sim.advance(warmup);
    sim.synchronize();
    std::vector<double> perStep;
    for (int b = 0; b < blocks; ++b) {
        comm.barrier();
        const auto start = std::chrono::steady_clock::now();
        sim.advance(steps);
        sim.synchronize();
        std::vector<double> ms{
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count() /
            steps};
        comm.maxInPlace(ms);
        perStep.push_back(ms[0]);
    }
    if (sim.fault().code != 0) {
        throw SimulationError(describeFault(sim.fault(), sim.params()));
    }
    std::sort(perStep.begin(), perStep.end());
    Timing t;
    t.stepMs = perStep[perStep.size() / 2];
    t.particles = sim.particleCount();
    return t;
}

SimulationSetup setupFor(const Scene& scene, std::int64_t count) {
    SetupOptions options;
    options.particleCount = count;
    options.seedOnDevice = true;  // each rank seeds only its slab
    return buildSetup(scene, options, nullptr);
}

Timing distributedTiming(Communicator& comm, const Scene& scene, std::int64_t count,
                         Backend backend, NeighbourMode mode, const BenchOptions& options,
                         HaloTransport transport, std::string* used) {
    DistributedOptions distributed;
    distributed.transport = transport;
    DistributedSimulation sim(comm, backend, mode, setupFor(scene, count), distributed);
    *used = sim.exchangeStats().transport;
    Timing t = timeSteps(sim, comm, options.warmup, options.steps, 5);
    const ExchangeStats& stats = sim.exchangeStats();
    std::vector<double> most{stats.exchangeSeconds * 1000, double(stats.ghosts)};
    comm.maxInPlace(most);
    std::vector<std::int64_t> sent{stats.bytesSent};
    comm.sumInPlace(sent);
    t.exchangeMs = most[0];
    t.ghosts = std::int64_t(most[1]);
    t.bytesSent = sent[0];
    return t;
}

}  // namespace

int scalingBenchCommand(const BenchOptions& options) {
    std::unique_ptr<Communicator> world = worldCommunicator();
    const bool root = world->rank() == 0;
    try {
        const int ranks = world->size();
        const Scene scene = withFluidModel(resolveScene(options.scene), options.model);
        const Backend backend = cudaDeviceAvailable() ? Backend::Cuda : Backend::Cpu;
        const NeighbourMode mode = NeighbourMode::Auto;
        nlohmann::json record;
        record["tool"] = "weir bench --scaling";
        record["commit"] = WEIR_COMMIT;
        record["scene"] = scene.name;
        record["model"] = options.model;
        record["ranks"] = ranks;
        record["backend"] = backendName(backend);
        record["device"] = describeBackend(backend);
        record["steps"] = options.steps;
        record["runs"] = nlohmann::json::array();
        if (root) {
            std::cerr << "weir bench --scaling: " << scene.name << ", fluid model " << options.model
                      << ", " << ranks << " ranks on " << backendName(backend) << " ("
                      << describeBackend(backend) << "), " << options.steps
                      << " steps per block, median of 5 blocks\n";
        }
        for (const std::string& text : splitList(options.sizes)) {
            const std::int64_t n =
                parseCount(text, "--sizes", 1, kMaxParticles, kParticleLimitText);
            // Baseline: the plain solver on rank 0 alone.
            std::unique_ptr<Communicator> first = world->firstRanks(1);
            Timing one;
            if (first != nullptr) {
                auto plain = makeSimulation(backend, mode, setupFor(scene, n));
                one = timeSteps(*plain, *first, options.warmup, options.steps, 5);
            }
            std::vector<double> shared{one.stepMs, double(one.particles)};
            world->maxInPlace(shared);
            one.stepMs = shared[0];
            one.particles = std::int64_t(shared[1]);
            std::string transport, hostTransport;
            const Timing weak = distributedTiming(*world, scene, n * ranks, backend, mode, options,
                                                  HaloTransport::Auto, &transport);
            const Timing strong = distributedTiming(*world, scene, n, backend, mode, options,
                                                    HaloTransport::Auto, &transport);
            nlohmann::json run;
            run["transport"] = transport;
            if (transport != "host" && ranks > 1) {
                // The same weak run with ghosts staged through the host, for comparison.
                const Timing staged =
                    distributedTiming(*world, scene, n * ranks, backend, mode, options,
                                      HaloTransport::Host, &hostTransport);
                run["weakHostStaged"] = {{"stepMs", staged.stepMs},
                                         {"exchangeMs", staged.exchangeMs},
                                         {"efficiency", one.stepMs / staged.stepMs}};
            }
            auto put = [](const Timing& t) {
                return nlohmann::json{{"particles", t.particles},
                                      {"stepMs", t.stepMs},
                                      {"exchangeMs", t.exchangeMs},
                                      {"ghostsMax", t.ghosts},
                                      {"bytesSentPerStep", t.bytesSent}};
            };
            run["single"] = put(one);
            run["weak"] = put(weak);
            run["strong"] = put(strong);
            run["weakEfficiency"] = one.stepMs / weak.stepMs;
            run["strongEfficiency"] = one.stepMs / (ranks * strong.stepMs);
            run["strongSpeedup"] = one.stepMs / strong.stepMs;
            record["runs"].push_back(run);
            if (root) {
                std::printf(
                    "%lld particles on 1 rank: %.4f ms/step | weak: %lld on %d ranks %.4f ms/step, "
                    "efficiency %.1f%% (ghosts %lld on the busiest rank, %.1f MB sent per step, "
                    "exchange %.3f ms) | strong: %lld on %d ranks %.4f ms/step, speedup %.2f, "
                    "efficiency %.1f%%\n",
                    (long long)one.particles, one.stepMs, (long long)weak.particles, ranks,
                    weak.stepMs, 100 * run["weakEfficiency"].get<double>(), (long long)weak.ghosts,
                    weak.bytesSent / 1e6, weak.exchangeMs, (long long)strong.particles, ranks,
                    strong.stepMs, run["strongSpeedup"].get<double>(),
                    100 * run["strongEfficiency"].get<double>());
                std::printf("  halo transport %s", transport.c_str());
                if (run.contains("weakHostStaged")) {
                    std::printf(
                        "; weak with the halo staged through the host: %.4f ms/step, "
                        "efficiency %.1f%%",
                        run["weakHostStaged"]["stepMs"].get<double>(),
                        100 * run["weakHostStaged"]["efficiency"].get<double>());
                }
                std::printf("\n");
                std::fflush(stdout);
            }
        }
        if (root) {
            std::filesystem::create_directories(options.outDir);
            const std::string path = options.outDir + "/scaling.json";
            writeFileAtomically(path, [&](std::ostream& out) { out << record.dump(2) << "\n"; });
            std::cerr << "weir bench --scaling: wrote " << path << "\n";
        }
        return kExitOk;
    } catch (...) {
        return reportCaughtError(*world);
    }
}

}  // namespace weir
