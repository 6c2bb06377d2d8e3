// The CPU loop over the image's rows, and tone mapping.
#include "raytrace/water_renderer.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "raytrace/tone_map.h"

namespace weir {

#if defined(WEIR_HAS_CUDA)
std::vector<Vec3f> traceWaterImageCuda(const TracingScene& scene, const WaterLook& look,
                                       const PinholeCamera& camera, int width, int height,
                                       int samples, int firstSample);  // water_renderer_cuda.cu
#endif

std::vector<Vec3f> traceWaterImage(Backend backend, const TracingScene& scene,
                                   const WaterLook& look, const PinholeCamera& camera, int width,
                                   int height, int samples, int firstSample) {
    if (width < 1 || height < 1 || samples < 1) {
        throw std::invalid_argument("water image of " + std::to_string(width) + " x " +
                                    std::to_string(height) + " pixels, " + std::to_string(samples) +
                                    " samples: each must be >= 1");
    }
    if (backend == Backend::Cuda) {
#if defined(WEIR_HAS_CUDA)
        return traceWaterImageCuda(scene, look, camera, width, height, samples, firstSample);
#else
        throw std::invalid_argument("the water look on cuda: this weir was built without CUDA");
#endif
    }
    std::vector<Vec3f> image(std::size_t(width) * std::size_t(height));
    const TracingSceneView view = scene.view();
    // Rows cost very different times (sky against water): handed out one at a time.
#pragma omp parallel for schedule(dynamic, 1)
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            image[std::size_t(y) * std::size_t(width) + std::size_t(x)] =
                tracePixel(view, look, camera, width, height, x, y, samples, firstSample);
        }
    }
    return image;
}

std::uint8_t toneMappedByte(float radiance, float exposure) {
    return toneMapToByte(radiance, exposure);  // tone_map.h: the live look's kernel runs it too
}

std::vector<std::uint8_t> toneMapToSrgb8(const std::vector<Vec3f>& radiance, float exposure) {
    std::vector<std::uint8_t> rgb(3 * radiance.size());
    for (std::size_t i = 0; i < radiance.size(); ++i) {
        for (int c = 0; c < 3; ++c) {
            rgb[3 * i + std::size_t(c)] = toneMappedByte(radiance[i][c], exposure);
        }
    }
    return rgb;
}

}  // namespace weir
