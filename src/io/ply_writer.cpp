// writePly: ASCII header, then the vertex rows as raw little-endian values.
#include "io/ply_writer.h"

#include <bit>
#include <ostream>
#include <type_traits>

#include "io/atomic_file.h"
#include "io/field_registry.h"
#include "io/io_util.h"

namespace weir {

static_assert(std::endian::native == std::endian::little, "the PLY writer emits native bytes");

void writePly(const std::string& path, const HostParticles& particles) {
    const char* type = std::is_same_v<Real, double> ? "double" : "float";
    writeFileAtomically(path, [&](std::ostream& out) {
        out << "ply\n"
               "format binary_little_endian 1.0\n"
               "comment weir SPH particles\n"
               "element vertex "
            << particles.size() << '\n';
        for (const std::string& name : particleColumnNames()) {
            out << "property " << type << ' ' << name << '\n';
        }
        out << "end_header\n";
        writeInterleaved<Real>(out, particleColumns(particles), particles.size());
    });
}

}  // namespace weir
