// Marching cubes alone, on fields given at the samples: the generated case table, closed and
// consistently wound meshes for random fields (every ambiguous case included), and a sampled
// sphere's volume, area and normals.
#include "surface/marching_cubes.h"

#include <gtest/gtest.h>

#include <random>
#include <set>
#include <vector>

#include "core/exec_cpu.h"
#include "surface/mesh_measures.h"
#include "surface/surface_pipeline.h"
#include "surface/surface_test_support.h"

namespace weir {
namespace {

using weir::testing::kPiForTests;

// Corner inside flags of a case, and the cube edges cut between them.
std::set<int> cutEdges(int cubeCase) {
    std::set<int> cut;
    for (int e = 0; e < 12; ++e) {
        const int a = cubeEdgeStart(e), b = a | (1 << cubeEdgeAxis(e));
        if (((cubeCase >> a) & 1) != ((cubeCase >> b) & 1)) {
            cut.insert(e);
        }
    }
    return cut;
}

TEST(MarchingCubesTable, TrianglesUseExactlyTheCutEdges) {
    int most = 0;
    for (int c = 0; c < 256; ++c) {
        const int count = kMarchingCubesTable.triangleCount[c];
        most = std::max(most, count);
        std::set<int> used;
        for (int k = 0; k < 3 * count; ++k) {
            used.insert(kMarchingCubesTable.triangleEdges[c][k]);
        }
        EXPECT_EQ(used, cutEdges(c)) << "case " << c;
        // Complementary cases cut the same edges.
        EXPECT_EQ(cutEdges(c), cutEdges(255 - c));
    }
    // The classic table's largest case has 5 triangles; the consistent face rule keeps that.
    EXPECT_LE(most, 5);
    EXPECT_GE(most, 4);
}

TEST(MarchingCubesTable, EdgesJoinTheirCorners) {
    std::set<std::pair<int, int>> pairs;
    for (int e = 0; e < 12; ++e) {
        const int a = cubeEdgeStart(e), b = a | (1 << cubeEdgeAxis(e));
        EXPECT_EQ(a & (1 << cubeEdgeAxis(e)), 0);
        EXPECT_EQ(cubeEdgeBetween(a, b), e);
        EXPECT_EQ(cubeEdgeBetween(b, a), e);
        pairs.insert({a, b});
    }
    EXPECT_EQ(pairs.size(), 12u);
}

TriangleMesh march(std::vector<float>& values, int n, float iso, double cellSize = 1,
                   Vec3d origin = Vec3d()) {
    CpuExec exec;
    SampledFieldView lattice{values.data(), iso, n, n, n, Vec3(origin), Real(cellSize)};
    return marchingCubes(exec, lattice);
}

TEST(MarchingCubes, RandomFieldsGiveClosedConsistentlyWoundMeshes) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> unit(-1, 1);
    const int n = 12;
    std::size_t triangles = 0;
    std::set<int> casesSeen;
    for (int round = 0; round < 20; ++round) {
        std::vector<float> values(n * n * n);
        for (int z = 0; z < n; ++z) {
            for (int y = 0; y < n; ++y) {
                for (int x = 0; x < n; ++x) {
                    const bool border =
                        x == 0 || y == 0 || z == 0 || x == n - 1 || y == n - 1 || z == n - 1;
                    values[(z * n + y) * n + x] = border ? 1.0f : unit(rng);
                }
            }
        }
        SampledFieldView lattice{values.data(), 0.0f, n, n, n, Vec3(), Real(1)};
        for (int z = 0; z + 1 < n; ++z) {
            for (int y = 0; y + 1 < n; ++y) {
                for (int x = 0; x + 1 < n; ++x) {
                    casesSeen.insert(cubeCase(lattice, x, y, z));
                }
            }
        }
        const TriangleMesh mesh = march(values, n, 0.0f);
        const MeshMeasures m = measureMesh(mesh);
        triangles += mesh.triangleCount();
        EXPECT_EQ(m.boundaryEdges, 0u) << "round " << round;
        EXPECT_EQ(m.nonManifoldEdges, 0u) << "round " << round;
        EXPECT_EQ(m.misorientedEdges, 0u) << "round " << round;
        EXPECT_GT(m.volume, 0) << "round " << round;  // wound with the inside enclosed
        for (const Vec3f& v : mesh.positions) {
            ASSERT_GT(v.x, 0.0f);
            ASSERT_LT(v.x, float(n - 1));
        }
    }
    EXPECT_GT(triangles, 10000u);
    EXPECT_GT(casesSeen.size(), 250u);  // nearly every case, the ambiguous ones included
}

TEST(MarchingCubes, SampledSphereHasItsVolumeAreaAndNormals) {
    const int n = 40;
    const double cell = 0.01, radius = 0.13;
    const Vec3d origin(-0.2, -0.2, -0.2), centre(0.003, -0.002, 0.001);
    std::vector<float> values(n * n * n);
    for (int z = 0; z < n; ++z) {
        for (int y = 0; y < n; ++y) {
            for (int x = 0; x < n; ++x) {
                const Vec3d p = origin + Vec3d(x, y, z) * cell;
                values[(z * n + y) * n + x] = float(length(p - centre) - radius);
            }
        }
    }
    const TriangleMesh mesh = march(values, n, 0.0f, cell, origin);
    const MeshMeasures m = measureMesh(mesh);
    EXPECT_TRUE(m.closed());
    EXPECT_EQ(m.eulerCharacteristic, 2);
    const double volume = 4.0 / 3.0 * kPiForTests * radius * radius * radius;
    const double area = 4 * kPiForTests * radius * radius;
    EXPECT_NEAR(m.volume, volume, 0.01 * volume);
    EXPECT_NEAR(m.area, area, 0.01 * area);
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
        const Vec3d p(mesh.positions[v]);
        EXPECT_NEAR(length(p - centre), radius, 1e-3);
        EXPECT_GT(dot(Vec3d(mesh.normals[v]), (p - centre) / length(p - centre)), 0.995);
    }

    // An iso-value away from zero gives the sphere of that radius.
    const MeshMeasures bigger = measureMesh(march(values, n, 0.02f, cell, origin));
    const double r2 = radius + 0.02;
    EXPECT_NEAR(bigger.volume, 4.0 / 3.0 * kPiForTests * r2 * r2 * r2, 0.01 * volume);
}

TEST(MarchingCubes, EmptyAndFullFieldsGiveNoTriangles) {
    std::vector<float> values(5 * 5 * 5, 1.0f);
    EXPECT_EQ(march(values, 5, 0.0f).triangleCount(), 0u);
    EXPECT_EQ(march(values, 5, 2.0f).triangleCount(), 0u);
    EXPECT_EQ(march(values, 5, 2.0f).vertexCount(), 0u);
}

}  // namespace
}  // namespace weir
