// The water look's images: every pixel traced by the path tracer (raytrace/path_tracer.h) on the
// CPU (OpenMP over rows) or on CUDA (a thread per pixel), then tone-mapped to 8-bit sRGB.
#pragma once

#include <cstdint>
#include <vector>

#include "core/backend.h"
#include "raytrace/path_tracer.h"
#include "raytrace/tracing_scene.h"
#include "raytrace/water_look.h"

namespace weir {

// Linear radiance of width x height pixels (rows from the top), the mean of `samples` paths per
// pixel. The same pixels on either backend up to float rounding (the random numbers are a
// function of pixel and sample). The paths are those numbered firstSample on: images of paths
// 0..a-1 and a..a+b-1, weighted by a and b, make the image of a+b paths (motion blur traces
// its time slices so). Throws std::invalid_argument for sizes or samples < 1.
std::vector<Vec3f> traceWaterImage(Backend backend, const TracingScene& scene,
                                   const WaterLook& look, const PinholeCamera& camera, int width,
                                   int height, int samples, int firstSample = 0);

// Exposure, the ACES filmic curve (Narkowicz 2015's fit: highlights roll off instead of clipping)
// and the sRGB transfer function: 3 bytes per pixel.
std::vector<std::uint8_t> toneMapToSrgb8(const std::vector<Vec3f>& radiance, float exposure);

// One channel of that mapping, for tests: linear radiance to the 8-bit value.
std::uint8_t toneMappedByte(float radiance, float exposure);

}  // namespace weir
