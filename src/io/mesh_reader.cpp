// OBJ by lines; PLY by its header, then raw little-endian records.
#include "io/mesh_reader.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "io/io_util.h"

namespace weir {

static_assert(std::endian::native == std::endian::little, "the PLY reader reads native bytes");

namespace {

IoError badFile(const std::string& path, const std::string& what) {
    return IoError("cannot read mesh '" + path + "': " + what);
}

// One corner of an OBJ face, "v", "v/t", "v//n" or "v/t/n", as 0-based indices (-1: absent).
bool parseCorner(const std::string& token, std::size_t vertices, std::size_t normals,
                 long long& vertex, long long& normal) {
    long long fields[3] = {0, 0, 0};
    int field = 0;
    std::size_t start = 0;
    for (std::size_t i = 0; i <= token.size(); ++i) {
        if (i == token.size() || token[i] == '/') {
            if (field > 2) {
                return false;
            }
            const std::string text = token.substr(start, i - start);
            if (!text.empty()) {
                std::size_t used = 0;
                try {
                    fields[field] = std::stoll(text, &used);
                } catch (const std::exception&) {
                    return false;
                }
                if (used != text.size() || fields[field] == 0) {
                    return false;
                }
            } else if (field == 0) {
                return false;
            }
            ++field;
            start = i + 1;
        }
    }
    auto resolve = [](long long index, std::size_t count) {
        return index > 0 ? index - 1 : (index < 0 ? (long long)count + index : -1);
    };
    vertex = resolve(fields[0], vertices);
    normal = fields[2] != 0 ? resolve(fields[2], normals) : -1;
    return vertex >= 0 && vertex < (long long)vertices &&
           (fields[2] == 0 || (normal >= 0 && normal < (long long)normals));
}

}  // namespace

TriangleMesh readObj(const std::string& path) {
    std::ifstream in(path);
    if (!in) {
        throw badFile(path, "no such file or not readable");
    }
    TriangleMesh mesh;
    bool normalsMatch = true;
    std::string line;
    std::size_t lineNumber = 0;
    while (std::getline(in, line)) {
        ++lineNumber;
        std::istringstream words(line);
        std::string tag;
        if (!(words >> tag) || tag[0] == '#') {
            continue;
        }
        const std::string where = "line " + std::to_string(lineNumber);
        if (tag == "v" || tag == "vn") {
            Vec3f v;
            for (int k = 0; k < 3; ++k) {
                std::string word;
                if (!(words >> word)) {
                    throw badFile(path, where + ": '" + tag + "' needs three numbers");
                }
                if (!parseNumber(word, v[k]) || !std::isfinite(v[k])) {
                    throw badFile(path, where + ": '" + tag + "' component " +
                                            std::to_string(k + 1) + " '" + word +
                                            "' is not a finite float");
                }
            }
            (tag == "v" ? mesh.positions : mesh.normals).push_back(v);
        } else if (tag == "f") {
            std::vector<std::string> corners;
            for (std::string corner; words >> corner;) {
                corners.push_back(corner);
            }
            if (corners.size() != 3) {
                throw badFile(path, where + ": a face with " + std::to_string(corners.size()) +
                                        " corners; only triangles are read");
            }
            for (const std::string& corner : corners) {
                long long vertex = -1, normal = -1;
                if (!parseCorner(corner, mesh.positions.size(), mesh.normals.size(), vertex,
                                 normal)) {
                    throw badFile(path, where + ": face corner '" + corner +
                                            "' is not an index of a vertex (and normal) above it");
                }
                normalsMatch = normalsMatch && normal == vertex;
                mesh.indices.push_back(std::uint32_t(vertex));
            }
        }
    }
    if (!normalsMatch || mesh.normals.size() != mesh.positions.size()) {
        mesh.normals.clear();
    }
    return mesh;
}

TriangleMesh readMeshPly(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        throw badFile(path, "no such file or not readable");
    }
    std::string line;
    if (!std::getline(in, line) || line != "ply") {
        throw badFile(path, "not a PLY file (no 'ply' on its first line)");
    }
    struct Property {
        std::string name, type, countType;  // countType set for lists
    };
    struct Element {
        std::string name;
        std::size_t count = 0;
        std::vector<Property> properties;
    };
    std::vector<Element> elements;
    bool binaryLittle = false;
    for (;;) {
        if (!std::getline(in, line)) {
            throw badFile(path, "the header has no 'end_header'");
        }
        std::istringstream words(line);
        std::string keyword;
        words >> keyword;
        if (keyword == "end_header") {
            break;
        }
        if (keyword == "format") {
            std::string format;
            words >> format;
            binaryLittle = format == "binary_little_endian";
        } else if (keyword == "element") {
            Element e;
            std::string count;
            if (!(words >> e.name >> count) || !parseNumber(count, e.count)) {
                throw badFile(path, "header line '" + line + "' is not 'element NAME COUNT'");
            }
            elements.push_back(e);
        } else if (keyword == "property") {
            if (elements.empty()) {
                throw badFile(path, "a property before any element");
            }
            Property p;
            words >> p.type;
            if (p.type == "list") {
                words >> p.countType >> p.type;
            }
            words >> p.name;
            elements.back().properties.push_back(p);
        }
    }
    if (!binaryLittle) {
        throw badFile(path, "only 'format binary_little_endian 1.0' is read");
    }
    auto typeSize = [&](const std::string& type) -> std::size_t {
        if (type == "uchar" || type == "uint8" || type == "char" || type == "int8") return 1;
        if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return 2;
        if (type == "int" || type == "uint" || type == "float" || type == "int32" ||
            type == "uint32" || type == "float32") {
            return 4;
        }
        if (type == "double" || type == "float64") return 8;
        throw badFile(path, "unknown property type '" + type + "'");
    };
    auto readBytes = [&](void* to, std::size_t n, const char* what) {
        if (!in.read(static_cast<char*>(to), std::streamsize(n))) {
            throw badFile(path, std::string("truncated in the ") + what);
        }
    };
    auto readInteger = [&](const std::string& type, const char* what) -> long long {
        std::uint8_t raw[8] = {};
        const std::size_t size = typeSize(type);
        readBytes(raw, size, what);
        if (type == "float" || type == "float32" || type == "double" || type == "float64") {
            throw badFile(path, "face indices of type '" + type + "' (must be integers)");
        }
        const bool isSigned = type == "char" || type == "int8" || type == "short" ||
                              type == "int16" || type == "int" || type == "int32";
        unsigned long long value = 0;
        std::memcpy(&value, raw, size);
        if (isSigned && size < 8 && (value >> (8 * size - 1)) & 1) {
            return (long long)value - (1ll << (8 * size));
        }
        return (long long)value;
    };

    // Every element's records take at least a byte each: a count past the bytes left is refused
    // before anything is allocated.
    const std::streamoff bodyStart = in.tellg();
    in.seekg(0, std::ios::end);
    const std::size_t bodyBytes = std::size_t(in.tellg() - bodyStart);
    in.seekg(bodyStart);
    std::size_t leastBytes = 0;
    for (const Element& element : elements) {
        std::size_t least = 0;
        for (const Property& p : element.properties) {
            least += p.countType.empty() ? typeSize(p.type) : typeSize(p.countType);
        }
        if (element.count > bodyBytes || (least > 0 && element.count > bodyBytes / least) ||
            (leastBytes += std::max<std::size_t>(least, 1) * element.count) > bodyBytes) {
            throw badFile(path, "element '" + element.name + "' claims " +
                                    std::to_string(element.count) + " records, more than the " +
                                    std::to_string(bodyBytes) + " bytes after the header hold");
        }
    }
    TriangleMesh mesh;
    for (const Element& element : elements) {
        if (element.name == "vertex") {
            int at[6] = {-1, -1, -1, -1, -1, -1};
            const char* names[6] = {"x", "y", "z", "nx", "ny", "nz"};
            std::size_t stride = 0;
            std::vector<std::size_t> offsets;
            for (const Property& p : element.properties) {
                if (!p.countType.empty()) {
                    throw badFile(path, "vertex property '" + p.name + "' is a list");
                }
                for (int k = 0; k < 6; ++k) {
                    if (p.name == names[k]) {
                        if (p.type != "float" && p.type != "float32") {
                            throw badFile(path, "vertex property '" + p.name + "' is '" + p.type +
                                                    "', must be float");
                        }
                        at[k] = int(stride);
                    }
                }
                stride += typeSize(p.type);
            }
            for (int k = 0; k < 3; ++k) {
                if (at[k] < 0) {
                    throw badFile(path,
                                  std::string("vertex property '") + names[k] + "' is missing");
                }
            }
            const bool normals = at[3] >= 0 && at[4] >= 0 && at[5] >= 0;
            std::vector<char> record(stride);
            mesh.positions.resize(element.count);
            if (normals) {
                mesh.normals.resize(element.count);
            }
            for (std::size_t i = 0; i < element.count; ++i) {
                readBytes(record.data(), stride, "vertices");
                for (int k = 0; k < 3; ++k) {
                    std::memcpy(&mesh.positions[i][k], record.data() + at[k], 4);
                    if (normals) {
                        std::memcpy(&mesh.normals[i][k], record.data() + at[k + 3], 4);
                    }
                    const int bad = !std::isfinite(mesh.positions[i][k])            ? k
                                    : normals && !std::isfinite(mesh.normals[i][k]) ? k + 3
                                                                                    : -1;
                    if (bad >= 0) {
                        throw badFile(path, "vertex " + std::to_string(i) + " property '" +
                                                names[bad] + "' is not a finite float");
                    }
                }
            }
        } else if (element.name == "face") {
            if (element.properties.size() != 1 || element.properties[0].countType.empty()) {
                throw badFile(path, "the face element must hold one list property of indices");
            }
            const Property& list = element.properties[0];
            mesh.indices.reserve(3 * element.count);
            for (std::size_t f = 0; f < element.count; ++f) {
                const long long count = readInteger(list.countType, "faces");
                if (count != 3) {
                    throw badFile(path, "face " + std::to_string(f) + " has " +
                                            std::to_string(count) +
                                            " corners; only triangles are read");
                }
                for (int k = 0; k < 3; ++k) {
                    const long long index = readInteger(list.type, "faces");
                    if (index < 0 || std::size_t(index) >= mesh.positions.size()) {
                        throw badFile(path, "face " + std::to_string(f) + " names vertex " +
                                                std::to_string(index) + " of " +
                                                std::to_string(mesh.positions.size()));
                    }
                    mesh.indices.push_back(std::uint32_t(index));
                }
            }
        } else {
            std::size_t stride = 0;
            for (const Property& p : element.properties) {
                if (!p.countType.empty()) {
                    throw badFile(path, "element '" + element.name +
                                            "' has a list property and cannot be skipped");
                }
                stride += typeSize(p.type);
            }
            std::vector<char> skip(stride * element.count);
            readBytes(skip.data(), skip.size(), element.name.c_str());
        }
    }
    return mesh;
}

TriangleMesh readMesh(const std::string& path) {
    const std::string extension = std::filesystem::path(path).extension().string();
    if (extension == ".obj") {
        return readObj(path);
    }
    if (extension == ".ply") {
        return readMeshPly(path);
    }
    throw badFile(path, "unknown mesh format '" + extension + "' (allowed: .obj, .ply)");
}

}  // namespace weir
