// The procedural sky of the water look: a gradient from the horizon to the zenith, a glow about
// the sun and the sun's disc.
#pragma once

#include <cmath>

#include "raytrace/optics.h"
#include "raytrace/water_look.h"

namespace weir {

// Radiance of the sun's disc: its irradiance spread over the disc's solid angle 2 pi (1 - cos a).
WEIR_HD inline Vec3f sunDiscRadiance(const WaterLook& look) {
    return look.sunIrradiance * (1.0f / (2.0f * kPiF * oneMinusCos(look.sunAngularRadius)));
}

// The sky's radiance along unit direction d, with the sun's disc or without it: after a matte
// bounce the sun is sampled directly (next-event estimation) and its disc is left out of the sky,
// so that it is not counted twice.
WEIR_HD inline Vec3f skyRadiance(const WaterLook& look, const Vec3f& d, bool withSunDisc) {
    Vec3f sky;
    if (d.y >= 0.0f) {
        const float up = std::sqrt(d.y);  // the horizon's haze thins quickly upwards
        sky = look.skyHorizon + (look.skyZenith - look.skyHorizon) * up;
    } else {
        const float down = fminf(1.0f, -8.0f * d.y);  // a soft edge just below the horizon
        sky = look.skyHorizon + (look.skyBelowHorizon - look.skyHorizon) * down;
    }
    const Vec3f sun = normalized(look.sunDirection);
    const float cosToSun = dot(d, sun);
    sky += look.sunGlow * std::pow(0.5f * (1.0f + cosToSun), look.sunGlowSharpness);
    if (withSunDisc && 1.0f - cosToSun <= oneMinusCos(look.sunAngularRadius)) {
        sky += sunDiscRadiance(look);
    }
    return sky;
}

}  // namespace weir
