// Triangle meshes for obstacles: Wavefront OBJ (v and f records; polygons fanned into triangles)
// and STL (binary or ASCII).
#pragma once

#include <array>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "core/vec3.h"

namespace weir {

struct MeshData {
    std::vector<Vec3d> vertices;
    std::vector<std::array<int, 3>> triangles;
};

// The largest coordinate magnitude a mesh file may hold (before the scene's scale): a number
// past it is a broken file, not a model (1e9 mm is 1000 km).
inline constexpr double kMaxMeshCoordinate = 1e9;

// Reads an OBJ or STL file by its extension (.obj, .stl, any case); throws std::runtime_error
// naming the file, the line (or the triangle of a binary STL), the bad value and what is allowed.
// Every number is range checked: coordinates finite and within kMaxMeshCoordinate, indices
// integers naming a vertex above them, a binary STL's triangle count matching its size (checked
// before anything is allocated).
MeshData readMeshFile(const std::string& path);

// The same from bytes already in memory; `name` is the file named in messages.
MeshData parseObjMesh(std::string_view text, const std::string& name);
MeshData parseStlMesh(std::string_view bytes, const std::string& name);

}  // namespace weir
