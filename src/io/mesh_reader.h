// Readers for the triangle meshes mesh_writer.h writes (OBJ and binary PLY), for tests and for
// tools that draw meshes written earlier.
#pragma once

#include <string>

#include "io/io_error.h"
#include "surface/triangle_mesh.h"

namespace weir {

// Reads `v`, `vn` and triangular `f` lines (`f a b c`, `a//n`, `a/t/n`; 1-based or negative
// indices). Normals are kept when every face corner names the normal of the same index as its
// vertex (as writeObj writes), else left empty. Throws IoError naming the file, the line and what
// is wrong.
TriangleMesh readObj(const std::string& path);

// Reads a binary little-endian PLY with float x y z (and optionally nx ny nz) per vertex and a
// face list of three indices (uchar or int/uint counts and indices). Throws IoError naming the
// file and what is wrong (format, missing property, polygon not a triangle, index out of range,
// truncated).
TriangleMesh readMeshPly(const std::string& path);

// By extension: .obj or .ply.
TriangleMesh readMesh(const std::string& path);

}  // namespace weir
