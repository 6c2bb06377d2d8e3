// The point-sprite timing of weir bench: upload, draw and wait, median of repeated frames.
#include "cli/sprite_timer.h"

#include <algorithm>
#include <chrono>
#include <vector>

#include "render/camera.h"
#include "render/egl_context.h"
#include "render/renderer.h"

namespace weir {

namespace {

class EglSpriteDrawTimer final : public SpriteDrawTimer {
   public:
    EglSpriteDrawTimer() : renderer_() { renderer_.setShowLegend(false); }

    double medianDrawMs(const Scene& scene, const HostParticles& particles,
                        double radius) override {
        constexpr int kWidth = 1280, kHeight = 720, kRepeats = 9;
        context_.makeCurrent();
        renderer_.setGeometry(SceneGeometry::of(scene));
        const OrbitCamera camera = frameBox(scene.container, double(kWidth) / kHeight);
        renderer_.setParticles(particles, ColourField::Speed, radius);
        renderer_.drawOffscreenAndWait(camera, kWidth, kHeight);  // warm-up: buffers, shaders
        std::vector<double> ms;
        for (int k = 0; k < kRepeats; ++k) {
            const auto start = std::chrono::steady_clock::now();
            renderer_.setParticles(particles, ColourField::Speed, radius);
            renderer_.drawOffscreenAndWait(camera, kWidth, kHeight);
            ms.push_back(
                std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                    .count());
        }
        std::sort(ms.begin(), ms.end());
        return ms[ms.size() / 2];
    }
    std::string description() const override { return context_.description(); }

   private:
    OffscreenContext context_;  // made current before the renderer is built
    Renderer renderer_;
};

}  // namespace

std::unique_ptr<SpriteDrawTimer> makeSpriteDrawTimer() {
    return std::make_unique<EglSpriteDrawTimer>();
}

}  // namespace weir
