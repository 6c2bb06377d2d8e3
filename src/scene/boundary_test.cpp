// Boundary particles (Akinci et al. 2012): sampling of walls and obstacles, the volumes psi, the
// rest density they give the fluid at the walls, and mesh obstacles from OBJ and STL files.
#include "scene/boundary.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>

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

}  // namespace
}  // namespace weir
