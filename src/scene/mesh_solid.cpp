#include "scene/mesh_solid.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>
#include <utility>

#include "core/symmetric_eigen.h"

namespace weir {

MeshSolid meshSolidOf(const std::vector<Vec3d>& vertices,
                      const std::vector<std::array<int, 3>>& triangles) {
    // Each triangle (a, b, c) with the origin is a tetrahedron of signed volume a.(b x c) / 6,
    // centroid (a + b + c) / 4 and second moment about the origin
    // a.(b x c) / 120 (a a^T + b b^T + c c^T + s s^T), s = a + b + c. The origin is moved to the
    // vertices' mean first, so a mesh far from the origin loses no digits.
    Vec3d origin;
    for (const Vec3d& v : vertices) {
        origin += v;
    }
    if (!vertices.empty()) {
        origin = origin / double(vertices.size());
    }
    double volume = 0;
    Vec3d first;
    std::array<double, 9> second{};
    for (const auto& t : triangles) {
        const Vec3d a = vertices[std::size_t(t[0])] - origin,
                    b = vertices[std::size_t(t[1])] - origin,
                    c = vertices[std::size_t(t[2])] - origin;
        const double det = dot(a, cross(b, c));
        volume += det / 6;
        const Vec3d s = a + b + c;
        first += s * (det / 24);
        for (int i = 0; i < 3; ++i) {
            for (int j = 0; j < 3; ++j) {
                second[std::size_t(3 * i + j)] +=
                    det / 120 * (a[i] * a[j] + b[i] * b[j] + c[i] * c[j] + s[i] * s[j]);
            }
        }
    }
    MeshSolid out;
    out.volume = volume;
    if (volume == 0) {
        out.centroid = origin;
        return out;
    }
    const Vec3d c = first / volume;
    out.centroid = origin + c;
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
            out.secondMoment[std::size_t(3 * i + j)] =
                second[std::size_t(3 * i + j)] / volume - c[i] * c[j];
        }
    }
    return out;
}

std::size_t unmatchedEdgesOf(const std::vector<Vec3d>& vertices,
                             const std::vector<std::array<int, 3>>& triangles) {
    // Vertices welded by exact coordinates.
    std::map<std::tuple<double, double, double>, int> welded;
    std::vector<int> id(vertices.size());
    for (std::size_t v = 0; v < vertices.size(); ++v) {
        const auto key = std::make_tuple(vertices[v].x, vertices[v].y, vertices[v].z);
        id[v] = welded.emplace(key, int(welded.size())).first->second;
    }
    // Each undirected edge: how many times it runs each way.
    std::map<std::pair<int, int>, std::pair<int, int>> edges;
    for (const auto& t : triangles) {
        for (int k = 0; k < 3; ++k) {
            const int from = id[std::size_t(t[k])], to = id[std::size_t(t[(k + 1) % 3])];
            if (from == to) {
                continue;  // a degenerate triangle's collapsed edge
            }
            auto& counts = edges[{std::min(from, to), std::max(from, to)}];
            (from < to ? counts.first : counts.second) += 1;
        }
    }
    std::size_t unmatched = 0;
    for (const auto& [edge, counts] : edges) {
        unmatched += counts.first == 1 && counts.second == 1 ? 0 : 1;
    }
    return unmatched;
}

std::array<double, 9> inertiaTensorOf(const MeshSolid& solid, double mass) {
    const auto& s = solid.secondMoment;
    const double trace = s[0] + s[4] + s[8];
    std::array<double, 9> inertia{};
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
            inertia[std::size_t(3 * i + j)] =
                mass * ((i == j ? trace : 0.0) - s[std::size_t(3 * i + j)]);
        }
    }
    return inertia;
}

PrincipalAxes principalAxesOf(const std::array<double, 9>& symmetric) {
    double a[3][3], v[3][3];
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
            a[i][j] = 0.5 * (symmetric[std::size_t(3 * i + j)] + symmetric[std::size_t(3 * j + i)]);
        }
    }
    jacobiEigen(a, v, 50, 1e-30);  // 3 x 3 reaches round-off in a handful of sweeps
    PrincipalAxes out;
    for (int k = 0; k < 3; ++k) {
        out.values[k] = a[k][k];
        out.axes[std::size_t(k)] = Vec3d(v[0][k], v[1][k], v[2][k]);
    }
    if (dot(cross(out.axes[0], out.axes[1]), out.axes[2]) < 0) {
        out.axes[2] = -out.axes[2];
    }
    return out;
}

}  // namespace weir
