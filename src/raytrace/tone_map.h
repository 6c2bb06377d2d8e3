// The water look's tone mapping, written once for the CPU and CUDA: exposure, the ACES filmic
// curve (Narkowicz 2015's fit: highlights roll off instead of clipping) and the sRGB transfer
// function, linear radiance to an 8-bit value.
#pragma once

#include <cmath>
#include <cstdint>

#include "core/config.h"

namespace weir {

WEIR_HD inline std::uint8_t toneMapToByte(float radiance, float exposure) {
    const float x = fmaxf(0.0f, radiance * exposure);
    const float filmic =
        fminf(fmaxf((x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f), 0.0f), 1.0f);
    const float encoded =
        filmic <= 0.0031308f ? 12.92f * filmic : 1.055f * powf(filmic, 1.0f / 2.4f) - 0.055f;
    return std::uint8_t(lroundf(fminf(fmaxf(encoded, 0.0f), 1.0f) * 255.0f));
}

}  // namespace weir
