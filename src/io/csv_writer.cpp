// writeCsv: header and rows of shortest round-trip numbers.
#include "io/csv_writer.h"

#include <charconv>
#include <ostream>
#include <vector>

#include "io/atomic_file.h"
#include "io/field_registry.h"
#include "io/io_util.h"

namespace weir {

void writeCsv(const std::string& path, const HostParticles& particles) {
    const auto names = particleColumnNames();
    const auto columns = particleColumns(particles);
    writeFileAtomically(path, [&](std::ostream& out) {
        for (std::size_t c = 0; c < names.size(); ++c) {
            out << (c > 0 ? "," : "") << names[c];
        }
        out << ',' << kParticleIdName << '\n';
        // Rows formatted straight into a buffer that goes out in blocks of ~1 MB (a string per
        // row and a stream insertion per row cost a third of the time: bench/NOTES.md F4).
        constexpr std::size_t kValueChars = 64;  // std::to_chars' longest Real, with room
        const std::size_t rowChars = (columns.size() + 1) * (kValueChars + 1);
        constexpr std::size_t kBlock = 1 << 20;
        std::vector<char> buffer(kBlock + rowChars);
        char* const begin = buffer.data();
        char* at = begin;
        for (std::size_t i = 0; i < particles.size(); ++i) {
            for (std::size_t c = 0; c < columns.size(); ++c) {
                if (c > 0) {
                    *at++ = ',';
                }
                at = std::to_chars(at, at + kValueChars, (*columns[c])[i]).ptr;
            }
            *at++ = ',';
            at = std::to_chars(at, at + kValueChars, particles.idOf(i)).ptr;
            *at++ = '\n';
            if (std::size_t(at - begin) >= kBlock) {
                out.write(begin, at - begin);
                at = begin;
            }
        }
        out.write(begin, at - begin);
    });
}

}  // namespace weir
