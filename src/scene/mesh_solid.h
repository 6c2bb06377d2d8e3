// The solid a closed triangle mesh bounds, for rigid bodies made from OBJ/STL files (issue 18):
// its volume, centroid and second moment by the divergence theorem (a signed tetrahedron from the
// origin to each triangle), whether its surface is closed, and the principal axes of an inertia
// tensor.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "core/vec3.h"

namespace weir {

struct MeshSolid {
    // Signed: positive when the triangles face outwards (counter-clockwise seen from outside).
    double volume = 0;
    Vec3d centroid;
    // The second moment about the centroid per unit volume, integral of (x - c)(x - c)^T dV / V,
    // row-major 3 x 3 (symmetric).
    std::array<double, 9> secondMoment{};
};

MeshSolid meshSolidOf(const std::vector<Vec3d>& vertices,
                      const std::vector<std::array<int, 3>>& triangles);

// How many edges of the surface do not join exactly two triangles, one running each way, with
// vertices at equal coordinates taken as one (an STL repeats each triangle's corners): 0 for a
// closed, consistently oriented surface.
std::size_t unmatchedEdgesOf(const std::vector<Vec3d>& vertices,
                             const std::vector<std::array<int, 3>>& triangles);

// The inertia tensor of a uniform solid of mass m with that second moment:
// I = m (trace(S) 1 - S), row-major.
std::array<double, 9> inertiaTensorOf(const MeshSolid& solid, double mass);

// A symmetric 3 x 3 matrix's eigenvalues and unit eigenvectors (Jacobi rotations): matrix =
// sum_k values[k] axes[k] axes[k]^T, the axes a right-handed frame.
struct PrincipalAxes {
    Vec3d values;
    std::array<Vec3d, 3> axes;
};
PrincipalAxes principalAxesOf(const std::array<double, 9>& symmetric);

}  // namespace weir
