// Boundary particles (Akinci et al. 2012): sampling of walls and obstacles, the volumes psi, the
// rest density they give the fluid at the walls, and mesh obstacles from OBJ and STL files.
#include "scene/boundary.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>

#include "grid/cell_id.h"
#include "scene/mesh_file.h"
#include "scene/setup.h"
#include "solver/simulation.h"

namespace weir {
namespace {

namespace fs = std::filesystem;

const char* kTank = R"({
    "container": {"min": [0, 0, 0], "max": [0.2, 0.3, 0.2]},
    "blocks": [{"min": [0, 0, 0], "max": [0.2, 0.15, 0.2]}],
    "particles": {"spacing": 0.02},
    "walls": {"model": "particles"}
})";

TEST(Boundary, WallLayersSitHalfASpacingBehindEachWall) {
    Scene scene = parseScene(kTank, "<test tank>");
    const double d = 0.02;
    std::vector<Vec3d> points = sampleBoundary(scene, d, 2 * d);
    ASSERT_FALSE(points.empty());
    for (const Vec3d& p : points) {
        // On the box d/2 outside the container: some coordinate sits on that box's face...
        double onFace = 1e9;
        for (int a = 0; a < 3; ++a) {
            onFace = std::min({onFace, std::fabs(p[a] - (scene.container.min[a] - d / 2)),
                               std::fabs(p[a] - (scene.container.max[a] + d / 2))});
            // ...and none lies inside the container.
        }
        EXPECT_LT(onFace, 1e-12);
    }
    // No two closer than half a spacing (edges and corners are not doubled).
    for (std::size_t i = 0; i < points.size(); i += 7) {
        for (std::size_t j = 0; j < points.size(); ++j) {
            if (j != i) {
                ASSERT_GE(length(points[i] - points[j]), 0.5 * d - 1e-12);
            }
        }
    }
    // One layer at h = 2d, two at h = 3d.
    EXPECT_EQ(boundaryLayers(2 * d, d), 1);
    EXPECT_EQ(boundaryLayers(3 * d, d), 2);
    EXPECT_GT(sampleBoundary(scene, d, 3 * d).size(), points.size() * 3 / 2);
}

TEST(Boundary, FluidAtTheWallsStartsAtRestDensity) {
    // With walls of boundary particles the first fluid layer has a full neighbourhood again:
    // its density at t = 0 is rho0 (the simple walls leave it ~30% light at the floor).
    for (double ratio : {2.0, 3.0}) {
        Scene scene = parseScene(kTank, "<test tank>");
        scene.smoothingRatio = ratio;
        SetupReport report;
        auto sim =
            makeSimulation(Backend::Cpu, NeighbourMode::Auto, buildSetup(scene, {}, &report));
        sim->computeDensity();
        HostParticles p;
        sim->download(p);
        const double h = report.smoothingRadius;
        int floorCount = 0;
        for (std::size_t i = 0; i < p.size(); ++i) {
            // The floor layer away from the side walls and below the surface region.
            if (p.y[i] < 0.02 && p.x[i] > h && p.x[i] < 0.2 - h && p.z[i] > h && p.z[i] < 0.2 - h) {
                EXPECT_NEAR(p.rho[i], 1000.0, 5.0) << "ratio " << ratio << " particle " << i;
                ++floorCount;
            }
        }
        EXPECT_GT(floorCount, 0);
    }
}

TEST(Boundary, PsiIsAkincisVolumeCappedAtAFullNeighbourhood) {
    Scene scene = parseScene(kTank, "<test tank>");
    scene.obstacleSpheres.push_back({Vec3d(0.1, 0.22, 0.1), 0.04});
    const double d = 0.02, h = 0.04, full = d * d * d / latticeKernelSum(2.0);
    BoundaryParticles b =
        buildBoundary(sampleBoundary(scene, d, h), scene.container, h, 1000, full);
    double psiMin = 1e9, psiMax = 0;
    for (const Real4& p : b.pos) {
        psiMin = std::min(psiMin, double(p.w));
        psiMax = std::max(psiMax, double(p.w));
    }
    EXPECT_LE(psiMax, 1000 * full * (1 + 1e-6));
    EXPECT_GT(psiMin, 0.3 * 1000 * full);
    // Uncapped, Akinci's value for the single layer facing the fluid exceeds a fluid
    // particle's volume (its own sum misses the fluid's half-space): the cap is what holds.
    BoundaryParticles uncapped =
        buildBoundary(sampleBoundary(scene, d, h), scene.container, h, 1000, 1e9);
    double floorPsi = 0;
    for (const Real4& p : uncapped.pos) {
        if (std::fabs(p.y + d / 2) < 1e-6 && p.x > 0.05 && p.x < 0.15 && p.z > 0.05 && p.z < 0.15) {
            floorPsi = std::max(floorPsi, double(p.w));
        }
    }
    EXPECT_GT(floorPsi, 1.3 * 1000 * full);
    // The grid holds every particle once, in cell order.
    EXPECT_EQ(std::size_t(b.cellStart.back()), b.pos.size());
}

void writeCubeObj(const fs::path& path, double lo, double hi) {
    std::ofstream f(path);
    for (int c = 0; c < 8; ++c) {
        f << "v " << ((c & 1) ? hi : lo) << " " << ((c & 2) ? hi : lo) << " " << ((c & 4) ? hi : lo)
          << "\n";
    }
    // Outward, counter-clockwise seen from outside; quads (fanned by the reader).
    f << "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n";
}

TEST(Boundary, MeshObstaclesFromObjAndStl) {
    const fs::path dir = fs::temp_directory_path() / "weir_mesh_test";
    fs::create_directories(dir);
    writeCubeObj(dir / "cube.obj", 0.0, 1.0);
    MeshData obj = readMeshFile((dir / "cube.obj").string());
    EXPECT_EQ(obj.vertices.size(), 8u);
    EXPECT_EQ(obj.triangles.size(), 12u);

    // The same cube as binary and ASCII STL.
    {
        std::ofstream bin(dir / "cube.stl", std::ios::binary);
        char header[80] = {};
        bin.write(header, 80);
        const std::uint32_t count = 12;
        bin.write(reinterpret_cast<const char*>(&count), 4);
        std::ofstream ascii(dir / "cube_ascii.STL");
        ascii << "solid cube\n";
        for (const auto& t : obj.triangles) {
            float record[12] = {};
            ascii << "facet normal 0 0 0\nouter loop\n";
            for (int k = 0; k < 3; ++k) {
                const Vec3d& v = obj.vertices[t[k]];
                record[3 + 3 * k] = float(v.x);
                record[4 + 3 * k] = float(v.y);
                record[5 + 3 * k] = float(v.z);
                ascii << "vertex " << v.x << " " << v.y << " " << v.z << "\n";
            }
            ascii << "endloop\nendfacet\n";
            bin.write(reinterpret_cast<const char*>(record), 48);
            bin.write("\0\0", 2);
        }
        ascii << "endsolid cube\n";
    }
    for (const char* name : {"cube.stl", "cube_ascii.STL"}) {
        MeshData stl = readMeshFile((dir / name).string());
        EXPECT_EQ(stl.triangles.size(), 12u) << name;
    }

    // In a scene: scaled and moved to a 0.1 m cube on the floor of a tank, it keeps fluid seeds
    // out exactly like the same box obstacle, and its boundary particles lie d/2 inside it.
    const std::string scene = R"({
        "container": {"min": [0, 0, 0], "max": [0.4, 0.3, 0.2]},
        "blocks": [{"min": [0, 0, 0], "max": [0.4, 0.15, 0.2]}],
        "particles": {"spacing": 0.02},
        "obstacles": {)";
    Scene withMesh = parseScene(
        scene +
            R"("meshes": [{"file": "cube.obj", "scale": 0.1, "translate": [0.155, 0, 0.055]}]}})",
        (dir / "mesh.json").string());
    Scene withBox = parseScene(
        scene + R"("boxes": [{"min": [0.155, 0, 0.055], "max": [0.255, 0.1, 0.155]}]}})", "<box>");
    EXPECT_EQ(withMesh.walls, WallModel::Particles);  // meshes act through boundary particles
    const double d = 0.02;
    EXPECT_EQ(seedParticles(withMesh, d).size(), seedParticles(withBox, d).size());
    EXPECT_TRUE(insideMesh(withMesh.obstacleMeshes[0], Vec3d(0.2, 0.05, 0.1)));
    EXPECT_GT(seedParticles(withMesh, d).size(), 0u);
    EXPECT_FALSE(insideMesh(withMesh.obstacleMeshes[0], Vec3d(0.3, 0.05, 0.1)));
    std::size_t inside = 0;
    for (const Vec3d& p : sampleBoundary(withMesh, d, 2 * d)) {
        inside += insideMesh(withMesh.obstacleMeshes[0], p) ? 1 : 0;
    }
    EXPECT_GT(inside, 50u);

    // Errors name the file, the field and what is wrong.
    try {
        parseScene(scene + R"("meshes": [{"file": "missing.obj"}]}})", (dir / "bad.json").string());
        FAIL() << "no error for a missing mesh";
    } catch (const SceneError& e) {
        const std::string text = e.what();
        EXPECT_NE(text.find("obstacles.meshes[0].file"), std::string::npos) << text;
        EXPECT_NE(text.find("cannot open"), std::string::npos) << text;
    }
    try {
        parseScene(scene + R"("meshes": [{"file": "cube.obj"}]}, "walls": {"model": "simple"}})",
                   (dir / "simple.json").string());
        FAIL() << "no error for a mesh with simple walls";
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("walls.model"), std::string::npos) << e.what();
    }
    fs::remove_all(dir);
}

// A blown-up particle (huge or NaN position) lands in a cell of the grid: no float-to-int
// conversion out of range (undefined behaviour) on the way.
TEST(Boundary, CellOfHugeAndNaNPositionsIsClamped) {
    const GridSpec grid = makeGridSpec(Vec3d(0, 0, 0), Vec3d(1, 1, 1), 0.1, 1 << 20);
    const Real huge = Real(1e30), nan = std::numeric_limits<Real>::quiet_NaN();
    const CellCoord far = grid.cellOf(huge, -huge, huge);
    EXPECT_EQ(far.x, grid.dims[0] - 1);
    EXPECT_EQ(far.y, 0);
    EXPECT_EQ(far.z, grid.dims[2] - 1);
    const CellCoord lost = grid.cellOf(nan, nan, nan);
    EXPECT_EQ(lost.x, 0);
    EXPECT_EQ(lost.y, 0);
    EXPECT_EQ(lost.z, 0);
}

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// An obstacle sticking far out of the container (1000 m up) is sampled only where the fluid can
// feel it: the set-up takes well under 2 s (it took minutes), and no boundary particle lies past
// 2 h and the wall layers outside the container (the paper's model: one layer at h = 2d).
TEST(Boundary, ObstaclesAreClippedToTheContainer) {
    const auto start = std::chrono::steady_clock::now();
    Scene scene = parseScene(R"({
        "container": {"min": [0, 0, 0], "max": [1, 0.5, 0.5]},
        "blocks": [{"min": [0, 0, 0], "max": [0.4, 0.3, 0.5]}],
        "obstacles": {"boxes": [{"min": [0.7, 0, 0.1], "max": [0.9, 1000, 0.4]}]},
        "fluid": {"model": "paper"},
        "particles": {"spacing": 0.01},
        "walls": {"model": "particles"}
    })",
                             "<tall obstacle>");
    SimulationSetup setup = buildSetup(scene, {}, nullptr);
    EXPECT_LT(secondsSince(start), 2.0);
    const double d = 0.01, h = 0.02, margin = 2 * h + 2 * d + 1e-6;
    std::size_t inObstacle = 0;
    for (const Real4& b : setup.boundary.pos) {
        ASSERT_LE(double(b.y), 0.5 + margin);
        inObstacle += b.x > 0.7 && b.x < 0.9 && b.z > 0.1 && b.z < 0.4 ? 1 : 0;
    }
    EXPECT_GT(inObstacle, 100u);  // the obstacle's part inside the container is there
    EXPECT_LT(boundarySampleBound(scene, d, h, 1), 1e6);
}

// A mesh triangle much larger than the container is sampled inside it only (it emitted n^2
// points); one too large for its edge to be cut at the spacing is an error naming the mesh.
TEST(Boundary, LargeMeshTrianglesAreClippedOrRefused) {
    const fs::path dir = fs::temp_directory_path() / "weir_big_triangle_test";
    fs::create_directories(dir);
    {
        std::ofstream f(dir / "sheet.obj");  // a 100 m triangle through the container at y = 0.2
        f << "v -50 0.2 -50\nv 50 0.2 -50\nv 0 0.2 50\nf 1 3 2\n";
    }
    const std::string scene = R"({
        "container": {"min": [0, 0, 0], "max": [1, 0.5, 0.5]},
        "blocks": [{"min": [0, 0.25, 0], "max": [0.4, 0.5, 0.5]}],
        "particles": {"spacing": 0.01},
        "obstacles": {"meshes": [{"file": "sheet.obj", "scale": )";
    const auto start = std::chrono::steady_clock::now();
    Scene sheet = parseScene(scene + "1}]}}", (dir / "sheet.json").string());
    const BoundarySamples samples = sampleBoundary(sheet, 0.01, 0.02, 1);
    EXPECT_LT(secondsSince(start), 2.0);
    std::size_t onSheet = 0;
    for (const Vec3d& p : samples.points) {
        onSheet += std::fabs(p.y - (0.2 - 0.005)) < 1e-9 ? 1 : 0;
    }
    EXPECT_GT(onSheet, 5000u);   // the container's cross-section, 1.1 x 0.6 m at d = 0.01
    EXPECT_LT(onSheet, 20000u);  // and not the 5e7 points of the whole triangle

    Scene huge = parseScene(scene + R"(1e4, "translate": [0, -1999.8, 0]}]}})",
                            (dir / "huge.json").string());
    try {
        sampleBoundary(huge, 0.01, 0.02, 1);
        FAIL() << "no error for a 1000 km triangle";
    } catch (const SceneError& e) {
        EXPECT_TRUE(std::string(e.what()).find("sheet.obj") != std::string::npos) << e.what();
        EXPECT_TRUE(std::string(e.what()).find("100000") != std::string::npos) << e.what();
    }
    fs::remove_all(dir);
}

// A closed UV sphere of rings x segments x 2 triangles.
MeshObstacle uvSphere(const Vec3d& centre, double radius, int rings, int segments) {
    MeshObstacle mesh;
    for (int r = 0; r <= rings; ++r) {
        const double theta = kPi * r / rings;
        for (int s = 0; s < segments; ++s) {
            const double phi = 2 * kPi * s / segments;
            mesh.vertices.push_back(centre + Vec3d(std::sin(theta) * std::cos(phi), std::cos(theta),
                                                   std::sin(theta) * std::sin(phi)) *
                                                 radius);
        }
    }
    for (int r = 0; r < rings; ++r) {
        for (int s = 0; s < segments; ++s) {
            const int a = r * segments + s, b = r * segments + (s + 1) % segments;
            const int c = a + segments, e = b + segments;
            mesh.triangles.push_back({a, c, b});
            mesh.triangles.push_back({b, c, e});
        }
    }
    return mesh;
}

// The inside test through the mesh's index gives what testing every triangle gives, and a mesh
// of 245k triangles answers 100k points in well under 2 s (every triangle for every point: hours
// over a scene's 40 counting passes).
TEST(Boundary, InsideMeshThroughTheIndexAgreesWithEveryTriangle) {
    MeshObstacle plain = uvSphere(Vec3d(0.5, 0.4, 0.5), 0.3, 60, 90);
    MeshObstacle indexed = plain;
    buildMeshIndex(indexed);
    ASSERT_TRUE(indexed.index);
    std::mt19937 random(7);
    std::uniform_real_distribution<double> in(0.0, 1.0);
    std::size_t inside = 0;
    for (int k = 0; k < 4000; ++k) {
        const Vec3d p(in(random), in(random), in(random));
        const bool expected = insideMesh(plain, p);
        ASSERT_EQ(insideMesh(indexed, p), expected) << p.x << " " << p.y << " " << p.z;
        inside += expected ? 1 : 0;
    }
    EXPECT_GT(inside, 300u);  // about 4/3 pi 0.3^3 = 11% of the cube
    // Points on the grid of an axis-aligned mesh's vertices, where rays graze edges.
    MeshObstacle cube;
    cube.vertices = {{0.2, 0.2, 0.2}, {0.6, 0.2, 0.2}, {0.2, 0.6, 0.2}, {0.6, 0.6, 0.2},
                     {0.2, 0.2, 0.6}, {0.6, 0.2, 0.6}, {0.2, 0.6, 0.6}, {0.6, 0.6, 0.6}};
    cube.triangles = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                      {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
    MeshObstacle cubeIndexed = cube;
    buildMeshIndex(cubeIndexed);
    for (double x = 0; x <= 0.8; x += 0.1) {
        for (double y = 0; y <= 0.8; y += 0.1) {
            for (double z = 0; z <= 0.8; z += 0.1) {
                ASSERT_EQ(insideMesh(cubeIndexed, {x, y, z}), insideMesh(cube, {x, y, z}))
                    << x << " " << y << " " << z;
            }
        }
    }

    MeshObstacle big = uvSphere(Vec3d(0.5, 0.5, 0.5), 0.4, 350, 350);
    ASSERT_EQ(big.triangles.size(), 245000u);
    const auto start = std::chrono::steady_clock::now();
    buildMeshIndex(big);
    std::size_t bigInside = 0;
    for (int k = 0; k < 100000; ++k) {
        bigInside += insideMesh(big, Vec3d(in(random), in(random), in(random))) ? 1 : 0;
    }
    EXPECT_LT(secondsSince(start), 2.0);
    EXPECT_NEAR(double(bigInside) / 100000, 4.0 / 3.0 * kPi * 0.064, 0.01);
}

}  // namespace
}  // namespace weir
