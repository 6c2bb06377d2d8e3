// writePly: ASCII header, then the vertex rows as raw little-endian values.
#include "io/ply_writer.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <ostream>
#include <type_traits>
#include <vector>

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
        out << "property int " << kParticleIdName << "\n"
            << "end_header\n";
        // Rows of the Real columns then the int32 id, through a bounded buffer.
        const auto columns = particleColumns(particles);
        const std::size_t rowBytes = columns.size() * sizeof(Real) + sizeof(std::int32_t);
        constexpr std::size_t kRowsPerChunk = 2048;
        std::vector<char> buffer(kRowsPerChunk * rowBytes);
        // Filled a column at a time: a loop the compiler unrolls (bench/NOTES.md F3).
        for (std::size_t start = 0; start < particles.size(); start += kRowsPerChunk) {
            const std::size_t rows = std::min(kRowsPerChunk, particles.size() - start);
            for (std::size_t c = 0; c < columns.size(); ++c) {
                const Real* from = columns[c]->data() + start;
                char* to = buffer.data() + c * sizeof(Real);
                for (std::size_t j = 0; j < rows; ++j) {
                    std::memcpy(to + j * rowBytes, from + j, sizeof(Real));
                }
            }
            char* ids = buffer.data() + columns.size() * sizeof(Real);
            for (std::size_t j = 0; j < rows; ++j) {
                const std::int32_t id = std::int32_t(particles.idOf(start + j));
                std::memcpy(ids + j * rowBytes, &id, sizeof id);
            }
            out.write(buffer.data(), std::streamsize(rows * rowBytes));
        }
    });
}

}  // namespace weir
