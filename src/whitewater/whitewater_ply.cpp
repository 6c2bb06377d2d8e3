// Binary PLY of diffuse particles: the writer and its strict reader.
#include "whitewater/whitewater_ply.h"

#include <bit>
#include <cstring>
#include <fstream>
#include <sstream>
#include <vector>

#include "io/atomic_file.h"

namespace weir {

namespace {

static_assert(std::endian::native == std::endian::little,
              "whitewater PLY files are written little-endian with the host's byte order");

// The columns in file order: name, and whether it is the uchar kind (else a float).
struct Column {
    const char* name;
    bool isKind;
};
constexpr Column kColumns[] = {{"x", false},  {"y", false},  {"z", false},   {"vx", false},
                               {"vy", false}, {"vz", false}, {"kind", true}, {"lifetime", false}};
constexpr std::size_t kRecordBytes = 7 * sizeof(float) + 1;

std::string header(std::size_t count) {
    std::ostringstream out;
    out << "ply\nformat binary_little_endian 1.0\n"
        << "comment weir whitewater: kind 0 spray, 1 foam, 2 bubble; lifetime in seconds\n"
        << "element vertex " << count << "\n";
    for (const Column& c : kColumns) {
        out << "property " << (c.isKind ? "uchar " : "float ") << c.name << "\n";
    }
    out << "end_header\n";
    return out.str();
}

}  // namespace

void writeWhitewaterPly(const std::string& path, const DiffuseParticles& p) {
    const std::size_t n = p.size();
    std::vector<char> body(n * kRecordBytes);
    char* out = body.data();
    for (std::size_t k = 0; k < n; ++k) {
        const float floats[6] = {p.x[k], p.y[k], p.z[k], p.vx[k], p.vy[k], p.vz[k]};
        std::memcpy(out, floats, sizeof floats);
        out += sizeof floats;
        *out++ = char(p.kind[k]);
        std::memcpy(out, &p.lifetime[k], sizeof(float));
        out += sizeof(float);
    }
    const std::string head = header(n);
    writeFileAtomically(path, [&](std::ostream& file) {
        file.write(head.data(), std::streamsize(head.size()));
        file.write(body.data(), std::streamsize(body.size()));
    });
}

DiffuseParticles readWhitewaterPly(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        throw IoError("cannot open '" + path + "': " + std::strerror(errno));
    }
    auto fail = [&](const std::string& what) {
        throw IoError("'" + path + "' is not a whitewater PLY: " + what);
    };
    std::string line;
    std::getline(in, line);
    if (line != "ply") {
        fail("the first line is not 'ply'");
    }
    std::getline(in, line);
    if (line != "format binary_little_endian 1.0") {
        fail("format '" + line + "', expected binary_little_endian 1.0");
    }
    long long count = -1;
    std::size_t column = 0;
    while (std::getline(in, line) && line != "end_header") {
        std::istringstream words(line);
        std::string word;
        words >> word;
        if (word == "comment") {
            continue;
        }
        if (word == "element") {
            std::string name;
            words >> name >> count;
            if (name != "vertex" || count < 0 || !words) {
                fail("element line '" + line + "', expected 'element vertex N'");
            }
        } else if (word == "property") {
            std::string type, name;
            words >> type >> name;
            if (column >= std::size(kColumns) || name != kColumns[column].name ||
                type != (kColumns[column].isKind ? "uchar" : "float")) {
                fail("property line '" + line + "' where column " + std::to_string(column + 1) +
                     " should be " +
                     (column < std::size(kColumns) ? kColumns[column].name : "none"));
            }
            ++column;
        } else {
            fail("unexpected header line '" + line + "'");
        }
    }
    if (line != "end_header" || count < 0 || column != std::size(kColumns)) {
        fail("the header lacks its vertex element, a column, or end_header");
    }
    const std::size_t n = std::size_t(count);
    std::vector<char> body(n * kRecordBytes);
    in.read(body.data(), std::streamsize(body.size()));
    if (std::size_t(in.gcount()) != body.size()) {
        fail("truncated: " + std::to_string(n) + " particles announced, " +
             std::to_string(std::size_t(in.gcount()) / kRecordBytes) + " present");
    }
    DiffuseParticles p;
    p.resize(n);
    const char* from = body.data();
    for (std::size_t k = 0; k < n; ++k) {
        float floats[6];
        std::memcpy(floats, from, sizeof floats);
        from += sizeof floats;
        p.x[k] = floats[0];
        p.y[k] = floats[1];
        p.z[k] = floats[2];
        p.vx[k] = floats[3];
        p.vy[k] = floats[4];
        p.vz[k] = floats[5];
        p.kind[k] = std::uint8_t(*from++);
        if (p.kind[k] >= kDiffuseKinds) {
            fail("particle " + std::to_string(k) + " has kind " + std::to_string(p.kind[k]) +
                 "; allowed are 0 (spray), 1 (foam), 2 (bubble)");
        }
        std::memcpy(&p.lifetime[k], from, sizeof(float));
        from += sizeof(float);
    }
    return p;
}

}  // namespace weir
