// A triangle mesh on the host: what surface reconstruction produces, mesh writers write and the
// renderer draws.
#pragma once

#include <cstdint>
#include <vector>

#include "core/vec3.h"

namespace weir {

struct TriangleMesh {
    std::vector<Vec3f> positions;        // one per vertex [m]
    std::vector<Vec3f> normals;          // unit, one per vertex, pointing out of the fluid
    std::vector<std::uint32_t> indices;  // three per triangle, counter-clockwise seen from outside

    std::size_t vertexCount() const { return positions.size(); }
    std::size_t triangleCount() const { return indices.size() / 3; }
};

}  // namespace weir
