// The water look, live: a frame pipeline that stays on the GPU. The particles (a CUDA solver's
// positions) become the marching-cubes surface in device memory, a linear hierarchy is built over
// it there (lbvh.h), the same tracePixel as `weir render --look water` adds a few paths per pixel
// to a float accumulation buffer, and the mean is tone-mapped into an RGBA8 buffer for OpenGL
// interop or a PNG. While the camera and the fluid stand still the paths accumulate (the image
// refines); a change of either starts the accumulation again. CUDA only: the constructor throws
// in a build without it or without a device.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/stage_timer.h"
#include "raytrace/path_tracer.h"
#include "raytrace/tracing_scene.h"
#include "raytrace/water_look.h"
#include "surface/surface.h"

namespace weir {

struct InteractiveWaterSetup {
    // The container, the static obstacles and the bodies' shapes (its `water` and `cameraEye`
    // are not used; the bodies are drawn at the poses setBodyPoses gives, none until then).
    // contactDistance: as for the offline look, the surface's faces on the floor and walls left
    // out (a particle spacing).
    TracingSceneDescription scene;
    SurfaceOptions surface;  // surface.spacing must be given; slivers are not removed (a host step)
    WaterLook look;
    int width = 1280, height = 720;
    int pathsPerFrame = 1;  // paths per pixel added by each render()
    // Whether each surface build's stages ("surface bins", "surface blocks", "surface field",
    // "surface vertices", "surface triangles") are timed into surfaceStages() (benchmarks).
    bool timeSurfaceStages = false;
};

// The last render()'s stages in milliseconds on the GPU (CUDA events; 0 for a stage it did not
// have to run: surface and hierarchy only when the fluid or the bodies moved).
struct InteractiveWaterTimes {
    double surfaceMs = 0;  // particle bounds, lattice, field, marching cubes
    double bvhMs = 0;      // the triangles prepared (contact faces left out), Morton sort, tree
    double traceMs = 0;
    double toneMapMs = 0;
    int paths = 0;               // paths per pixel traced by the last render()
    std::int64_t triangles = 0;  // in the hierarchy: the surface's kept faces and the matte ones
};

class InteractiveWater {
   public:
    explicit InteractiveWater(const InteractiveWaterSetup& setup);
    ~InteractiveWater();
    InteractiveWater(const InteractiveWater&) = delete;
    InteractiveWater& operator=(const InteractiveWater&) = delete;

    // The fluid moved: the next render() rebuilds the surface from these n positions (x, y, z of
    // a Real4 each, in device memory, valid until then and finished being written: synchronize
    // the solver first).
    void setParticles(const Real4* devicePositions, Index n);
    // The same from host memory (a CPU simulation, tests): uploaded into a buffer of its own.
    void setHostParticles(const HostParticles& particles);
    // A surface given on the host instead of particles (tests: the offline look's mesh).
    void setMesh(const TriangleMesh& mesh);
    // The rigid bodies' poses of this frame (the setup's bodies): their triangles are rebuilt
    // when the poses differ from the last ones.
    void setBodyPoses(const std::vector<BodyPose>& poses);
    // The camera; the accumulation starts again when it differs from the last one. Its aspect is
    // set to the image's.
    void setCamera(const PinholeCamera& camera);
    // A new image size (the accumulation starts again).
    void resize(int width, int height);
    // Paths per pixel each render() adds from now on (1..65536): more while the fluid stands
    // still, so that the image refines faster.
    void setPathsPerFrame(int paths);

    // One frame: what changed rebuilt, pathsPerFrame more paths per pixel traced, tone-mapped.
    // Waits for the GPU at the end (the times are read).
    void render();

    int width() const;
    int height() const;
    int pathsPerPixel() const;  // accumulated so far
    const InteractiveWaterTimes& times() const;
    // The surface stages of every build so far (InteractiveWaterSetup::timeSurfaceStages).
    const StageTimes& surfaceStages() const;
    // The tone-mapped image in device memory: width x height RGBA8 pixels, rows from the top.
    const std::uint8_t* deviceRgba() const;
    // The accumulated image downloaded: the mean radiance per pixel, or its sRGB bytes (3 per
    // pixel).
    std::vector<Vec3f> radiance() const;
    std::vector<std::uint8_t> rgb() const;

   private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

// The setup for a scene's fluid of particle spacing d: its container, obstacles and bodies, the
// surface at spacing d with faces within d of the floor and walls left out, the floor's checker
// as `weir render --look water` sizes it.
InteractiveWaterSetup interactiveWaterSetupOf(const Scene& scene, double spacing, int width,
                                              int height, int pathsPerFrame);

// Whether this build and machine can run the live water look; if not, why (for a status line).
bool interactiveWaterAvailable(std::string* why);

// The floor's checker square for a container: about 1/16 of its longer side, rounded down to 1,
// 2 or 5 times a power of ten metres (both looks: `weir render --look water` and the live one).
double checkerSquareOf(const Box& container);

}  // namespace weir
