// Triangle meshes for obstacles: Wavefront OBJ (v and f records; polygons fanned into triangles)
// and STL (binary or ASCII).
#pragma once

#include <array>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/vec3.h"

namespace weir {

struct MeshData {
    std::vector<Vec3d> vertices;
    std::vector<std::array<int, 3>> triangles;
};

// Reads an OBJ or STL file by its extension (.obj, .stl, any case); throws std::runtime_error
// with what is wrong (and the line, for text formats).
MeshData readMeshFile(const std::string& path);

}  // namespace weir
