// measureMesh: sums over triangles, then the edges sorted so that each edge's uses are adjacent.
#include "surface/mesh_measures.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

namespace weir {

namespace {

std::uint32_t findRoot(std::vector<std::uint32_t>& parent, std::uint32_t v) {
    while (parent[v] != v) {
        parent[v] = parent[parent[v]];
        v = parent[v];
    }
    return v;
}

}  // namespace

MeshMeasures measureMesh(const TriangleMesh& mesh) {
    MeshMeasures m;
    const std::size_t triangles = mesh.triangleCount();
    const std::size_t vertices = mesh.vertexCount();
    for (std::uint32_t index : mesh.indices) {
        if (index >= vertices) {
            throw std::out_of_range("triangle vertex index " + std::to_string(index) +
                                    " is past the " + std::to_string(vertices) + " vertices");
        }
    }
    struct DirectedEdge {
        std::uint32_t low, high;
        bool forward;  // runs low -> high
    };
    std::vector<DirectedEdge> edges;
    edges.reserve(3 * triangles);
    std::vector<std::uint32_t> parent(vertices);
    std::iota(parent.begin(), parent.end(), 0u);
    std::vector<bool> used(vertices, false);
    for (std::size_t t = 0; t < triangles; ++t) {
        const std::uint32_t* v = &mesh.indices[3 * t];
        const Vec3d a(mesh.positions[v[0]]), b(mesh.positions[v[1]]), c(mesh.positions[v[2]]);
        const Vec3d ab = b - a, ac = c - a;
        const Vec3d cross{ab.y * ac.z - ab.z * ac.y, ab.z * ac.x - ab.x * ac.z,
                          ab.x * ac.y - ab.y * ac.x};
        m.area += 0.5 * length(cross);
        m.volume +=
            dot(a, Vec3d{b.y * c.z - b.z * c.y, b.z * c.x - b.x * c.z, b.x * c.y - b.y * c.x}) / 6;
        if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2]) {
            ++m.degenerateTriangles;
        }
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t from = v[k], to = v[(k + 1) % 3];
            edges.push_back({std::min(from, to), std::max(from, to), from < to});
            used[from] = true;
            parent[findRoot(parent, from)] = findRoot(parent, to);
        }
    }
    std::sort(edges.begin(), edges.end(), [](const DirectedEdge& x, const DirectedEdge& y) {
        return std::tie(x.low, x.high, x.forward) < std::tie(y.low, y.high, y.forward);
    });
    for (std::size_t i = 0; i < edges.size();) {
        std::size_t j = i, forward = 0;
        for (; j < edges.size() && edges[j].low == edges[i].low && edges[j].high == edges[i].high;
             ++j) {
            forward += edges[j].forward ? 1 : 0;
        }
        const std::size_t uses = j - i;
        ++m.edges;
        if (uses == 1) {
            ++m.boundaryEdges;
        } else if (uses > 2) {
            ++m.nonManifoldEdges;
        } else if (forward != 1) {
            ++m.misorientedEdges;
        }
        i = j;
    }
    std::size_t usedVertices = 0;
    for (std::uint32_t v = 0; v < vertices; ++v) {
        if (used[v]) {
            ++usedVertices;
            m.components += findRoot(parent, v) == v ? 1 : 0;
        }
    }
    m.eulerCharacteristic =
        std::int64_t(usedVertices) - std::int64_t(m.edges) + std::int64_t(triangles);
    return m;
}

double cornerAngleDegrees(const Vec3d& corner, const Vec3d& a, const Vec3d& b) {
    const Vec3d u = a - corner, v = b - corner;
    const Vec3d cross{u.y * v.z - u.z * v.y, u.z * v.x - u.x * v.z, u.x * v.y - u.y * v.x};
    return std::atan2(length(cross), dot(u, v)) * (180 / 3.14159265358979323846);
}

MeshQuality measureQuality(const TriangleMesh& mesh, double shortEdge, double smallAngleDegrees) {
    MeshQuality q;
    q.minEdge = std::numeric_limits<double>::infinity();
    q.minAngleDegrees = 180;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        const std::uint32_t* v = &mesh.indices[3 * t];
        const Vec3d p[3] = {Vec3d(mesh.positions[v[0]]), Vec3d(mesh.positions[v[1]]),
                            Vec3d(mesh.positions[v[2]])};
        double smallest = 180;
        for (int k = 0; k < 3; ++k) {
            const double edge = length(p[(k + 1) % 3] - p[k]);
            q.minEdge = std::min(q.minEdge, edge);
            // A closed mesh runs each edge once each way: count it from its lower vertex.
            q.shortEdges += edge < shortEdge && v[k] < v[(k + 1) % 3] ? 1 : 0;
            smallest = std::min(smallest, cornerAngleDegrees(p[k], p[(k + 1) % 3], p[(k + 2) % 3]));
        }
        q.minAngleDegrees = std::min(q.minAngleDegrees, smallest);
        q.smallAngles += smallest < smallAngleDegrees ? 1 : 0;
    }
    return q;
}

}  // namespace weir
