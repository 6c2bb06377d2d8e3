// Mesh files: what writeObj and writeMeshPly write reads back to the same mesh; malformed files
// are refused with the file and the reason.
#include "io/mesh_reader.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <limits>

#include "io/mesh_writer.h"

namespace weir {
namespace {

namespace fs = std::filesystem;

// A tetrahedron wound outwards, with unit normals pointing away from its centre.
TriangleMesh tetrahedron() {
    TriangleMesh mesh;
    mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    const Vec3f centre{0.25f, 0.25f, 0.25f};
    for (const Vec3f& p : mesh.positions) {
        const Vec3f d = p - centre;
        mesh.normals.push_back(d / float(length(d)));
    }
    mesh.indices = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
    return mesh;
}

class MeshFiles : public ::testing::Test {
   protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() / ("weir_mesh_reader_" + std::to_string(::getpid()));
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    std::string path(const std::string& name) const { return (dir_ / name).string(); }
    void write(const std::string& name, const std::string& text) const {
        std::ofstream(dir_ / name, std::ios::binary) << text;
    }
    fs::path dir_;
};

void expectSameMesh(const TriangleMesh& a, const TriangleMesh& b) {
    ASSERT_EQ(a.positions.size(), b.positions.size());
    ASSERT_EQ(a.normals.size(), b.normals.size());
    EXPECT_EQ(a.indices, b.indices);
    for (std::size_t i = 0; i < a.positions.size(); ++i) {
        for (int k = 0; k < 3; ++k) {
            EXPECT_EQ(a.positions[i][k], b.positions[i][k]);
            EXPECT_EQ(a.normals[i][k], b.normals[i][k]);
        }
    }
}

// A surface PLY written with the frame's particles carries each vertex's velocity (vx vy vz,
// what Houdini reads as attributes and weir_blender.py as `velocity`): for particles all moving
// alike, that velocity; the mesh still reads back.
TEST_F(MeshFiles, SurfacePlyCarriesTheParticlesVelocityPerVertex) {
    const TriangleMesh mesh = tetrahedron();
    HostParticles particles;
    for (int i = 0; i < 4; ++i) {
        for (int j = 0; j < 4; ++j) {
            for (int k = 0; k < 4; ++k) {
                particles.push(Vec3d(i, j, k) * 0.3, Vec3d(1.5, -2, 0.25));
            }
        }
    }
    writeMesh(path("v.ply"), MeshFormat::Ply, SurfaceFrame{mesh, &particles, 0.3});
    expectSameMesh(readMesh(path("v.ply")), mesh);
    std::ifstream in(path("v.ply"), std::ios::binary);
    std::string header, line;
    while (std::getline(in, line) && line != "end_header") {
        header += line + "\n";
    }
    EXPECT_NE(header.find("property float nz\nproperty float vx\nproperty float vy\n"
                          "property float vz\nelement face 4"),
              std::string::npos)
        << header;
    for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
        float record[9];
        in.read(reinterpret_cast<char*>(record), sizeof record);
        EXPECT_FLOAT_EQ(record[0], mesh.positions[v].x);
        EXPECT_NEAR(record[6], 1.5, 1e-5);
        EXPECT_NEAR(record[7], -2, 1e-5);
        EXPECT_NEAR(record[8], 0.25, 1e-5);
    }
    // Without the particles: positions and normals only, as before.
    writeMesh(path("plain.ply"), MeshFormat::Ply, mesh);
    EXPECT_EQ(
        fs::file_size(path("plain.ply")) + 4 * 12 + 3 * std::string("property float vx\n").size(),
        fs::file_size(path("v.ply")));
}

TEST_F(MeshFiles, ObjAndPlyReadBackExactly) {
    const TriangleMesh mesh = tetrahedron();
    writeObj(path("t.obj"), mesh);
    writeMeshPly(path("t.ply"), mesh);
    expectSameMesh(readObj(path("t.obj")), mesh);
    expectSameMesh(readMeshPly(path("t.ply")), mesh);
    expectSameMesh(readMesh(path("t.ply")), mesh);
    // Binary PLY: 4 vertices of 24 bytes and 4 faces of 13 after the header.
    const auto size = fs::file_size(path("t.ply"));
    std::ifstream in(path("t.ply"), std::ios::binary);
    std::string header, line;
    while (std::getline(in, line) && line != "end_header") {
        header += line + "\n";
    }
    EXPECT_EQ(size, header.size() + std::string("end_header\n").size() + 4 * 24 + 4 * 13);
    EXPECT_NE(header.find("format binary_little_endian 1.0"), std::string::npos);
}

TEST_F(MeshFiles, ObjFacesWithoutNormalsAndNegativeIndices) {
    write("q.obj", "# a triangle\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\nf 1/1 2/2 3/3\n");
    const TriangleMesh mesh = readObj(path("q.obj"));
    EXPECT_EQ(mesh.positions.size(), 3u);
    EXPECT_TRUE(mesh.normals.empty());
    EXPECT_EQ(mesh.indices, (std::vector<std::uint32_t>{0, 1, 2, 0, 1, 2}));
}

TEST_F(MeshFiles, MalformedFilesNameTheFileAndTheFault) {
    auto message = [&](const std::string& name) {
        try {
            readMesh(path(name));
        } catch (const IoError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    write("quad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3 4\n");
    EXPECT_NE(message("quad.obj").find("line 5"), std::string::npos) << message("quad.obj");
    EXPECT_NE(message("quad.obj").find("quad.obj"), std::string::npos);
    write("far.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n");
    EXPECT_NE(message("far.obj").find("'4'"), std::string::npos) << message("far.obj");
    write("ascii.ply", "ply\nformat ascii 1.0\nelement vertex 0\nend_header\n");
    EXPECT_NE(message("ascii.ply").find("binary_little_endian"), std::string::npos);
    writeMeshPly(path("cut.ply"), tetrahedron());
    fs::resize_file(path("cut.ply"), fs::file_size(path("cut.ply")) - 5);
    EXPECT_NE(message("cut.ply").find("truncated"), std::string::npos) << message("cut.ply");
    EXPECT_NE(message("missing.obj").find("missing.obj"), std::string::npos);
    write("mesh.stl", "solid");
    EXPECT_NE(message("mesh.stl").find("allowed: .obj, .ply"), std::string::npos);
}

TEST_F(MeshFiles, NonFiniteVerticesAndCountsPastTheFileAreRefused) {
    auto message = [&](const std::string& name) {
        try {
            readMesh(path(name));
        } catch (const IoError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    write("nan.obj", "v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n");
    EXPECT_NE(message("nan.obj").find("line 2: 'v' component 2 'nan'"), std::string::npos)
        << message("nan.obj");
    write("huge.obj", "v 0 0 0\nv 1 0 0\nv 0 1 1e39\nf 1 2 3\n");
    EXPECT_NE(message("huge.obj").find("'1e39' is not a finite float"), std::string::npos)
        << message("huge.obj");
    // A binary PLY whose first vertex's y is NaN, and one claiming 4e9 vertices in a few bytes.
    TriangleMesh mesh = tetrahedron();
    mesh.positions[0].y = std::numeric_limits<float>::quiet_NaN();
    writeMeshPly(path("nan.ply"), mesh);
    EXPECT_NE(message("nan.ply").find("vertex 0 property 'y' is not a finite float"),
              std::string::npos)
        << message("nan.ply");
    write("many.ply",
          "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\n"
          "property float y\nproperty float z\nend_header\n0123456789ab");
    EXPECT_NE(message("many.ply").find("claims 4000000000 records"), std::string::npos)
        << message("many.ply");
    write("negative.ply",
          "ply\nformat binary_little_endian 1.0\nelement vertex -1\nproperty float x\n"
          "end_header\n");
    EXPECT_NE(message("negative.ply").find("is not 'element NAME COUNT'"), std::string::npos)
        << message("negative.ply");
}

}  // namespace
}  // namespace weir
