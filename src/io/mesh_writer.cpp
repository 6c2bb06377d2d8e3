// OBJ as text through a bounded buffer; PLY as an ASCII header and raw little-endian records.
#include "io/mesh_writer.h"

#include <bit>
#include <cstdint>
#include <cstring>
#include <ostream>
#include <stdexcept>

#include "io/atomic_file.h"
#include "io/io_util.h"
#include "io/optional_formats.h"
#include "io/vdb_file.h"
#include "surface/point_velocity.h"

namespace weir {

static_assert(std::endian::native == std::endian::little, "the PLY writer emits native bytes");

const std::vector<MeshFormatEntry>& meshFormatTable() {
    // The one place that lists the mesh formats: `weir mesh --format` and `weir run
    // --mesh-format` take a row added here.
    static const std::vector<MeshFormatEntry> table = {
        {"obj", "Wavefront OBJ text with normals",
         [](const std::string& path, const SurfaceFrame& frame) { writeObj(path, frame.mesh); }},
        {"ply", "binary PLY with normals (and per-vertex velocity vx vy vz)",
         [](const std::string& path, const SurfaceFrame& frame) {
             // Each vertex's velocity, for motion blur: the particles' within 2 d
             // (surface/point_velocity.h), as the USD stage's surface has it.
             if (frame.particles != nullptr && frame.spacing > 0) {
                 const std::vector<Vec3f> velocities =
                     particleVelocityAt(*frame.particles, frame.mesh.positions, 2 * frame.spacing);
                 writeMeshPly(path, frame.mesh, &velocities);
             } else {
                 writeMeshPly(path, frame.mesh);
             }
         }},
#if defined(WEIR_HAS_OPENVDB)
        {"vdb", "OpenVDB: the surface as a level set, with a velocity grid and the points",
         [](const std::string& path, const SurfaceFrame& frame) {
             if (frame.particles == nullptr) {
                 throw std::invalid_argument("cannot write '" + path +
                                             "': a vdb surface needs the frame's particles");
             }
             writeVdbFrame(path, *frame.particles, {frame.time, frame.spacing, frame.cellSize},
                           &frame.mesh);
         }},
#endif
    };
    return table;
}

const MeshFormat MeshFormat::Obj = parseMeshFormat("obj");
const MeshFormat MeshFormat::Ply = parseMeshFormat("ply");

MeshFormat parseMeshFormat(const std::string& text) {
    const auto& table = meshFormatTable();
    for (std::size_t i = 0; i < table.size(); ++i) {
        if (text == table[i].name) {
            return MeshFormat(i);
        }
    }
    const std::string missing = missingFormatReason(text);
    if (!missing.empty()) {
        throw std::invalid_argument("mesh format '" + text + "': " + missing);
    }
    throw std::invalid_argument("unknown mesh format '" + text + "': allowed are " +
                                meshFormatList());
}

std::string meshExtension(MeshFormat format) { return format.entry().name; }

std::string meshFormatList() {
    std::string list;
    for (const MeshFormatEntry& entry : meshFormatTable()) {
        list += (list.empty() ? "" : ", ") + std::string(entry.name);
    }
    return list;
}

std::string meshFormatHelp() {
    std::string help;
    for (const MeshFormatEntry& entry : meshFormatTable()) {
        help += (help.empty() ? "" : ", ") + std::string(entry.name) + " (" + entry.help + ")";
    }
    return "one or more of " + help + ", comma-separated";
}

void writeObj(const std::string& path, const TriangleMesh& mesh) {
    writeFileAtomically(path, [&](std::ostream& out) {
        std::string buffer;
        buffer.reserve(1 << 16);
        const auto flush = [&](bool always) {
            if (always || buffer.size() > (1 << 16) - 256) {
                out.write(buffer.data(), std::streamsize(buffer.size()));
                buffer.clear();
            }
        };
        const auto vector = [&](const char* tag, const Vec3f& v) {
            buffer += tag;
            for (int a = 0; a < 3; ++a) {
                buffer += ' ';
                buffer += numberText(v[a]);
            }
            buffer += '\n';
            flush(false);
        };
        buffer += "# weir fluid surface: " + std::to_string(mesh.vertexCount()) + " vertices, " +
                  std::to_string(mesh.triangleCount()) + " triangles\n";
        for (const Vec3f& p : mesh.positions) {
            vector("v", p);
        }
        for (const Vec3f& n : mesh.normals) {
            vector("vn", n);
        }
        for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
            buffer += 'f';
            for (int k = 0; k < 3; ++k) {
                const std::string index = std::to_string(mesh.indices[3 * t + k] + 1ull);
                buffer += ' ';
                buffer += index;
                if (!mesh.normals.empty()) {
                    buffer += "//";
                    buffer += index;
                }
            }
            buffer += '\n';
            flush(false);
        }
        flush(true);
    });
}

void writeMeshPly(const std::string& path, const TriangleMesh& mesh,
                  const std::vector<Vec3f>* velocities) {
    if (!mesh.normals.empty() && mesh.normals.size() != mesh.positions.size()) {
        throw std::invalid_argument("mesh for '" + path + "' has " +
                                    std::to_string(mesh.normals.size()) + " normals for " +
                                    std::to_string(mesh.positions.size()) + " vertices");
    }
    if (velocities != nullptr && velocities->size() != mesh.positions.size()) {
        throw std::invalid_argument("mesh for '" + path + "' has " +
                                    std::to_string(velocities->size()) + " velocities for " +
                                    std::to_string(mesh.positions.size()) + " vertices");
    }
    const int columns = velocities != nullptr ? 9 : 6;
    writeFileAtomically(path, [&](std::ostream& out) {
        out << "ply\n"
               "format binary_little_endian 1.0\n"
               "comment weir fluid surface\n"
               "element vertex "
            << mesh.vertexCount()
            << "\n"
               "property float x\nproperty float y\nproperty float z\n"
               "property float nx\nproperty float ny\nproperty float nz\n"
            << (velocities != nullptr ? "property float vx\nproperty float vy\nproperty float vz\n"
                                      : "")
            << "element face " << mesh.triangleCount()
            << "\n"
               "property list uchar uint vertex_indices\n"
               "end_header\n";
        const bool hasNormals = !mesh.normals.empty();
        writeSequence<float>(out, std::size_t(columns) * mesh.vertexCount(), [&](std::size_t i) {
            const std::size_t v = i / std::size_t(columns);
            const int k = int(i % std::size_t(columns));
            if (k < 3) {
                return mesh.positions[v][k];
            }
            if (k < 6) {
                return hasNormals ? mesh.normals[v][k - 3] : 0.0f;
            }
            return (*velocities)[v][k - 6];
        });
        // 13 bytes per face: the count 3, then three uint32 indices.
        constexpr std::size_t kFaceBytes = 1 + 3 * sizeof(std::uint32_t);
        writeSequence<char>(out, kFaceBytes * mesh.triangleCount(), [&](std::size_t i) {
            const std::size_t t = i / kFaceBytes, byte = i % kFaceBytes;
            if (byte == 0) {
                return char(3);
            }
            const std::uint32_t index = mesh.indices[3 * t + (byte - 1) / 4];
            return char((index >> (8 * ((byte - 1) % 4))) & 0xff);
        });
    });
}

void writeMesh(const std::string& path, MeshFormat format, const TriangleMesh& mesh) {
    format.entry().write(path, SurfaceFrame{mesh});
}

void writeMesh(const std::string& path, MeshFormat format, const SurfaceFrame& frame) {
    format.entry().write(path, frame);
}

}  // namespace weir
