// The constants of the water look: the water's optics, the sky and sun that light the scene, the
// matte surfaces around the fluid, the path tracer's bounce limits and the exposure. Plain data,
// passed by value to the CPU loop and the CUDA kernel.
#pragma once

#include "core/vec3.h"

namespace weir {

struct WaterLook {
    // Water at 20 C in visible light.
    float refractiveIndex = 1.333f;
    // Beer-Lambert absorption (1/m) for red, green, blue. Pure water's is about 0.34, 0.06, 0.01
    // /m (Pope and Fry 1997, at 650, 550, 450 nm): over a tank of a metre that tints too little
    // to see. These are 3.5x, 4x and 16x stronger, in the same order (red absorbed most, blue
    // least): water a few tens of centimetres deep turns blue-green, as a pool a few metres deep.
    Vec3f absorption{1.2f, 0.24f, 0.16f};

    // The sky: radiance straight up, at the horizon, and below it (seen only where no floor is).
    Vec3f skyZenith{0.32f, 0.52f, 0.95f};
    Vec3f skyHorizon{0.70f, 0.80f, 0.95f};
    Vec3f skyBelowHorizon{0.35f, 0.34f, 0.32f};
    // The sun: unit direction towards it (from the camera's side, high), its angular radius (rad;
    // the real sun's is 0.0047: a larger disc softens the shadows) and the irradiance it gives a
    // surface facing it. A glow about the sun (Henyey-Greenstein-like lobe) brightens the sky near
    // it, as haze does.
    Vec3f sunDirection{-0.38f, 0.80f, 0.46f};
    float sunAngularRadius = 0.03f;
    Vec3f sunIrradiance{3.6f, 3.4f, 3.1f};
    Vec3f sunGlow{0.6f, 0.5f, 0.35f};
    float sunGlowSharpness = 24.0f;

    // Matte (Lambertian) surfaces: a light grey checker floor in the container and plain ground
    // around it, pale blue-grey walls, static obstacles, rigid bodies (wood, as the preview draws
    // them).
    Vec3f floorLight{0.78f, 0.78f, 0.76f};
    Vec3f floorDark{0.42f, 0.42f, 0.41f};
    float checkerSize = 0.1f;  // metres per square; the command line scales it to the container
    Vec3f groundAlbedo{0.30f, 0.30f, 0.29f};
    Vec3f wallAlbedo{0.50f, 0.56f, 0.60f};
    Vec3f obstacleAlbedo{0.58f, 0.56f, 0.52f};
    Vec3f bodyAlbedo{0.72f, 0.48f, 0.26f};
    // Spray, foam and bubbles (whitewater/): near-white, as the air-water froth scatters light.
    Vec3f whitewaterAlbedo{0.88f, 0.90f, 0.92f};

    // A path ends after this many reflections or refractions at the water, or after this many
    // bounces off matte surfaces (each of which also samples the sun).
    int maxSpecularBounces = 8;
    int maxDiffuseBounces = 2;

    // Radiance scale before tone mapping.
    float exposure = 0.6f;
};

}  // namespace weir
