// The OpenGL 3.3 core renderer: particles as sphere-shaded point sprites coloured through viridis,
// or a water-shaded triangle mesh; the container as lines, obstacles as grey solids; a legend bar
// with its range and a few lines of text on top.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "render/camera.h"
#include "render/colour_map.h"
#include "render/png_image.h"
#include "scene/scene.h"
#include "solver/particles.h"
#include "surface/triangle_mesh.h"
#include "whitewater/diffuse_particles.h"

namespace weir {

// What stays put between frames: the container and the static obstacles; and the rigid bodies'
// shapes (where they are comes with each frame: Renderer::setBodies).
struct SceneGeometry {
    Box container;
    std::vector<Box> obstacleBoxes;
    std::vector<SphereShape> obstacleSpheres;
    std::vector<BodySpec> bodies;

    static SceneGeometry of(const Scene& scene);
};

// The background colour of every image.
constexpr Rgb kBackground{0.13f, 0.14f, 0.17f};

// Particle lighting: a light fixed to the camera, ambient + diffuse + a Blinn specular highlight
// seen from straight ahead. particleCentreColour is the shade the shader gives a particle's centre
// (its normal facing the viewer), so tests can check the colour map through the lighting.
struct ParticleLighting {
    float ambient = 0.4f, diffuse = 0.6f, specular = 0.2f, shininess = 40.0f;
    float lightX = -0.35f, lightY = 0.55f, lightZ = 0.76f;  // unit, view space
};
Rgb particleCentreColour(Rgb base, const ParticleLighting& lighting = {});

// The legend bar's rectangle in image pixels (rows from the top): value lo at the bottom row, hi at
// the top row.
struct PixelRect {
    int left = 0, top = 0, right = 0, bottom = 0;  // right and bottom exclusive
};
PixelRect legendBarRect(int width, int height);

enum class RenderMode { Particles, Surface };

class Renderer {
   public:
    // Needs a current OpenGL 3.3 core context (EGL offscreen or a window's); throws RenderError
    // when a shader does not build.
    Renderer();
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    void setGeometry(const SceneGeometry& geometry);
    // The rigid bodies (the scene's shapes) at their poses of this frame, drawn as solids.
    void setBodies(const std::vector<BodySpec>& bodies, const std::vector<BodyPose>& poses);
    // Uploads positions and the field's values; radius is the sphere drawn per particle (m).
    void setParticles(const HostParticles& particles, ColourField field, double radius);
    // For filling the particle buffers elsewhere (CUDA-OpenGL interop): sizes the two vertex
    // buffers for n particles, 3 floats of position and 1 float of value each, and returns their
    // OpenGL names (positions, values); then setFilledParticles draws what was written there.
    std::pair<unsigned, unsigned> reserveParticleBuffers(std::size_t n);
    void setFilledParticles(std::size_t n, ColourField field, double radius);
    // The values mapped to the ends of the colour map. Until it is called (and again after the
    // field changes) each setParticles takes the robust range of its data.
    void setColourRange(const ValueRange& range);
    const ValueRange& colourRange() const { return range_; }
    ColourField colourField() const { return field_; }
    void setMesh(const TriangleMesh& mesh);
    // Spray, foam and bubbles (whitewater/), drawn as white sprites in both modes: foam of this
    // radius [m], spray 0.7x and bubbles 0.5x it. An empty set draws none.
    void setWhitewater(const DiffuseParticles& whitewater, double radius);
    void setMode(RenderMode mode) { mode_ = mode; }
    RenderMode mode() const { return mode_; }
    // Lines of text at the top left (empty: none).
    void setOverlayText(std::vector<std::string> lines) { overlay_ = std::move(lines); }
    void setShowLegend(bool show) { showLegend_ = show; }
    // Multisampling for renderImage (1 = off).
    void setSamples(int samples) { samples_ = samples; }

    // Draws into the bound framebuffer, whose size is width x height.
    void draw(const OrbitCamera& camera, int width, int height);
    // Only the text lines (and the legend, where shown) over what the bound framebuffer holds:
    // over an image drawn by another path (the live water look).
    void drawOverlayOnly(int width, int height);
    // Draws into the offscreen framebuffer and waits for the GPU to finish, without reading the
    // image back: the cost of a frame's drawing alone.
    void drawOffscreenAndWait(const OrbitCamera& camera, int width, int height);
    // Draws into an offscreen framebuffer and reads the image back.
    Image renderImage(const OrbitCamera& camera, int width, int height);

    std::size_t particleCount() const { return particleCount_; }

   private:
    struct Gpu;
    void drawOverlay(int width, int height);

    std::unique_ptr<Gpu> gpu_;
    std::size_t particleCount_ = 0;
    double radius_ = 0.01;
    ColourField field_ = ColourField::Speed;
    ValueRange range_;
    bool autoRange_ = true;
    RenderMode mode_ = RenderMode::Particles;
    std::vector<std::string> overlay_;
    bool showLegend_ = true;
    int samples_ = 4;
    std::size_t whitewaterCounts_[kDiffuseKinds] = {0, 0, 0};  // by kind, uploaded in that order
    double whitewaterRadius_ = 0;
    std::size_t reserved_ = 0;  // particles the buffers hold room for (reserveParticleBuffers)
};

// The sphere radius to draw for particles seeded on a lattice: half the spacing, estimated as the
// median nearest-neighbour distance of a sample of particles (0.01 m for fewer than two).
double estimateParticleRadius(const HostParticles& particles);

}  // namespace weir
