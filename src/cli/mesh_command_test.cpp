// End-to-end tests of `weir mesh` and `weir run --mesh`: per-frame OBJ and PLY files that parse,
// are closed, wound outwards with vertex normals that agree, and hold the fluid's volume; bad
// options are refused with the value and what is allowed.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "cli/cli_test_support.h"
#include "io/mesh_reader.h"
#include "surface/mesh_measures.h"

namespace weir {
namespace {

using namespace cli_testing;

// 6 x 8 x 5 particles at 1 cm: a 6 x 8 x 5 cm block in a 16 x 12 x 5 cm box.
constexpr const char* kBlockScene = R"({
    "name": "block",
    "container": {"min": [0, 0, 0], "max": [0.16, 0.12, 0.05]},
    "blocks": [{"min": [0, 0, 0], "max": [0.06, 0.08, 0.05]}],
    "particles": {"spacing": 0.01},
    "time": {"duration": 1, "frameRate": 30}
})";
constexpr double kBlockVolume = 0.06 * 0.08 * 0.05;

class MeshCli : public Cli {};

// Closed, outward (positive volume), and each triangle's winding agrees with the normals of its
// corners (sliver triangles, whose winding normal is rounding noise, aside).
void expectClosedOutwardMesh(const TriangleMesh& mesh, const std::string& name) {
    ASSERT_GT(mesh.triangleCount(), 100u) << name;
    ASSERT_EQ(mesh.normals.size(), mesh.positions.size()) << name;
    const MeshMeasures m = measureMesh(mesh);
    EXPECT_TRUE(m.closed()) << name << ": " << m.boundaryEdges << " boundary, "
                            << m.misorientedEdges << " misoriented edges";
    EXPECT_GT(m.volume, 0) << name;
    std::size_t checked = 0, disagreeing = 0;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        const Vec3d a(mesh.positions[mesh.indices[3 * t]]);
        const Vec3d b(mesh.positions[mesh.indices[3 * t + 1]]);
        const Vec3d c(mesh.positions[mesh.indices[3 * t + 2]]);
        const Vec3d ab = b - a, ac = c - a;
        const Vec3d n{ab.y * ac.z - ab.z * ac.y, ab.z * ac.x - ab.x * ac.z,
                      ab.x * ac.y - ab.y * ac.x};
        if (0.5 * length(n) < 1e-3 * 0.005 * 0.005) {
            continue;
        }
        ++checked;
        for (int k = 0; k < 3; ++k) {
            const Vec3d normal(mesh.normals[mesh.indices[3 * t + k]]);
            EXPECT_NEAR(length(normal), 1.0, 1e-4);
            if (dot(n, normal) <= 0) {
                ++disagreeing;
                break;
            }
        }
    }
    EXPECT_GT(checked, mesh.triangleCount() * 9 / 10) << name;
    EXPECT_EQ(disagreeing, 0u) << name << ": of " << checked << " triangles";
}

TEST_F(MeshCli, RunWritesClosedOutwardMeshesPerFrameInObjAndPly) {
    writeFile("block.json", kBlockScene);
    const RunResult run =
        weir("run block.json --backend cpu --quiet --frames 2 --out frames --mesh");
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_TRUE(contains(run.output, "3 meshes in frames/mesh/"));
    // Exactly the meshes: no temporaries left behind.
    EXPECT_EQ(
        entries(dir_ / "frames" / "mesh"),
        (std::vector<std::string>{"surface_00000.obj", "surface_00000.ply", "surface_00001.obj",
                                  "surface_00001.ply", "surface_00002.obj", "surface_00002.ply"}));
    for (int frame = 0; frame <= 2; ++frame) {
        const std::string base = path("frames/mesh/surface_0000" + std::to_string(frame));
        const TriangleMesh obj = readObj(base + ".obj");
        const TriangleMesh ply = readMeshPly(base + ".ply");
        expectClosedOutwardMesh(obj, base + ".obj");
        expectClosedOutwardMesh(ply, base + ".ply");
        // The two files hold the same mesh (OBJ's shortest round-trip text is exact).
        ASSERT_EQ(obj.indices, ply.indices);
        ASSERT_EQ(obj.positions.size(), ply.positions.size());
        for (std::size_t i = 0; i < obj.positions.size(); ++i) {
            ASSERT_EQ(obj.positions[i].x, ply.positions[i].x);
            ASSERT_EQ(obj.normals[i].z, ply.normals[i].z);
        }
        // Frame 0 is the seeded block: its volume within the rounding of the block's edges and
        // corners. Later the collapsing block spreads and thins at its front, where the surface
        // hugs the particles more closely, so less volume but still most of it.
        const double volume = measureMesh(ply).volume / kBlockVolume;
        if (frame == 0) {
            EXPECT_NEAR(volume, 1.0, 0.1) << base;
        } else {
            EXPECT_GT(volume, 0.7) << base;
            EXPECT_LT(volume, 1.1) << base;
        }
    }
}

TEST_F(MeshCli, MeshCommandMeshesAnExistingRun) {
    writeFile("block.json", kBlockScene);
    ASSERT_EQ(
        weir("run block.json --backend cpu --quiet --frames 1 --out frames --format ply").exitCode,
        0);
    const RunResult mesh = weir("mesh frames --format ply --backend cpu --out surfaces");
    ASSERT_EQ(mesh.exitCode, 0) << mesh.output;
    EXPECT_TRUE(contains(mesh.output, "2 meshes in surfaces/"));
    EXPECT_TRUE(contains(mesh.output, "spacing 0.01 m"));  // measured on frame 0
    EXPECT_EQ(entries(dir_ / "surfaces"),
              (std::vector<std::string>{"surface_00000.ply", "surface_00001.ply"}));
    const TriangleMesh first = readMesh(path("surfaces/surface_00000.ply"));
    expectClosedOutwardMesh(first, "surface_00000.ply");
    EXPECT_NEAR(measureMesh(first).volume / kBlockVolume, 1.0, 0.1);

    // A finer cell converges on the same surface: more triangles, nearly the same volume.
    ASSERT_EQ(weir("mesh frames --format obj --backend cpu --cell-size 0.0025 --quiet --out fine")
                  .exitCode,
              0);
    const TriangleMesh fine = readMesh(path("fine/surface_00000.obj"));
    expectClosedOutwardMesh(fine, "fine surface_00000.obj");
    EXPECT_GT(fine.triangleCount(), first.triangleCount() * 3 / 2);
    EXPECT_NEAR(measureMesh(fine).volume / measureMesh(first).volume, 1.0, 0.03);

    // Yu & Turk's anisotropic kernels: a closed block, each face 0.3 d in (the smoothed centres,
    // anisotropy.h): 5.4 x 7.4 x 4.4 of the 6 x 8 x 5 spacings, 0.73 of the volume.
    const RunResult aniso =
        weir("mesh frames --format ply --backend cpu --surface-field anisotropic --out aniso");
    ASSERT_EQ(aniso.exitCode, 0) << aniso.output;
    EXPECT_TRUE(contains(aniso.output, "anisotropic field"));
    const TriangleMesh anisotropic = readMesh(path("aniso/surface_00000.ply"));
    expectClosedOutwardMesh(anisotropic, "anisotropic surface_00000.ply");
    EXPECT_NEAR(measureMesh(anisotropic).volume / kBlockVolume, 0.73, 0.05);
    EXPECT_NE(anisotropic.vertexCount(), first.vertexCount());
}

TEST_F(MeshCli, BadInputIsRefusedWithTheValue) {
    const RunResult missing = weir("mesh nowhere");
    EXPECT_EQ(missing.exitCode, 1) << missing.output;
    EXPECT_TRUE(contains(missing.output, "'nowhere'"));

    writeFile("block.json", kBlockScene);
    ASSERT_EQ(weir("run block.json --backend cpu --quiet --frames 0 --out frames").exitCode, 0);
    const RunResult format = weir("mesh frames --format stl");
    EXPECT_EQ(format.exitCode, 2) << format.output;
    EXPECT_TRUE(contains(format.output, "'stl'"));
    EXPECT_TRUE(contains(format.output, "obj, ply"));

    const RunResult cell = weir("mesh frames --cell-size -1");
    EXPECT_EQ(cell.exitCode, 2) << cell.output;
    EXPECT_TRUE(contains(cell.output, "--cell-size -1"));

    const RunResult iso = weir("mesh frames --iso 9");
    EXPECT_EQ(iso.exitCode, 2) << iso.output;
    EXPECT_TRUE(contains(iso.output, "iso-value is 9"));

    const RunResult field = weir("mesh frames --surface-field blobby");
    EXPECT_EQ(field.exitCode, 2) << field.output;
    EXPECT_TRUE(contains(field.output, "--surface-field")) << field.output;
    EXPECT_TRUE(contains(field.output, "blobby")) << field.output;
    EXPECT_TRUE(contains(field.output, "anisotropic")) << field.output;

    const RunResult runFormat = weir("run block.json --frames 0 --mesh --mesh-format vtk");
    EXPECT_EQ(runFormat.exitCode, 2) << runFormat.output;
    EXPECT_TRUE(contains(runFormat.output, "'vtk'"));

    const RunResult help = weir("mesh --help");
    EXPECT_EQ(help.exitCode, 0);
    for (const char* option :
         {"--format", "--backend", "--cell-size", "--iso", "--spacing", "--surface-field"}) {
        EXPECT_TRUE(contains(help.output, option));
    }
}

}  // namespace
}  // namespace weir
