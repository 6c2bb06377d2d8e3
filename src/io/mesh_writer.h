// Triangle-mesh files: Wavefront OBJ (text) and binary little-endian PLY, written atomically.
#pragma once

#include <string>

#include "io/io_error.h"
#include "surface/triangle_mesh.h"

namespace weir {

enum class MeshFormat { Obj, Ply };

// "obj" or "ply"; anything else throws std::invalid_argument naming the value and the allowed list.
MeshFormat parseMeshFormat(const std::string& text);
// The extension without the dot: "obj", "ply".
std::string meshExtension(MeshFormat format);

// `v x y z` and `vn nx ny nz` per vertex (shortest text that reads back to the same float), then
// `f a//a b//b c//c` per triangle (1-based). Throws IoError when the file cannot be written.
void writeObj(const std::string& path, const TriangleMesh& mesh);

// `element vertex` with float x y z nx ny nz, `element face` with a `list uchar uint
// vertex_indices` of three per triangle. Throws IoError when the file cannot be written.
void writeMeshPly(const std::string& path, const TriangleMesh& mesh);

void writeMesh(const std::string& path, MeshFormat format, const TriangleMesh& mesh);

}  // namespace weir
