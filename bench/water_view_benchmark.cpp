// The live water look's frame rate without a display: a CUDA simulation of a scene (the dam break
// by default) at N particles, and per displayed frame what `weir view` does in its water look:
// `--steps` time steps, the surface on the GPU, the hierarchy built on the GPU, `--paths` paths
// per pixel traced into the accumulation buffer, tone mapping. Reports the median milliseconds
// of each stage and of the whole frame (host clock, the GPU waited for) and the frames per second
// over `--frames` frames after `--warmup`, as text and JSON; then, the fluid standing still,
// `--refine` more frames accumulate, and the image is written (PNG where weir renders, else PPM).
//
//   weir_water_view_bench --particles 1M --frames 100 --out water_view.png --json water_view.json
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <vector>

#include "cli/count_option.h"
#include "raytrace/interactive_water.h"
#include "scene/scene.h"
#include "scene/setup.h"
#include "solver/neighbour_search.h"
#include "solver/simulation.h"
#if defined(WEIR_HAS_RENDER)
#include "render/png_image.h"
#endif

namespace weir {
namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

double median(std::vector<double> values) {
    if (values.empty()) {
        return 0;
    }
    std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
    return values[values.size() / 2];
}

// The viewer's default camera (yaw 25, pitch 20 degrees, 40 degrees of field of view) framing the
// container's bounding sphere.
PinholeCamera framedCamera(const Box& box, int width, int height) {
    const double pi = 3.14159265358979323846, fovY = 40 * pi / 180;
    const double aspect = double(width) / height, yaw = 25 * pi / 180, pitch = 20 * pi / 180;
    const Vec3d centre = (box.min + box.max) * 0.5;
    const double radius = 0.5 * length(box.max - box.min);
    const double fov = aspect < 1 ? 2 * std::atan(std::tan(fovY / 2) * aspect) : fovY;
    const double distance = 1.05 * radius / std::sin(fov / 2);
    const Vec3d toEye(std::sin(yaw) * std::cos(pitch), std::sin(pitch),
                      std::cos(yaw) * std::cos(pitch));
    PinholeCamera camera;
    camera.eye = Vec3f(centre + toEye * distance);
    camera.forward = Vec3f(toEye * -1.0);
    camera.right = normalized(cross(camera.forward, Vec3f(0, 1, 0)));
    camera.up = cross(camera.right, camera.forward);
    camera.tanHalfFovY = float(std::tan(fovY / 2));
    camera.aspect = float(aspect);
    return camera;
}

void writeImage(const std::string& path, int width, int height,
                const std::vector<std::uint8_t>& rgb) {
#if defined(WEIR_HAS_RENDER)
    Image image(width, height);
    image.rgb = rgb;
    writePng(path, image);
#else
    std::ofstream out(path, std::ios::binary);
    out << "P6\n" << width << " " << height << "\n255\n";
    out.write(reinterpret_cast<const char*>(rgb.data()), std::streamsize(rgb.size()));
#endif
}

std::string imagePath(std::string path) {
#if !defined(WEIR_HAS_RENDER)
    if (path.size() > 4 && path.substr(path.size() - 4) == ".png") {
        path = path.substr(0, path.size() - 4) + ".ppm";  // no libpng in this build
    }
#endif
    return path;
}

int run(int argc, char** argv) {
    CLI::App app{"weir_water_view_bench: the live water look's frame rate, simulation included"};
    std::string sceneName = "dam_break", particlesText = "1M", outPath = "water_view.png", jsonPath;
    int width = 1280, height = 720, paths = 1, steps = 1, frames = 100, warmup = 10, refine = 63;
    double settle = 0.5;
    app.add_option("scene", sceneName, "a built-in scene or a scene file");
    app.add_option("--particles", particlesText, "particle count (1M, 100k, ...)");
    app.add_option("--width", width, "image width")->check(CLI::Range(16, 16384));
    app.add_option("--height", height, "image height")->check(CLI::Range(16, 16384));
    app.add_option("--paths", paths, "paths per pixel per frame")->check(CLI::Range(1, 1024));
    app.add_option("--steps", steps, "time steps per frame")->check(CLI::Range(0, 10000));
    app.add_option("--frames", frames, "timed frames")->check(CLI::Range(1, 100000));
    app.add_option("--warmup", warmup, "frames before timing")->check(CLI::Range(0, 100000));
    app.add_option("--settle", settle, "simulated seconds before the first frame (the dam breaks)")
        ->check(CLI::Range(0.0, 100.0));
    app.add_option("--refine", refine, "frames accumulated at the end, the fluid still")
        ->check(CLI::Range(0, 100000));
    app.add_option("--out", outPath,
                   "the refined image (and OUT with _1path before .png: the "
                   "last timed frame)");
    app.add_option("--json", jsonPath, "write the results here as JSON");
    CLI11_PARSE(app, argc, argv);

    std::string why;
    if (!interactiveWaterAvailable(&why)) {
        std::cerr << "weir_water_view_bench: the live water look cannot run here: " << why << "\n";
        return 1;
    }
    const Scene scene = resolveScene(sceneName);
    SetupOptions setupOptions;
    setupOptions.particleCount = parseCount(particlesText, "--particles", 1000, kMaxParticles);
    setupOptions.backend = Backend::Cuda;
    SetupReport report;
    SimulationSetup setup = buildSetup(scene, setupOptions, &report);
    const NeighbourMode mode =
        resolveNeighbourMode(NeighbourMode::Auto, setup.grid, std::int64_t(setup.particles.size()));
    std::unique_ptr<Simulation> sim = makeSimulation(Backend::Cuda, mode, std::move(setup));
    sim->computeDensity();
    const auto settleStart = Clock::now();
    if (settle > 0) {
        sim->advanceTo(settle);
    }
    sim->synchronize();
    std::cerr << "weir_water_view_bench: " << scene.name << ", " << sim->particleCount()
              << " particles on " << sim->deviceName() << " (spacing " << report.spacing
              << " m), settled to t = " << sim->time() << " s in " << msSince(settleStart) / 1000
              << " s; " << width << "x" << height << ", " << paths << " path(s) per pixel, "
              << steps << " step(s) per frame\n";

    InteractiveWaterSetup waterSetup =
        interactiveWaterSetupOf(scene, report.spacing, width, height, paths);
    waterSetup.timeSurfaceStages = true;
    InteractiveWater water(waterSetup);
    water.setCamera(framedCamera(scene.container, width, height));

    std::vector<double> stepMs, surfaceMs, bvhMs, traceMs, toneMs, frameMs;
    std::int64_t triangles = 0;
    for (int f = 0; f < warmup + frames; ++f) {
        const auto start = Clock::now();
        if (steps > 0) {
            sim->advance(steps);
        }
        sim->synchronize();
        const double step = msSince(start);
        const ParticleArrays arrays = sim->particleArrays();
        water.setParticles(arrays.pos, arrays.count);
        if (!scene.bodies.empty()) {
            std::vector<BodyPose> poses;
            for (const RigidBody& b : sim->rigidBodies()) {
                poses.push_back(poseOf(b));
            }
            water.setBodyPoses(poses);
        }
        water.render();
        const double frame = msSince(start);
        if (f < warmup) {
            continue;
        }
        const InteractiveWaterTimes& t = water.times();
        stepMs.push_back(step);
        surfaceMs.push_back(t.surfaceMs);
        bvhMs.push_back(t.bvhMs);
        traceMs.push_back(t.traceMs);
        toneMs.push_back(t.toneMapMs);
        frameMs.push_back(frame);
        triangles = t.triangles;
    }
    const std::string lastPath = [&] {
        std::string p = imagePath(outPath);
        const std::size_t dot = p.rfind('.');
        return dot == std::string::npos ? p + "_1path"
                                        : p.substr(0, dot) + "_1path" + p.substr(dot);
    }();
    writeImage(lastPath, width, height, water.rgb());
    // Paused: the same fluid and camera, the paths accumulate.
    std::vector<double> refineMs;
    for (int f = 0; f < refine; ++f) {
        const auto start = Clock::now();
        water.render();
        refineMs.push_back(msSince(start));
    }
    const std::string refinedPath = imagePath(outPath);
    writeImage(refinedPath, width, height, water.rgb());

    const double frame = median(frameMs);
    nlohmann::ordered_json out;
    out["scene"] = scene.name;
    out["particles"] = sim->particleCount();
    out["device"] = sim->deviceName();
    out["width"] = width;
    out["height"] = height;
    out["paths_per_frame"] = paths;
    out["steps_per_frame"] = steps;
    out["frames"] = frames;
    out["triangles_last"] = triangles;
    out["simulated_time_s"] = sim->time();
    out["ms_median"] = {
        {"step", median(stepMs)},          {"surface", median(surfaceMs)}, {"bvh", median(bvhMs)},
        {"trace", median(traceMs)},        {"tone_map", median(toneMs)},   {"frame", frame},
        {"refine_frame", median(refineMs)}};
    out["frames_per_second"] = frame > 0 ? 1000 / frame : 0;
    // The surface's own stages (CUDA events, over warm-up and timed frames): what the surface's
    // time holds beyond them is allocation and the host's reading of counts.
    nlohmann::ordered_json surfaceStages;
    double stagesSum = 0;
    for (const auto& [stage, samples] : water.surfaceStages().samples()) {
        surfaceStages[stage] = median(samples);
        stagesSum += median(samples);
    }
    out["surface_stages_ms_median"] = surfaceStages;
    out["frame_ms_samples"] = frameMs;
    out["paths_per_pixel_refined"] = water.pathsPerPixel();
    out["image_last_frame"] = lastPath;
    out["image_refined"] = refinedPath;
    std::cout << "particles " << sim->particleCount() << ", triangles " << triangles << "\n"
              << "median ms per frame: step " << median(stepMs) << " (x" << steps << "), surface "
              << median(surfaceMs) << ", bvh " << median(bvhMs) << ", trace " << median(traceMs)
              << " (" << paths << " path/pixel), tone map " << median(toneMs) << "; frame " << frame
              << " ms = " << (frame > 0 ? 1000 / frame : 0) << " frames/s\n"
              << "surface stages (median ms): " << surfaceStages.dump() << ", sum " << stagesSum
              << "\n"
              << "refining (paused): " << median(refineMs) << " ms per frame, "
              << water.pathsPerPixel() << " paths per pixel in " << refinedPath << "\n";
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
        std::cerr << "weir_water_view_bench: " << e.what() << "\n";
        return 1;
    }
}
