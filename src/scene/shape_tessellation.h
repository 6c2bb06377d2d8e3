// How render/ and raytrace/ cut a box and a sphere into triangles: the same corners and lattice
// for both, so the preview and the water look draw the same shapes.
#pragma once

#include <cmath>

#include "core/vec3.h"
#include "scene/scene.h"

namespace weir {

// The four corners of the face of `box` normal to `axis` on its upper (side 1) or lower side,
// in order around the face: corner k has the upper value along the next axis for k = 1, 2 and
// along the one after for k = 2, 3.
inline void boxFaceCorners(const Box& box, int axis, int side, Vec3d corner[4]) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    for (int k = 0; k < 4; ++k) {
        corner[k][axis] = side ? box.max[axis] : box.min[axis];
        corner[k][u] = (k == 1 || k == 2) ? box.max[u] : box.min[u];
        corner[k][v] = (k >= 2) ? box.max[v] : box.min[v];
    }
}

// The unit normal at point (i, j) of a sphere's lattice of `slices` around by `stacks` from pole
// to pole (j = 0 the +y pole); each lattice cell is a quad of four such points.
inline Vec3d sphereLatticeNormal(int i, int j, int slices, int stacks) {
    constexpr double kPi = 3.14159265358979323846;
    const double theta = kPi * j / stacks, phi = 2 * kPi * i / slices;
    return {std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)};
}

}  // namespace weir
