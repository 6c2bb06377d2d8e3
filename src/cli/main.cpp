// weir's command line: `weir run`, `weir info`.
#include <CLI/CLI.hpp>

#include <iostream>

#include "cli/commands.h"
#include "scene/scene.h"

int main(int argc, char** argv) {
    using namespace weir;
    CLI::App app{"weir: SPH fluid animation on CPU and NVIDIA GPUs", "weir"};
    app.set_version_flag("--version", std::string(WEIR_VERSION));
    app.require_subcommand(1);

    RunOptions run;
    std::string scenes;
    for (const std::string& name : builtinSceneNames()) {
        scenes += (scenes.empty() ? "" : ", ") + name;
    }
    CLI::App* runCmd = app.add_subcommand("run", "Simulate a scene and write particle frames");
    runCmd->add_option("scene", run.scene,
                       "Scene JSON file or built-in scene (" + scenes + "); default dam_break");
    runCmd->add_option("--backend", run.backend, "auto (GPU if present), cuda or cpu")
        ->check(CLI::IsMember({"auto", "cuda", "cpu"}))
        ->capture_default_str();
    runCmd->add_option("--neighbours", run.neighbours,
                       "auto, grid (paper §6.2 cell and neighbour tables), dense (same sort, "
                       "dense cell table: faster) or brute (O(N^2), for comparison)")
        ->check(CLI::IsMember({"auto", "grid", "dense", "brute"}))
        ->capture_default_str();
    runCmd->add_option("--particles,-n", run.particles, "Particle count (overrides the scene)")
        ->check(CLI::Range(std::int64_t(1), std::int64_t(2147483647)));
    runCmd->add_option("--frames", run.frames, "Stop after this many frames (default: duration)")
        ->check(CLI::Range(std::int64_t(0), std::int64_t(1) << 40));
    runCmd->add_option("--out,-o", run.outDir, "Output directory (default out/<scene name>)");
    runCmd->add_option("--format", run.format, "Frame format: vtu (+ .pvd), ply or csv")
        ->check(CLI::IsMember({"vtu", "ply", "csv"}))
        ->capture_default_str();
    runCmd->add_flag("--explain", run.explain, "Print the derived parameters and why");
    runCmd->add_flag("--quiet,-q", run.quiet, "No progress line");

    BenchOptions bench;
    CLI::App* benchCmd = app.add_subcommand(
        "bench", "Time every stage of the step: the paper's Tables 1-3 on this machine");
    benchCmd->add_option("scene", bench.scene, "Scene file or built-in scene; default dam_break");
    benchCmd->add_option("--sizes", bench.sizes, "Particle counts, e.g. 10k,50k,100k,1M")
        ->capture_default_str();
    benchCmd->add_option("--backends,--columns", bench.columns,
                         "auto, or a list of cpu-brute, cpu-grid, cpu-dense, cuda-brute, "
                         "cuda-grid, cuda-dense")
        ->capture_default_str();
    benchCmd->add_option("--steps", bench.steps, "Timed steps; stage times are their medians")
        ->check(CLI::Range(1, 100000))
        ->capture_default_str();
    benchCmd->add_option("--warmup", bench.warmup, "Untimed steps before timing")
        ->check(CLI::Range(0, 100000))
        ->capture_default_str();
    benchCmd->add_option("--settle", bench.settle,
                         "Simulated seconds before timing, so the fluid is in motion")
        ->check(CLI::Range(0.0, 100.0))
        ->capture_default_str();
    benchCmd->add_option("--budget", bench.budget,
                         "Seconds allowed per size and column; slower runs are skipped, never "
                         "extrapolated")
        ->check(CLI::Range(0.0, 1e6))
        ->capture_default_str();
    benchCmd->add_option("--out,-o", bench.outDir, "Directory for bench.json, bench.csv, bench.png")
        ->capture_default_str();
    benchCmd->add_flag("--no-plot", bench.noPlot, "Skip the PNG plot");

    ValidateOptions validate;
    CLI::App* validateCmd = app.add_subcommand(
        "validate",
        "Check the physics: a hydrostatic tank and the Martin & Moyce (1952) dam break, with "
        "tolerances; writes CSV, JSON and PNG plots");
    validateCmd->add_option("--backend", validate.backend, "auto (GPU if present), cuda or cpu")
        ->check(CLI::IsMember({"auto", "cuda", "cpu"}))
        ->capture_default_str();
    validateCmd->add_option("--tank-resolution", validate.tankResolution,
                            "Particles over the tank's water depth")
        ->check(CLI::Range(6, 400))
        ->capture_default_str();
    validateCmd->add_option("--column-resolution", validate.columnResolution,
                            "Particles across the dam-break column's width")
        ->check(CLI::Range(6, 400))
        ->capture_default_str();
    validateCmd->add_option("--end-time", validate.damEndT,
                            "Dam break end, in T = t sqrt(2 g / a) (data reach 9.2)")
        ->check(CLI::Range(1.0, 9.3))
        ->capture_default_str();
    validateCmd->add_option("--out,-o", validate.outDir, "Directory for results and plots")
        ->capture_default_str();
    validateCmd->add_flag("--no-plot", validate.noPlot, "Skip the PNG plots");

    app.add_subcommand("info", "Show the build, the backends and the GPU found");

    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        app.exit(e);
        return kExitUsage;
    }
    if (runCmd->parsed()) {
        return runCommand(run);
    }
    if (benchCmd->parsed()) {
        return benchCommand(bench);
    }
    if (validateCmd->parsed()) {
        return validateCommand(validate);
    }
    return infoCommand();
}
