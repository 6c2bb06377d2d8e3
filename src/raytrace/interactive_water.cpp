// The live water look's host pieces: the floor's checker size, and a
// build without CUDA's stand-in that says the look needs it.
#include "raytrace/interactive_water.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace weir {

double checkerSquareOf(const Box& container) {
    const double side =
        std::max(container.max.x - container.min.x, container.max.z - container.min.z) / 16;
    if (!(side > 0) || !std::isfinite(side)) {
        return 0.1;
    }
    // log10(0.1) may round to just below -1.
    const double decade = std::pow(10.0, std::floor(std::log10(side) + 1e-9));
    for (double step : {5.0, 2.0}) {
        if (step * decade <= side) {
            return step * decade;
        }
    }
    return decade;
}

InteractiveWaterSetup interactiveWaterSetupOf(const Scene& scene, double spacing, int width,
                                              int height, int pathsPerFrame) {
    InteractiveWaterSetup setup;
    TracingSceneDescription& d = setup.scene;
    d.container = scene.container;
    d.obstacleBoxes = scene.obstacleBoxes;
    d.obstacleSpheres = scene.obstacleSpheres;
    d.obstacleMeshes = scene.obstacleMeshes;
    d.bodies = scene.bodies;
    // Where the fluid touches the floor and walls its surface lies within about a particle
    // radius of them: a spacing takes those faces and no others (as the offline look).
    d.contactDistance = spacing;
    setup.surface.spacing = spacing;
    setup.surface.removeSlivers = false;
    setup.look.checkerSize = float(checkerSquareOf(scene.container));
    setup.width = width;
    setup.height = height;
    setup.pathsPerFrame = pathsPerFrame;
    return setup;
}

#if !defined(WEIR_HAS_CUDA)
struct InteractiveWater::Impl {
    InteractiveWaterTimes times;
    StageTimes surfaceStages;
};

InteractiveWater::InteractiveWater(const InteractiveWaterSetup&) {
    throw std::runtime_error("the live water look needs CUDA: this weir was built without it");
}
InteractiveWater::~InteractiveWater() = default;
void InteractiveWater::setParticles(const Real4*, Index) {}
void InteractiveWater::setHostParticles(const HostParticles&) {}
void InteractiveWater::setMesh(const TriangleMesh&) {}
void InteractiveWater::setBodyPoses(const std::vector<BodyPose>&) {}
void InteractiveWater::setCamera(const PinholeCamera&) {}
void InteractiveWater::resize(int, int) {}
void InteractiveWater::setPathsPerFrame(int) {}
void InteractiveWater::render() {}
int InteractiveWater::width() const { return 0; }
int InteractiveWater::height() const { return 0; }
int InteractiveWater::pathsPerPixel() const { return 0; }
const InteractiveWaterTimes& InteractiveWater::times() const { return impl_->times; }
const StageTimes& InteractiveWater::surfaceStages() const { return impl_->surfaceStages; }
const std::uint8_t* InteractiveWater::deviceRgba() const { return nullptr; }
std::vector<Vec3f> InteractiveWater::radiance() const { return {}; }
std::vector<std::uint8_t> InteractiveWater::rgb() const { return {}; }

bool interactiveWaterAvailable(std::string* why) {
    if (why != nullptr) {
        *why = "this weir was built without CUDA";
    }
    return false;
}
#endif

}  // namespace weir
