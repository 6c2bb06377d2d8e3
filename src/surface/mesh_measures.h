// Measures of a triangle mesh: area, enclosed volume, and whether it is closed and consistently
// wound (every edge shared by exactly two triangles that run it in opposite directions).
#pragma once

#include <cstddef>
#include <cstdint>

#include "surface/triangle_mesh.h"

namespace weir {

struct MeshMeasures {
    double area = 0;        // [m^2]
    double volume = 0;      // enclosed [m^3] by the divergence theorem; > 0 when wound outwards
    std::size_t edges = 0;  // undirected edges
    std::size_t boundaryEdges = 0;         // used by one triangle only
    std::size_t nonManifoldEdges = 0;      // used by more than two triangles
    std::size_t misorientedEdges = 0;      // used twice in the same direction
    std::size_t degenerateTriangles = 0;   // a vertex index repeated
    std::size_t components = 0;            // connected pieces (through shared vertices)
    std::int64_t eulerCharacteristic = 0;  // V - E + F over the vertices used: 2 per sphere

    bool closed() const {
        return boundaryEdges == 0 && nonManifoldEdges == 0 && misorientedEdges == 0 &&
               degenerateTriangles == 0;
    }
};

// Throws std::out_of_range if an index points past the vertices.
MeshMeasures measureMesh(const TriangleMesh& mesh);

// Slivers: the shortest edge and the smallest angle, and how many are under given limits.
struct MeshQuality {
    double minEdge = 0;           // [m]
    double minAngleDegrees = 0;   // over every corner of every triangle
    std::size_t shortEdges = 0;   // undirected edges shorter than the limit
    std::size_t smallAngles = 0;  // triangles with an angle under the limit
};
MeshQuality measureQuality(const TriangleMesh& mesh, double shortEdge, double smallAngleDegrees);

// The angle at `corner` between the directions to a and b, in degrees (atan2 of the cross and dot
// products: accurate near 0 and 180 degrees).
double cornerAngleDegrees(const Vec3d& corner, const Vec3d& a, const Vec3d& b);

}  // namespace weir
