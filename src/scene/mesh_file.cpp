// OBJ and STL readers for obstacle meshes.
#include "scene/mesh_file.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace weir {
namespace {

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return s;
}

MeshData readObj(std::istream& in) {
    MeshData mesh;
    std::string line;
    int lineNumber = 0;
    while (std::getline(in, line)) {
        ++lineNumber;
        std::istringstream words(line);
        std::string tag;
        words >> tag;
        if (tag == "v") {
            Vec3d v;
            if (!(words >> v.x >> v.y >> v.z)) {
                throw std::runtime_error("line " + std::to_string(lineNumber) +
                                         ": a vertex needs three numbers");
            }
            mesh.vertices.push_back(v);
        } else if (tag == "f") {
            std::vector<int> face;
            std::string item;
            while (words >> item) {
                const int index = std::atoi(item.c_str());  // "7", "7/1", "7//3", "-1"
                const int n = int(mesh.vertices.size());
                const int resolved = index > 0 ? index - 1 : n + index;
                if (index == 0 || resolved < 0 || resolved >= n) {
                    throw std::runtime_error("line " + std::to_string(lineNumber) +
                                             ": face index " + item + " names no vertex (" +
                                             std::to_string(n) + " so far)");
                }
                face.push_back(resolved);
            }
            if (face.size() < 3) {
                throw std::runtime_error("line " + std::to_string(lineNumber) +
                                         ": a face needs at least three vertices");
            }
            for (std::size_t k = 1; k + 1 < face.size(); ++k) {
                mesh.triangles.push_back({face[0], face[k], face[k + 1]});
            }
        }
    }
    return mesh;
}

MeshData readStl(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    MeshData mesh;
    auto addTriangle = [&](const Vec3d& a, const Vec3d& b, const Vec3d& c) {
        const int base = int(mesh.vertices.size());
        mesh.vertices.push_back(a);
        mesh.vertices.push_back(b);
        mesh.vertices.push_back(c);
        mesh.triangles.push_back({base, base + 1, base + 2});
    };
    if (bytes.size() >= 84) {
        std::uint32_t count;
        std::memcpy(&count, bytes.data() + 80, 4);
        if (bytes.size() == 84 + std::size_t(count) * 50) {  // binary
            for (std::uint32_t t = 0; t < count; ++t) {
                const char* record = bytes.data() + 84 + std::size_t(t) * 50 + 12;
                Vec3d v[3];
                for (int k = 0; k < 3; ++k) {
                    float xyz[3];
                    std::memcpy(xyz, record + 12 * k, 12);
                    v[k] = {xyz[0], xyz[1], xyz[2]};
                }
                addTriangle(v[0], v[1], v[2]);
            }
            return mesh;
        }
    }
    std::istringstream text(bytes);
    std::string word;
    std::vector<Vec3d> corners;
    while (text >> word) {
        if (word == "vertex") {
            Vec3d v;
            if (!(text >> v.x >> v.y >> v.z)) {
                throw std::runtime_error("an ASCII STL 'vertex' needs three numbers");
            }
            corners.push_back(v);
        } else if (word == "endfacet") {
            if (corners.size() != 3) {
                throw std::runtime_error("an ASCII STL facet has " +
                                         std::to_string(corners.size()) + " vertices, not 3");
            }
            addTriangle(corners[0], corners[1], corners[2]);
            corners.clear();
        }
    }
    return mesh;
}

}  // namespace

MeshData readMeshFile(const std::string& path) {
    const std::string ext = lower(std::filesystem::path(path).extension().string());
    if (ext != ".obj" && ext != ".stl") {
        throw std::runtime_error("the extension is not .obj or .stl");
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        throw std::runtime_error("cannot open the file");
    }
    MeshData mesh = ext == ".obj" ? readObj(in) : readStl(path);
    if (mesh.triangles.empty()) {
        throw std::runtime_error("the file holds no triangles");
    }
    return mesh;
}

}  // namespace weir
