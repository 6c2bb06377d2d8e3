// Surface reconstruction speed: particles in host memory to a cleaned mesh in host memory, on the
// CPU or the GPU, with each stage's time (surface.h lists them). Input: a frame file of any
// format weir reads, or a synthetic frame of N particles (a jittered body of water under a wavy
// surface with 0.2% spray above it). Output: medians over the repeats, after one warm-up, as text
// and JSON.
//
//   weir_surface_bench --particles 1000000 --backend cuda --repeats 5 --json out.json
//   weir_surface_bench --frame run/frame_00030.ply --spacing 0.005 --backend cuda
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <vector>

#include "core/backend.h"
#include "core/exec_cpu.h"
#include "core/stage_timer.h"
#include "io/frame_index.h"
#include "surface/sliver_cleanup.h"
#include "surface/surface.h"

namespace weir {
namespace {

using Clock = std::chrono::steady_clock;

// A deterministic uniform number in [0, 1) from an integer (splitmix64).
double hashUnit(std::uint64_t k) {
    k += 0x9E3779B97F4A7C15ull;
    k = (k ^ (k >> 30)) * 0xBF58476D1CE4E5B9ull;
    k = (k ^ (k >> 27)) * 0x94D049BB133111EBull;
    k ^= k >> 31;
    return double(k >> 11) * (1.0 / 9007199254740992.0);
}

// About n particles of spacing d: a body of water 2 : 1 : 1 (x : y : z) whose surface height
// h(x, z) = H (0.6 + 0.3 sin(2 pi x / L) cos(2 pi z / W)) waves, each particle jittered by up to
// 0.2 d, and n / 500 drops of spray scattered in a band up to 0.1 H above the surface.
HostParticles syntheticFrame(std::int64_t n, double d) {
    const int m = std::max(4, int(std::cbrt(double(n) / 1.2)));
    const int nx = 2 * m, ny = m, nz = m;
    const double pi = 3.14159265358979323846;
    const auto height = [&](int i, int k) {
        return ny * (0.6 + 0.3 * std::sin(2 * pi * i / nx) * std::cos(2 * pi * k / nz));
    };
    std::vector<std::int64_t> slabEnd(std::size_t(nx), 0);
    CpuExec().forEach(nx, [&](Index i) {
        std::int64_t count = 0;
        for (int k = 0; k < nz; ++k) {
            count += std::int64_t(std::ceil(height(i, k)));
        }
        slabEnd[std::size_t(i)] = count;
    });
    for (int i = 1; i < nx; ++i) {
        slabEnd[std::size_t(i)] += slabEnd[std::size_t(i - 1)];
    }
    const std::int64_t water = slabEnd.back(), spray = water / 500;
    HostParticles particles;
    particles.resize(std::size_t(water + spray));
    CpuExec().forEach(nx, [&](Index i) {
        std::int64_t at = i == 0 ? 0 : slabEnd[std::size_t(i - 1)];
        for (int k = 0; k < nz; ++k) {
            const int top = int(std::ceil(height(i, k)));
            for (int j = 0; j < top; ++j, ++at) {
                const std::uint64_t key = std::uint64_t(at) * 3;
                particles.x[std::size_t(at)] = Real((i + 0.5 + 0.4 * (hashUnit(key) - 0.5)) * d);
                particles.y[std::size_t(at)] =
                    Real((j + 0.5 + 0.4 * (hashUnit(key + 1) - 0.5)) * d);
                particles.z[std::size_t(at)] =
                    Real((k + 0.5 + 0.4 * (hashUnit(key + 2) - 0.5)) * d);
            }
        }
    });
    for (std::int64_t s = 0; s < spray; ++s) {
        const std::uint64_t key = std::uint64_t(water + s) * 3;
        const double x = hashUnit(key) * nx, z = hashUnit(key + 2) * nz;
        const double above = height(int(x), int(z)) + 2 + hashUnit(key + 1) * 0.1 * ny;
        const std::size_t at = std::size_t(water + s);
        particles.x[at] = Real(x * d);
        particles.y[at] = Real(above * d);
        particles.z[at] = Real(z * d);
    }
    return particles;
}

double median(std::vector<double> values) {
    if (values.empty()) {
        return 0;
    }
    std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
    return values[values.size() / 2];
}

int run(int argc, char** argv) {
    CLI::App app{"weir_surface_bench: surface reconstruction speed, particles to a cleaned mesh"};
    std::string frame, backendName = "cuda", fieldName = "isotropic", jsonPath;
    std::int64_t particleCount = 1000000;
    double spacing = 0;
    int repeats = 5;
    bool keepSlivers = false;
    double snapFraction = kSurfaceSnapFraction;
    app.add_option("--frame", frame, "a frame file (vtu, ply, csv, ...); default: synthetic");
    app.add_option("--particles", particleCount, "particles of the synthetic frame")
        ->check(CLI::Range(std::int64_t(1000), std::int64_t(2000000000)));
    app.add_option("--spacing", spacing,
                   "particle spacing in m (synthetic: 0.01; a frame: 0 estimates it)");
    app.add_option("--backend", backendName, "cpu or cuda");
    app.add_option("--surface-field", fieldName, "isotropic or anisotropic");
    app.add_option("--repeats", repeats, "timed repeats after one warm-up")
        ->check(CLI::Range(1, 1000));
    app.add_flag("--keep-slivers", keepSlivers, "skip the sliver cleanup");
    app.add_option("--snap", snapFraction,
                   "keep vertices this fraction of a cell off the samples (0: no snapping)");
    app.add_option("--json", jsonPath, "write the results here as JSON");
    CLI11_PARSE(app, argc, argv);

    const Backend backend = parseBackend(backendName);
    const auto loadStart = Clock::now();
    HostParticles particles;
    if (frame.empty()) {
        if (spacing == 0) {
            spacing = 0.01;
        }
        particles = syntheticFrame(particleCount, spacing);
    } else {
        particles = readFrameFile(frame);
    }
    const double loadSeconds = std::chrono::duration<double>(Clock::now() - loadStart).count();
    SurfaceOptions options;
    options.spacing = spacing;
    options.field = parseSurfaceField(fieldName);
    options.removeSlivers = !keepSlivers;
    options.snapFraction = snapFraction;
    std::cerr << "weir_surface_bench: " << particles.size() << " particles ("
              << (frame.empty() ? "synthetic" : frame) << ", " << loadSeconds << " s to load), "
              << backendName << ", " << fieldName << " field\n";

    StageTimes stages;
    std::vector<double> totalMs, planMs;
    std::size_t triangles = 0, vertices = 0;
    SurfacePlan plan;
    SliverCleanupReport slivers;
    for (int r = 0; r <= repeats; ++r) {
        StageTimes here;
        const auto start = Clock::now();
        plan = planSurface(particles, options);
        plan.removeSlivers = false;  // cleaned here, as reconstructSurface would, for its report
        const auto planned = Clock::now();
        TriangleMesh mesh = reconstructSurface(backend, particles, plan, &here);
        if (!keepSlivers) {
            const auto cleanStart = Clock::now();
            slivers = removeSlivers(mesh, plan.cellSize);
            here.add("surface slivers",
                     std::chrono::duration<double, std::milli>(Clock::now() - cleanStart).count());
        }
        const auto done = Clock::now();
        triangles = mesh.triangleCount();
        vertices = mesh.positions.size();
        if (r == 0) {
            continue;  // warm-up: the CUDA context, first allocations, page faults
        }
        planMs.push_back(std::chrono::duration<double, std::milli>(planned - start).count());
        totalMs.push_back(std::chrono::duration<double, std::milli>(done - start).count());
        for (const auto& [stage, samples] : here.samples()) {
            for (double ms : samples) {
                stages.add(stage, ms);
            }
        }
    }

    const double total = median(totalMs);
    nlohmann::ordered_json out;
    out["particles"] = particles.size();
    out["input"] = frame.empty() ? "synthetic" : frame;
    out["backend"] = backendName;
    out["field"] = fieldName;
    out["snap_fraction"] = snapFraction;
    out["spacing_m"] = plan.spacing;
    out["cell_size_m"] = plan.cellSize;
    out["box_samples"] = plan.sampleCount();
    out["repeats"] = repeats;
    out["vertices"] = vertices;
    out["triangles"] = triangles;
    out["sliver_cleanup"] = {{"bad_triangles", slivers.badTriangles},
                             {"collapses", slivers.collapses},
                             {"flips", slivers.flips},
                             {"specks", slivers.specks},
                             {"left", slivers.left}};
    out["plan_ms_median"] = median(planMs);
    out["total_ms_median"] = total;
    out["total_ms_samples"] = totalMs;
    out["particles_per_second"] = double(particles.size()) / (total / 1000);
    nlohmann::ordered_json stageJson;
    for (const auto& [stage, samples] : stages.samples()) {
        stageJson[stage] = median(samples);
    }
    out["stage_ms_median"] = stageJson;
    std::cout << out.dump(2) << "\n";
    if (!jsonPath.empty()) {
        std::ofstream(jsonPath) << out.dump(2) << "\n";
    }
    return 0;
}

}  // namespace
}  // namespace weir

int main(int argc, char** argv) {
    try {
        return weir::run(argc, argv);
    } catch (const std::exception& e) {
        std::cerr << "weir_surface_bench: " << e.what() << "\n";
        return 1;
    }
}
