// weir's command line: `weir run`, `weir render`, `weir mesh`, `weir view`, `weir bench`,
// `weir info`.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cstdlib>
#include <iostream>

#include "cli/commands.h"
#include "cli/count_option.h"
#include "cluster/communicator.h"
#include "core/backend.h"
#include "io/field_registry.h"
#include "io/frame_formats.h"
#include "io/mesh_writer.h"
#include "scene/scene.h"
#if defined(WEIR_HAS_RENDER)
#include "cli/render_commands.h"
#include "cli/sprite_timer.h"
#endif

namespace {

constexpr const char* kNoRendering =
    "weir: error: this weir was built without rendering (OpenGL, EGL, GLFW or libpng were not "
    "found when it was configured). On Debian/Ubuntu: apt-get install libglfw3-dev libegl-dev "
    "libgl-dev libpng-dev libegl-mesa0 libgl1-mesa-dri, then configure and build again (or run "
    "scripts/setup.sh).\n";

// The colourable fields of the field registry (render/colour_map.h colours by these).
std::vector<std::string> colourChoiceNames() {
    std::vector<std::string> names;
    for (const weir::FieldInfo& field : weir::particleFieldInfo()) {
        if (!field.colourName.empty()) {
            names.push_back(field.colourName);
        }
    }
    return names;
}

std::string colourChoices() {
    std::string list;
    for (const std::string& name : colourChoiceNames()) {
        list += (list.empty() ? "" : ", ") + name;
    }
    return list;
}

// --format of weir run: a frame format's name, or why this build lacks it (no OpenVDB).
CLI::Validator frameFormatValidator() {
    return CLI::Validator(
        [](std::string& text) -> std::string {
            try {
                weir::parseFrameFormat(text);
                return "";
            } catch (const std::invalid_argument& e) {
                return e.what();
            }
        },
        "FORMAT", "frame format");
}

// FRAMES_DIR of the commands that read a run's frames (render, mesh, usd).
void addFramesDirectory(CLI::App* cmd, std::string& dir) {
    cmd->add_option("FRAMES_DIR", dir, "Frames directory written by `weir run` (holds frames.json)")
        ->required();
}

// --frame N and --frames A:B of the commands that read a run's frames (render, mesh).
void addFrameSelection(CLI::App* cmd, std::optional<std::int64_t>& frame, std::string& frames) {
    CLI::Option* one = cmd->add_option("--frame", frame, "Only frame N (its index in frames.json)")
                           ->transform(weir::countOption(0, 99999999));
    CLI::Option* range = cmd->add_option(
        "--frames", frames, "Only frames A to B, both included (A:B; A: from A on, :B up to B)");
    one->excludes(range);
}

// The drawing options `weir render` and `weir run --render` share.
// --surface-field isotropic|anisotropic, for the commands that build surfaces.
void addSurfaceField(CLI::App* cmd, std::string& field, const std::string& lead) {
    cmd->add_option("--surface-field", field,
                    lead +
                        "isotropic (Zhu & Bridson's blobs, the default) or anisotropic (Yu & "
                        "Turk's kernels stretched along the fluid: thin sheets stay thin, lone "
                        "particles round drops; free surfaces 0.3 spacings in; docs/surfaces.md)")
        ->check(CLI::IsMember({"isotropic", "anisotropic"}))
        ->capture_default_str();
}

void addImageOptions(CLI::App* cmd, weir::RenderOptions& o) {
    cmd->add_option("--width", o.width, "Image width in pixels")
        ->check(CLI::Range(16, 16384))
        ->capture_default_str();
    cmd->add_option("--height", o.height, "Image height in pixels")
        ->check(CLI::Range(16, 16384))
        ->capture_default_str();
    cmd->add_option("--color,--colour", o.color, "Particle colour by: " + colourChoices())
        ->check(CLI::IsMember(colourChoiceNames()))
        ->capture_default_str();
    cmd->add_option("--camera", o.camera,
                    "Camera as yaw,pitch,distance (degrees, degrees, metres); default: framed "
                    "on the container, yaw 25, pitch 20");
    cmd->add_option("--target", o.target,
                    "Point the camera looks at, x,y,z (default: the container's centre)");
    cmd->add_option("--samples", o.samples,
                    "Samples per pixel: multisampling of the preview look (1..16, 1 = off, "
                    "default 4); paths per pixel of `weir render --look water` (1..65536, "
                    "default 32)")
        ->check(CLI::Range(1, 65536));
}

}  // namespace

// OpenMP threads that wait for work spin by default (libgomp: 300 000 turns before sleeping).
// On a machine shared with one other busy process, a spinning thread holds a core that the thread
// it waits for needs, and a small run took 13x longer (issue 20). So weir's threads sleep while
// they wait, unless the user chose a policy in OMP_WAIT_POLICY. libgomp reads its environment
// once, as it loads (before main), so the choice takes a re-exec of this same binary; if that
// fails, weir runs on with the runtime's default.
void sleepWhileWaitingUnlessChosen(char** argv) {
    if (std::getenv("OMP_WAIT_POLICY") != nullptr) {
        return;
    }
    ::setenv("OMP_WAIT_POLICY", "passive", 1);
    ::setenv("WEIR_SET_OMP_WAIT_POLICY", "1", 1);  // for `weir info`: who chose it
    ::execv("/proc/self/exe", argv);
}

int weirMain(int argc, char** argv);

int main(int argc, char** argv) {
    sleepWhileWaitingUnlessChosen(argv);
    // Under mpirun: MPI first, and one GPU per rank of each host (cluster/).
    weir::startCommunication(&argc, &argv);
    if (weir::launchedByMpi()) {
        weir::selectCudaDevice(weir::localRank());
    }
    const int code = weirMain(argc, argv);
    weir::endCommunication();
    return code;
}

int weirMain(int argc, char** argv) {
    using namespace weir;
    CLI::App app{"weir: SPH fluid animation on CPU and NVIDIA GPUs", "weir"};
    app.set_version_flag("--version", std::string(WEIR_VERSION));
    app.require_subcommand(1);

    RunOptions run;
    std::string scenes;
    for (const std::string& name : builtinSceneNames()) {
        scenes += (scenes.empty() ? "" : ", ") + name;
    }
    CLI::App* runCmd = app.add_subcommand(
        "run",
        "Simulate a scene and write particle frames (started by mpirun -n R: one simulation "
        "across R ranks, one GPU each; see docs/cluster.md)");
    runCmd->add_option("scene", run.scene,
                       "Scene JSON file or built-in scene (" + scenes + "); default dam_break");
    runCmd
        ->add_option("--model", run.model,
                     "Run the scene with this fluid.model: delta-sph (the default: Wendland "
                     "kernel, density diffusion, the fluid's own viscosity) or paper (Müller et "
                     "al. 2003 as the paper has it); default: the scene's")
        ->check(CLI::IsMember({"paper", "delta-sph"}));
    runCmd
        ->add_option("--solver", run.solver,
                     "Run the scene with this pressure solver: wcsph (weakly compressible, the "
                     "default) or dfsph (divergence-free SPH: incompressible, a time step set by "
                     "the flow's speed); default: the scene's \"solver\"")
        ->check(CLI::IsMember({"wcsph", "dfsph"}));
    runCmd->add_option("--backend", run.backend, "auto (GPU if present), cuda or cpu")
        ->check(CLI::IsMember({"auto", "cuda", "cpu"}))
        ->capture_default_str();
    runCmd
        ->add_option("--neighbours", run.neighbours,
                     "auto, grid (paper §6.2 cell and neighbour tables), dense (same sort, "
                     "dense cell table: faster) or brute (O(N^2), for comparison)")
        ->check(CLI::IsMember({"auto", "grid", "dense", "brute"}))
        ->capture_default_str();
    runCmd
        ->add_option("--particles,-n", run.particles,
                     "Particle count, e.g. 20000, 20k, 5M, 1e9 (overrides the scene)")
        ->transform(countOption(1, kMaxParticles, kParticleLimitText));
    runCmd->add_option("--frames", run.frames, "Stop after this many frames (default: duration)")
        ->transform(countOption(0, std::int64_t(1) << 40));
    runCmd->add_option("--out,-o", run.outDir, "Output directory (default out/<scene name>)");
    runCmd->add_flag("--overwrite", run.overwrite,
                     "Replace the frames of an earlier run in the output directory (they are "
                     "removed first, with its images/, mesh/ and whitewater/ files); without it "
                     "such a directory is refused");
    runCmd->add_option("--format", run.format, "Frame format. " + frameFormatHelp())
        ->check(frameFormatValidator())
        ->capture_default_str();
    runCmd
        ->add_option("--first-frame-number", run.firstFrameNumber,
                     "Number of the first frame (the initial state) in file names and "
                     "frames.json: 1 for tools that count frames from 1 (Houdini's $F)")
        ->transform(countOption(0, 1000000))
        ->capture_default_str();
    runCmd->add_flag("--explain", run.explain, "Print the derived parameters and why");
    runCmd->add_flag("--quiet,-q", run.quiet, "No progress line");
    RenderOptions runRender;
    MeshOptions runMesh;
    runCmd->add_flag("--render", run.render,
                     "Also render every frame to OUT/images/frame_NNNNN.png (offscreen, EGL)");
    runCmd->add_flag("--surface", runRender.surface,
                     "With --render: draw the fluid's surface instead of particles");
    addImageOptions(runCmd, runRender);
    runCmd->add_flag("--mesh", run.mesh,
                     "Also write every frame's surface to OUT/mesh/surface_NNNNN.obj/.ply");
    runCmd->add_option("--mesh-format", runMesh.formats, "With --mesh: " + meshFormatHelp())
        ->capture_default_str();
    UsdOptions runUsd;
    runCmd->add_flag("--usd", run.usd,
                     "Also write all frames (and, with --mesh, the surfaces) as one USD stage, "
                     "OUT/frames.usda, after the last frame");
    WhitewaterOptions runWhitewater;
    bool runWithWhitewater = false;
    runCmd->add_flag("--whitewater", runWithWhitewater,
                     "Also write every frame's spray, foam and bubbles to "
                     "OUT/whitewater/whitewater_NNNNN.ply (as `weir whitewater` does)");
    addSurfaceField(runCmd, runMesh.surfaceField,
                    "With --mesh (and --render --surface): the surface field, ");
    runCmd->add_option("--cell-size", runMesh.cellSize,
                       "With --mesh or --format vdb: marching-cubes cell and voxel in metres "
                       "(default half the spacing)");

    BenchOptions bench;
    CLI::App* benchCmd = app.add_subcommand(
        "bench", "Time every stage of the step: the paper's Tables 1-3 on this machine");
    benchCmd->add_option("scene", bench.scene, "Scene file or built-in scene; default dam_break");
    benchCmd
        ->add_option("--model", bench.model,
                     "fluid.model timed, whatever the scene says: paper (the paper's system, "
                     "as in its Tables 1-3) or delta-sph (weir's default model)")
        ->check(CLI::IsMember({"paper", "delta-sph"}))
        ->capture_default_str();
    benchCmd
        ->add_option("--solver", bench.solver,
                     "Pressure solver timed: wcsph or dfsph (with --model delta-sph); default: "
                     "the scene's \"solver\"")
        ->check(CLI::IsMember({"wcsph", "dfsph"}));
    benchCmd->add_option("--sizes", bench.sizes, "Particle counts, e.g. 10k,50k,100k,1M,1e9")
        ->capture_default_str();
    benchCmd
        ->add_option("--backends,--columns", bench.columns,
                     "auto, or a list of cpu-brute, cpu-grid, cpu-dense, cuda-brute, "
                     "cuda-grid, cuda-dense")
        ->capture_default_str();
    benchCmd->add_option("--steps", bench.steps, "Timed steps; stage times are their medians")
        ->transform(countOption(1, 100000))
        ->capture_default_str();
    benchCmd->add_option("--warmup", bench.warmup, "Untimed steps before timing")
        ->transform(countOption(0, 100000))
        ->capture_default_str();
    benchCmd
        ->add_option("--settle", bench.settle,
                     "Simulated seconds before timing, so the fluid is in motion")
        ->check(CLI::Range(0.0, 100.0))
        ->capture_default_str();
    benchCmd
        ->add_option("--budget", bench.budget,
                     "Seconds allowed per size and column; slower runs are skipped, never "
                     "extrapolated")
        ->check(CLI::Range(0.0, 1e6))
        ->capture_default_str();
    benchCmd->add_option("--out,-o", bench.outDir, "Directory for bench.json, bench.csv, bench.png")
        ->capture_default_str();
    benchCmd->add_flag("--no-plot", bench.noPlot, "Skip the PNG plot");
    benchCmd->add_flag("--scaling", bench.scaling,
                       "Weak and strong scaling of distributed runs: start under mpirun -n R; "
                       "--sizes are particles per rank (weak) and in all (strong)");
    benchCmd->add_flag("--no-render", bench.noRender,
                       "Skip the point-sprite rendering row (drawn offscreen with OpenGL)");

    RenderOptions render;
    CLI::App* renderCmd = app.add_subcommand(
        "render", "Render the frames of a run to PNG images (and an MP4 with ffmpeg), offscreen");
    addFramesDirectory(renderCmd, render.framesDir);
    renderCmd->add_option("--out,-o", render.outDir, "Images directory (default FRAMES/images)");
    addImageOptions(renderCmd, render);
    renderCmd->add_option("--scene", render.scene,
                          "Scene file or built-in scene whose container and obstacles are drawn "
                          "(default: the run's own, recorded in frames.json; else a box around "
                          "the particles)");
    renderCmd
        ->add_option("--look", render.look,
                     "preview: particles or (--surface) the surface drawn with OpenGL; water: the "
                     "surface path traced as water (refraction, reflection, absorption; no "
                     "OpenGL needed; docs/rendering.md)")
        ->check(CLI::IsMember({"preview", "water"}))
        ->capture_default_str();
    renderCmd->add_flag("--surface", render.surface,
                        "Draw the fluid's surface (marching cubes) instead of particles");
    renderCmd->add_option("--export-water", render.exportWater,
                          "With --look water: also write what is traced into this folder, for "
                          "other renderers: per frame the water's triangles (.obj), camera and "
                          "constants (.json), linear radiance (.pfm); sky.hdr (docs/rendering.md)");
    renderCmd
        ->add_option("--motion-blur", render.motionBlur,
                     "With --look water: blur the moving surface as a camera whose shutter is open "
                     "for this share of the time between frames (0.5: a 180-degree shutter; "
                     "default 0: none), traced in up to 8 time slices")
        ->check(CLI::Range(0.0, 1.0));
    addSurfaceField(renderCmd, render.surfaceField, "With --surface: the surface field, ");
    renderCmd
        ->add_option("--backend", render.backend,
                     "Where --surface is reconstructed and --look water traced: auto, cuda or "
                     "cpu")
        ->check(CLI::IsMember({"auto", "cuda", "cpu"}))
        ->capture_default_str();
    renderCmd->add_option("--spacing", render.spacing,
                          "Particle spacing in metres: sets the sphere size and the surface's "
                          "scale (default: the run's, from frames.json; else from the scene, "
                          "else measured on the first frame)");
    renderCmd->add_option("--video", render.video,
                          "Also encode the images into this .mp4 with ffmpeg (H.264)");
    CLI::Option* withWhitewater = renderCmd->add_option(
        "--whitewater", render.whitewater,
        "Folder of whitewater_NNNNN.ply files (weir whitewater) to draw with the fluid: white "
        "sprites (preview), white matte octahedra (water look); default FRAMES/whitewater where "
        "it exists");
    renderCmd->add_flag("--no-whitewater", render.noWhitewater, "Draw no spray, foam or bubbles")
        ->excludes(withWhitewater);
    renderCmd->add_flag("--quiet,-q", render.quiet, "No progress line");
    addFrameSelection(renderCmd, render.frame, render.frames);

    MeshOptions mesh;
    CLI::App* meshCmd = app.add_subcommand(
        "mesh",
        "Reconstruct the fluid surface of each frame (marching cubes): OBJ and PLY files, or "
        "OpenVDB level sets");
    addFramesDirectory(meshCmd, mesh.framesDir);
    meshCmd->add_option("--out,-o", mesh.outDir, "Mesh directory (default FRAMES/mesh)");
    meshCmd->add_option("--format", mesh.formats, "Mesh formats: " + meshFormatHelp())
        ->capture_default_str();
    meshCmd->add_option("--backend", mesh.backend, "auto (GPU if present), cuda or cpu")
        ->check(CLI::IsMember({"auto", "cuda", "cpu"}))
        ->capture_default_str();
    meshCmd->add_option("--spacing", mesh.spacing,
                        "Particle spacing in metres (default: the run's, from frames.json; "
                        "else measured on the first frame)");
    meshCmd->add_option("--cell-size", mesh.cellSize,
                        "Marching-cubes cell in metres (default half the spacing)");
    meshCmd
        ->add_option("--iso", mesh.iso,
                     "Iso-value in particle spacings: 0 is the fluid surface, > 0 inflates it")
        ->capture_default_str();
    addSurfaceField(meshCmd, mesh.surfaceField, "The surface field, ");
    meshCmd->add_flag("--quiet,-q", mesh.quiet, "No progress line");
    addFrameSelection(meshCmd, mesh.frame, mesh.frames);

    UsdOptions usd;
    CLI::App* usdCmd = app.add_subcommand(
        "usd",
        "Write a run's frames, its surface meshes (weir mesh) and its container and obstacles as "
        "one USD stage (.usda, time-sampled) for Blender, Houdini and usdview");
    addFramesDirectory(usdCmd, usd.framesDir);
    usdCmd->add_option("--out,-o", usd.outPath, "The stage (default FRAMES/frames.usda)");
    usdCmd->add_option("--mesh-dir", usd.meshDir,
                       "Where the surface_NNNNN.ply/.obj meshes are (default FRAMES/mesh)");
    usdCmd->add_flag("--no-meshes", usd.noMeshes, "Leave the surface meshes out");
    usdCmd->add_option("--scene", usd.scene,
                       "Scene whose container and obstacles go in (default: the run's own)");
    usdCmd->add_option("--spacing", usd.spacing,
                       "Particle spacing in metres: the points' width (default: the run's)");
    addFrameSelection(usdCmd, usd.frame, usd.frames);

    WhitewaterOptions whitewater;
    CLI::App* whitewaterCmd = app.add_subcommand(
        "whitewater",
        "Spray, foam and bubbles (Ihmsen et al. 2012): diffuse particles generated where the "
        "fluid traps air, breaks into crests and moves fast, advanced from frame to frame; "
        "whitewater_NNNNN.ply per frame (CPU)");
    addFramesDirectory(whitewaterCmd, whitewater.framesDir);
    whitewaterCmd->add_option("--out,-o", whitewater.outDir,
                              "Whitewater directory (default FRAMES/whitewater)");
    whitewaterCmd->add_option(
        "--frames", whitewater.frames,
        "Only frames A to B, both included (A:B; A: from A on, :B up to B); frame A has none");
    whitewaterCmd
        ->add_option("--max-particles", whitewater.maxParticles,
                     "At most this many diffuse particles; generation stops at the cap")
        ->transform(countOption(0, std::int64_t(1) << 40))
        ->capture_default_str();
    whitewaterCmd
        ->add_option("--rate", whitewater.rate,
                     "Diffuse particles per fluid particle per second at full potential "
                     "(the paper's k_ta and k_wc)")
        ->check(CLI::Range(0.0, 1e6))
        ->capture_default_str();
    whitewaterCmd
        ->add_option("--lifetime", whitewater.lifetime,
                     "Foam's mean lifetime in seconds (each lives 0.5..1.5 times it)")
        ->check(CLI::Range(1e-6, 1e6))
        ->capture_default_str();
    whitewaterCmd
        ->add_option("--substeps", whitewater.substeps,
                     "Advection sub-steps per frame interval (0: enough that none moves more "
                     "than h/2 in one)")
        ->check(CLI::Range(0, 10000))
        ->capture_default_str();
    whitewaterCmd->add_flag("--explain", whitewater.explain,
                            "Print the scale, the thresholds in physical units, the potentials "
                            "of the first frame and every frame's counts");
    whitewaterCmd->add_flag("--quiet,-q", whitewater.quiet, "No progress line");

    ViewOptions view;
    CLI::App* viewCmd = app.add_subcommand(
        "view",
        "Simulate a scene in a window and draw it as it runs. Keys: space pause, s single step, "
        "r reset, c colouring, m particles/surface, w water look (live path tracing, CUDA), "
        "f frame the scene, arrows orbit, +/- zoom, q quit. Mouse: left drag orbit, right (or "
        "shift+left) drag pan, wheel zoom");
    viewCmd->add_option("scene", view.scene,
                        "Scene JSON file or built-in scene (" + scenes + "); default dam_break");
    viewCmd->add_option("--backend", view.backend, "auto (GPU if present), cuda or cpu")
        ->check(CLI::IsMember({"auto", "cuda", "cpu"}))
        ->capture_default_str();
    viewCmd->add_option("--neighbours", view.neighbours, "auto, grid, dense or brute")
        ->check(CLI::IsMember({"auto", "grid", "dense", "brute"}))
        ->capture_default_str();
    viewCmd
        ->add_option("--particles,-n", view.particles,
                     "Particle count, e.g. 20000, 20k, 5M (overrides the scene)")
        ->transform(countOption(1, kMaxParticles, kParticleLimitText));
    viewCmd->add_option("--width", view.width, "Window width in pixels")
        ->check(CLI::Range(16, 16384))
        ->capture_default_str();
    viewCmd->add_option("--height", view.height, "Window height in pixels")
        ->check(CLI::Range(16, 16384))
        ->capture_default_str();
    viewCmd->add_option("--color,--colour", view.color, "Particle colour by: " + colourChoices())
        ->check(CLI::IsMember(colourChoiceNames()))
        ->capture_default_str();
    viewCmd->add_option("--camera", view.camera, "Camera as yaw,pitch,distance");
    viewCmd->add_option("--target", view.target, "Point the camera looks at, x,y,z");
    viewCmd
        ->add_option("--max-frames", view.maxFrames,
                     "Close after drawing this many frames (0: when the window is closed)")
        ->transform(countOption(0, std::int64_t(1) << 40))
        ->capture_default_str();
    viewCmd->add_option("--press", view.press,
                        "Keys pressed on successive frames, for demos and tests, e.g. "
                        "none,c,m,space (names: space s r c m f q left right up down plus minus "
                        "escape none)");
    viewCmd->add_option("--screenshot", view.screenshot,
                        "With --max-frames: save the last frame drawn to this PNG");
    viewCmd->add_option("--record", view.record,
                        "Record every frame drawn into this .mp4 (needs ffmpeg on PATH)");

    ValidateOptions validate;
    CLI::App* validateCmd = app.add_subcommand(
        "validate",
        "Check the physics against analytic solutions and experiments (hydrostatic tank, Martin & "
        "Moyce and Lobovsky dam breaks, water/oil/honey, Poiseuille and Couette flow, the "
        "Taylor-Green vortex), with tolerances; writes CSV, JSON and PNG plots");
    validateCmd->add_option("--backend", validate.backend, "auto (GPU if present), cuda or cpu")
        ->check(CLI::IsMember({"auto", "cuda", "cpu"}))
        ->capture_default_str();
    validateCmd
        ->add_option("--tank-resolution", validate.tankResolution,
                     "Particles over the tank's water depth")
        ->transform(countOption(6, 400))
        ->capture_default_str();
    validateCmd
        ->add_option("--column-resolution", validate.columnResolutions,
                     "Particles across the dam-break column's width; several (e.g. 12,24,48) run "
                     "a resolution ladder, the finest held to the tolerances")
        ->delimiter(',')
        ->transform(countOption(6, 400))
        ->capture_default_str();
    validateCmd
        ->add_option("--model", validate.model,
                     "fluid.model of every case: paper or delta-sph (default: the scenes' own "
                     "default, delta-sph)")
        ->check(CLI::IsMember({"paper", "delta-sph"}));
    validateCmd
        ->add_option("--solver", validate.solver,
                     "Pressure solver of every case: wcsph or dfsph (default: the scenes' own, "
                     "wcsph)")
        ->check(CLI::IsMember({"wcsph", "dfsph"}));
    validateCmd
        ->add_option("--cases", validate.cases,
                     "Comma-separated cases: hydrostatic, dam-break (Martin & Moyce, over the "
                     "ladder), viscous (water, oil, honey at the coarsest rung), channels "
                     "(start-up Poiseuille and Couette flow, Morris et al. 1997), lobovsky "
                     "(Lobovsky et al. 2014: front and impact pressures), taylor-green (the "
                     "2-D vortex at Re 100)")
        ->capture_default_str();
    validateCmd
        ->add_option("--taylor-green-resolution", validate.taylorGreenResolutions,
                     "Particles across the Taylor-Green vortex's periodic box; several (e.g. "
                     "32,64,128) run a resolution ladder, the finest held to the tolerance")
        ->delimiter(',')
        ->transform(countOption(8, 400))
        ->capture_default_str();
    validateCmd
        ->add_option("--shifting", validate.shifting,
                     "fluid.shifting of every case (delta-sph): particle shifting's coefficient "
                     "as a multiple of Sun et al.'s, 0 off (default: off, but 1 in the "
                     "Taylor-Green case)")
        ->check(CLI::Range(0.0, 10.0));
    validateCmd
        ->add_option("--smoothing-ratio", validate.smoothingRatio,
                     "particles.smoothingRatio (h / d, the kernel's support over the spacing) of "
                     "every case (default: the scenes' default)")
        ->check(CLI::Range(1.2, 5.0));
    validateCmd
        ->add_option("--lobovsky-resolution", validate.lobovskyResolution,
                     "Particles over the height of the Lobovsky et al. column (H = 0.3 m)")
        ->transform(countOption(6, 400))
        ->capture_default_str();
    validateCmd
        ->add_option("--channel-resolution", validate.channelResolution,
                     "Particles across the Poiseuille and Couette channels")
        ->transform(countOption(6, 400))
        ->capture_default_str();
    validateCmd
        ->add_option("--end-time", validate.damEndT,
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
        run.cellSize = runMesh.cellSize;
        try {
            RunObserverList observers;
            // Before the renderer, which draws each frame's whitewater once it is written.
            if (runWithWhitewater) {
                observers.add(makeRunWhitewater(runWhitewater));
            }
            if (run.render) {
#if defined(WEIR_HAS_RENDER)
                runRender.backend = run.backend;
                runRender.quiet = run.quiet;
                runRender.surfaceField = runMesh.surfaceField;
                observers.add(makeRunRenderer(runRender));
#else
                std::cerr << kNoRendering;
                return kExitError;
#endif
            } else if (runRender.surface) {
                std::cerr << "weir: error: --surface draws surfaces in rendered images and needs "
                             "--render (for mesh files use --mesh)\n";
                return kExitUsage;
            }
            if (run.mesh) {
                runMesh.backend = run.backend;
                observers.add(makeRunMesher(runMesh));
            }
            if (run.usd) {
                observers.add(makeRunUsdWriter(runUsd));
            }
            return runCommand(run, observers.empty() ? nullptr : &observers);
        } catch (const std::invalid_argument& e) {
            std::cerr << "weir: error: " << e.what() << "\n";
            return kExitUsage;
        }
    }
    if (renderCmd->parsed()) {
#if defined(WEIR_HAS_RENDER)
        return renderCommand(render);
#else
        std::cerr << kNoRendering;
        return kExitError;
#endif
    }
    if (viewCmd->parsed()) {
#if defined(WEIR_HAS_RENDER)
        return viewCommand(view);
#else
        std::cerr << kNoRendering;
        return kExitError;
#endif
    }
    if (meshCmd->parsed()) {
        return meshCommand(mesh);
    }
    if (usdCmd->parsed()) {
        return usdCommand(usd);
    }
    if (whitewaterCmd->parsed()) {
        return whitewaterCommand(whitewater);
    }
    if (benchCmd->parsed()) {
        std::unique_ptr<SpriteDrawTimer> spriteTimer;
#if defined(WEIR_HAS_RENDER)
        if (!bench.noRender && !bench.scaling) {
            try {
                spriteTimer = makeSpriteDrawTimer();
            } catch (const std::exception& e) {
                std::cerr << "weir bench: no point-sprite row, no OpenGL context: " << e.what()
                          << "\n";
            }
        }
#endif
        return benchCommand(bench, spriteTimer.get());
    }
    if (validateCmd->parsed()) {
        return validateCommand(validate);
    }
#if defined(WEIR_HAS_RENDER)
    return infoCommand(true);
#else
    return infoCommand(false);
#endif
}
