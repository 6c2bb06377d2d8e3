// The latitude-longitude lattice that render/ and raytrace/ draw spheres with.
#pragma once

#include <cmath>

#include "core/vec3.h"

namespace weir {

// The unit normal at point (i, j) of a sphere's lattice of `slices` around by `stacks` from pole
// to pole (j = 0 the +y pole); each lattice cell is a quad of four such points.
inline Vec3d sphereLatticeNormal(int i, int j, int slices, int stacks) {
    constexpr double kPi = 3.14159265358979323846;
    const double theta = kPi * j / stacks, phi = 2 * kPi * i / slices;
    return {std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)};
}

}  // namespace weir
