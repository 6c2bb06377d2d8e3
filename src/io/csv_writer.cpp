// writeCsv: header and rows of shortest round-trip numbers.
#include "io/csv_writer.h"

#include <ostream>

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
        std::string row;
        for (std::size_t i = 0; i < particles.size(); ++i) {
            row.clear();
            for (std::size_t c = 0; c < columns.size(); ++c) {
                row += (c > 0 ? "," : "");
                row += numberText((*columns[c])[i]);
            }
            row += ',';
            row += std::to_string(i);
            row += '\n';
            out << row;
        }
    });
}

}  // namespace weir
