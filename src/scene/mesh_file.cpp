// OBJ and STL readers for obstacle meshes: every number parsed with std::from_chars and range
// checked (atoi and stream extraction let overflow and NaN through).
#include "scene/mesh_file.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

namespace weir {
namespace {

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return s;
}

// The largest mesh the readers build: triangle corners are ints.
constexpr std::size_t kMaxVertices = INT_MAX / 4;

[[noreturn]] void fail(const std::string& name, const std::string& where, const std::string& what) {
    throw std::runtime_error(name + (where.empty() ? "" : " " + where) + ": " + what);
}

// Splits a line at blanks (spaces, tabs, carriage returns).
std::vector<std::string_view> wordsOf(std::string_view line) {
    std::vector<std::string_view> words;
    std::size_t at = 0;
    while (at < line.size()) {
        while (at < line.size() && std::isspace(static_cast<unsigned char>(line[at]))) {
            ++at;
        }
        const std::size_t start = at;
        while (at < line.size() && !std::isspace(static_cast<unsigned char>(line[at]))) {
            ++at;
        }
        if (at > start) {
            words.push_back(line.substr(start, at - start));
        }
    }
    return words;
}

// Calls visit(words, "line N") for each line of text that holds a word (lines end at '\n').
template <class Visit>
void forEachLineOfWords(std::string_view text, Visit&& visit) {
    std::size_t lineNumber = 0;
    for (std::size_t start = 0; start < text.size();) {
        const std::size_t end = std::min(text.find('\n', start), text.size());
        const std::string_view line = text.substr(start, end - start);
        start = end + 1;
        ++lineNumber;
        const std::vector<std::string_view> words = wordsOf(line);
        if (!words.empty()) {
            visit(words, "line " + std::to_string(lineNumber));
        }
    }
}

// A short, printable quote of a token for messages.
std::string quoted(std::string_view text) {
    std::string out = "'";
    for (char c : text.substr(0, 40)) {
        out += std::isprint(static_cast<unsigned char>(c)) ? c : '?';
    }
    return out + (text.size() > 40 ? "...'" : "'");
}

// A coordinate: all of `text` a finite number within kMaxMeshCoordinate.
double coordinate(std::string_view text, const std::string& name, const std::string& where,
                  const char* axis) {
    double value = 0;
    const char* begin = text.data();
    if (!text.empty() && text[0] == '+') {
        ++begin;  // from_chars takes no '+'
    }
    const auto result = std::from_chars(begin, text.data() + text.size(), value);
    if (result.ec != std::errc() || result.ptr != text.data() + text.size() ||
        !std::isfinite(value) || std::fabs(value) > kMaxMeshCoordinate) {
        fail(name, where,
             std::string("vertex ") + axis + " " + quoted(text) +
                 " is not a finite number of magnitude at most 1e9");
    }
    return value;
}

Vec3d vertexOf(const std::vector<std::string_view>& words, std::size_t first,
               const std::string& name, const std::string& where) {
    if (words.size() < first + 3) {
        fail(name, where,
             "a vertex needs three numbers, it has " + std::to_string(words.size() - first));
    }
    return {coordinate(words[first], name, where, "x"),
            coordinate(words[first + 1], name, where, "y"),
            coordinate(words[first + 2], name, where, "z")};
}

// A face corner "7", "7/1", "7//3" or "-1": the 0-based vertex it names, of `count` so far.
int cornerIndex(std::string_view item, int count, const std::string& name,
                const std::string& where) {
    const std::string allowed = count == 0
                                    ? "no vertex is defined above it"
                                    : "allowed: 1.." + std::to_string(count) + " or -" +
                                          std::to_string(count) + "..-1, the vertices above it";
    std::string_view parts[3];
    int partCount = 0;
    for (std::size_t start = 0;;) {
        const std::size_t slash = item.find('/', start);
        if (partCount == 3) {
            fail(name, where, "face corner " + quoted(item) + " has more than three parts");
        }
        parts[partCount++] = item.substr(start, slash - start);
        if (slash == std::string_view::npos) {
            break;
        }
        start = slash + 1;
    }
    for (int k = 0; k < partCount; ++k) {
        long long value = 0;
        const std::string_view text = parts[k];
        const auto result = std::from_chars(text.data(), text.data() + text.size(), value);
        const bool integer = result.ec == std::errc() && result.ptr == text.data() + text.size();
        if (k == 0 && !integer) {
            fail(name, where,
                 "face index " + quoted(item) + " is not an integer (" + allowed + ")");
        }
        if (k > 0 && !text.empty() && !integer) {
            fail(name, where,
                 "face corner " + quoted(item) + " has a texture or normal index " + quoted(text) +
                     " that is not an integer");
        }
    }
    long long index = 0;
    std::from_chars(parts[0].data(), parts[0].data() + parts[0].size(), index);
    const long long resolved = index > 0 ? index - 1 : count + index;
    if (index == 0 || resolved < 0 || resolved >= count) {
        fail(name, where, "face index " + quoted(parts[0]) + " names no vertex (" + allowed + ")");
    }
    return int(resolved);
}

// The shortest text of a float ("nan", "inf", "3e+38").
std::string shortNumber(float value) {
    char text[32];
    const auto result = std::to_chars(text, text + sizeof text, value);
    return std::string(text, result.ptr);
}

void addTriangle(MeshData& mesh, const Vec3d& a, const Vec3d& b, const Vec3d& c) {
    const int base = int(mesh.vertices.size());
    mesh.vertices.push_back(a);
    mesh.vertices.push_back(b);
    mesh.vertices.push_back(c);
    mesh.triangles.push_back({base, base + 1, base + 2});
}

bool startsWithSolid(std::string_view bytes) {
    const std::size_t first = bytes.find_first_not_of(" \t\r\n");
    return first != std::string_view::npos && bytes.substr(first, 5) == "solid";
}

MeshData parseBinaryStl(std::string_view bytes, std::uint32_t count, const std::string& name) {
    MeshData mesh;
    mesh.vertices.reserve(3 * std::size_t(count));
    mesh.triangles.reserve(count);
    for (std::uint32_t t = 0; t < count; ++t) {
        const char* record = bytes.data() + 84 + std::size_t(t) * 50 + 12;
        Vec3d v[3];
        for (int k = 0; k < 3; ++k) {
            float xyz[3];
            std::memcpy(xyz, record + 12 * k, 12);
            for (int a = 0; a < 3; ++a) {
                if (!std::isfinite(xyz[a]) || std::fabs(xyz[a]) > kMaxMeshCoordinate) {
                    fail(name, "triangle " + std::to_string(t + 1) + " of " + std::to_string(count),
                         std::string("vertex ") + char('1' + k) + " " + char('x' + a) + " is " +
                             shortNumber(xyz[a]) +
                             " (allowed: a finite number of magnitude at most 1e9)");
                }
            }
            v[k] = {xyz[0], xyz[1], xyz[2]};
        }
        addTriangle(mesh, v[0], v[1], v[2]);
    }
    return mesh;
}

MeshData parseAsciiStl(std::string_view text, const std::string& name) {
    MeshData mesh;
    std::vector<Vec3d> corners;
    forEachLineOfWords(
        text, [&](const std::vector<std::string_view>& words, const std::string& where) {
            if (words[0] == "vertex") {
                if (corners.size() == 3) {
                    fail(name, where, "a facet with more than three vertices (only triangles)");
                }
                corners.push_back(vertexOf(words, 1, name, where));
            } else if (words[0] == "endfacet") {
                if (corners.size() != 3) {
                    fail(name, where,
                         "an ASCII STL facet has " + std::to_string(corners.size()) +
                             " vertices, not 3");
                }
                if (mesh.vertices.size() + 3 > kMaxVertices) {
                    fail(name, where, "more than " + std::to_string(kMaxVertices) + " vertices");
                }
                addTriangle(mesh, corners[0], corners[1], corners[2]);
                corners.clear();
            }
        });
    return mesh;
}

}  // namespace

MeshData parseObjMesh(std::string_view text, const std::string& name) {
    MeshData mesh;
    std::vector<int> face;
    forEachLineOfWords(text, [&](const std::vector<std::string_view>& words,
                                 const std::string& where) {
        if (words[0] == "v") {
            if (mesh.vertices.size() >= kMaxVertices) {
                fail(name, where, "more than " + std::to_string(kMaxVertices) + " vertices");
            }
            mesh.vertices.push_back(vertexOf(words, 1, name, where));
        } else if (words[0] == "f") {
            face.clear();
            const int count = int(mesh.vertices.size());
            for (std::size_t k = 1; k < words.size(); ++k) {
                face.push_back(cornerIndex(words[k], count, name, where));
            }
            if (face.size() < 3) {
                fail(name, where,
                     "a face needs at least three vertices, it has " + std::to_string(face.size()));
            }
            for (std::size_t k = 1; k + 1 < face.size(); ++k) {
                mesh.triangles.push_back({face[0], face[k], face[k + 1]});
            }
        }
    });
    return mesh;
}

MeshData parseStlMesh(std::string_view bytes, const std::string& name) {
    // Binary: an 80-byte header, a 32-bit triangle count, 50 bytes per triangle. Some binary
    // files start with "solid" too, so the size decides first.
    if (bytes.size() >= 84) {
        std::uint32_t count;
        std::memcpy(&count, bytes.data() + 80, 4);
        const std::uint64_t needed = 84 + std::uint64_t(count) * 50;
        if (bytes.size() == needed) {
            if (std::size_t(count) * 3 > kMaxVertices) {
                fail(name, "",
                     "a binary STL of " + std::to_string(count) + " triangles (at most " +
                         std::to_string(kMaxVertices / 3) + ")");
            }
            return parseBinaryStl(bytes, count, name);
        }
        if (!startsWithSolid(bytes)) {
            fail(name, "",
                 "binary STL header says " + std::to_string(count) + " triangles, which need " +
                     std::to_string(needed) + " bytes, but the file has " +
                     std::to_string(bytes.size()) + " (truncated, or not an STL file)");
        }
    } else if (!startsWithSolid(bytes)) {
        fail(name, "",
             "a file of " + std::to_string(bytes.size()) +
                 " bytes is neither ASCII STL (starting with 'solid') nor binary STL "
                 "(84 bytes or more)");
    }
    return parseAsciiStl(bytes, name);
}

MeshData readMeshFile(const std::string& path) {
    const std::string ext = lower(std::filesystem::path(path).extension().string());
    if (ext != ".obj" && ext != ".stl") {
        throw std::runtime_error(path + ": the extension is not .obj or .stl");
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        throw std::runtime_error(path + ": cannot open the file");
    }
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    MeshData mesh = ext == ".obj" ? parseObjMesh(bytes, path) : parseStlMesh(bytes, path);
    if (mesh.triangles.empty()) {
        throw std::runtime_error(path + ": the file holds no triangles");
    }
    return mesh;
}

}  // namespace weir
