// Triangle-mesh files: Wavefront OBJ (text) and binary little-endian PLY, written atomically.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "io/io_error.h"
#include "solver/particles.h"
#include "surface/triangle_mesh.h"

namespace weir {

// A frame's surface, and what the volume format (vdb) writes beside it: the frame's particles,
// its scale and its time. Mesh-only formats (obj, ply) take the mesh alone.
struct SurfaceFrame {
    const TriangleMesh& mesh;
    const HostParticles* particles = nullptr;  // null: none known (vdb refuses)
    double spacing = 0;                        // particle spacing d [m]
    double cellSize = 0;                       // the surface lattice's cell [m]: vdb's voxel
    double time = 0;                           // [s]
};

// The mesh formats as one table (mesh_writer.cpp): name (also the extension), help, writer.
struct MeshFormatEntry {
    const char* name;
    const char* help;
    void (*write)(const std::string& path, const SurfaceFrame& frame);
};
const std::vector<MeshFormatEntry>& meshFormatTable();

// One entry of the table, with named constants for the formats code refers to.
class MeshFormat {
   public:
    static const MeshFormat Obj, Ply;

    const MeshFormatEntry& entry() const { return meshFormatTable()[index_]; }
    friend bool operator==(MeshFormat a, MeshFormat b) { return a.index_ == b.index_; }

   private:
    friend MeshFormat parseMeshFormat(const std::string& text);
    explicit MeshFormat(std::size_t index) : index_(index) {}
    std::size_t index_;
};

// "obj", "ply" (and "vdb" where OpenVDB is built); anything else throws std::invalid_argument
// naming the value and the allowed list, or, for a format this build lacks, why.
MeshFormat parseMeshFormat(const std::string& text);
// The extension without the dot: "obj", "ply".
std::string meshExtension(MeshFormat format);
// "obj, ply".
std::string meshFormatList();
// For a --format option's help: "one or more of obj (...), ply (...), comma-separated".
std::string meshFormatHelp();

// `v x y z` and `vn nx ny nz` per vertex (shortest text that reads back to the same float), then
// `f a//a b//b c//c` per triangle (1-based). Throws IoError when the file cannot be written.
void writeObj(const std::string& path, const TriangleMesh& mesh);

// `element vertex` with float x y z nx ny nz (and vx vy vz, each vertex's velocity in m/s, where
// `velocities` is given: one per vertex), `element face` with a `list uchar uint vertex_indices`
// of three per triangle. Throws IoError when the file cannot be written.
void writeMeshPly(const std::string& path, const TriangleMesh& mesh,
                  const std::vector<Vec3f>* velocities = nullptr);

void writeMesh(const std::string& path, MeshFormat format, const TriangleMesh& mesh);
void writeMesh(const std::string& path, MeshFormat format, const SurfaceFrame& frame);

}  // namespace weir
