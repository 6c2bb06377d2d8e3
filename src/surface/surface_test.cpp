// Surface reconstruction on the CPU: a lattice ball and box give closed, outward-wound meshes of
// the right volume and area; spacing estimate, options and bad input.
#include "surface/surface.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "surface/mesh_measures.h"
#include "surface/surface_test_support.h"

namespace weir {
namespace {

using namespace weir::testing;

Vec3d faceNormal(const TriangleMesh& mesh, std::size_t t, double* area = nullptr) {
    const Vec3d a(mesh.positions[mesh.indices[3 * t]]), b(mesh.positions[mesh.indices[3 * t + 1]]),
        c(mesh.positions[mesh.indices[3 * t + 2]]);
    const Vec3d ab = b - a, ac = c - a;
    const Vec3d n{ab.y * ac.z - ab.z * ac.y, ab.z * ac.x - ab.x * ac.z, ab.x * ac.y - ab.y * ac.x};
    if (area != nullptr) {
        *area = 0.5 * length(n);
    }
    return n;
}

// Each triangle's winding normal agrees with its vertices' normals: checked on the triangles
// that are not slivers (a sliver's winding normal is rounding noise), which must be nearly all.
void expectWindingAgreesWithNormals(const TriangleMesh& mesh, double cellSize) {
    std::size_t checked = 0, disagreeing = 0;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        double area = 0;
        const Vec3d n = faceNormal(mesh, t, &area);
        if (area < 1e-3 * cellSize * cellSize) {
            continue;
        }
        ++checked;
        for (int k = 0; k < 3; ++k) {
            if (dot(n, Vec3d(mesh.normals[mesh.indices[3 * t + k]])) <= 0) {
                ++disagreeing;
                break;
            }
        }
    }
    EXPECT_GT(checked, mesh.triangleCount() * 95 / 100);
    EXPECT_EQ(disagreeing, 0u) << "of " << checked << " triangles";
}

void expectUnitNormals(const TriangleMesh& mesh) {
    ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
    for (const Vec3f& n : mesh.normals) {
        ASSERT_NEAR(length(Vec3d(n)), 1.0, 1e-5);
    }
}

TEST(Surface, LatticeBallGivesAClosedSphere) {
    const double d = 0.01, radius = 0.1;
    const Vec3d centre(0.4, 1.2, -0.3);
    const HostParticles ball = latticeBall(centre, radius, d);
    SurfacePlan plan;
    const TriangleMesh mesh = reconstructSurface(Backend::Cpu, ball, SurfaceOptions{}, &plan);
    EXPECT_TRUE(plan.spacingEstimated);
    EXPECT_NEAR(plan.spacing, d, 1e-6);
    EXPECT_NEAR(plan.cellSize, d / 2, 1e-6);

    const MeshMeasures m = measureMesh(mesh);
    ASSERT_GT(mesh.triangleCount(), 1000u);
    EXPECT_TRUE(m.closed()) << m.boundaryEdges << " boundary, " << m.nonManifoldEdges
                            << " non-manifold, " << m.misorientedEdges << " misoriented edges";
    EXPECT_EQ(m.components, 1u);
    EXPECT_EQ(m.eulerCharacteristic, 2);  // a sphere: no handles, no holes
    const double sphereVolume = 4.0 / 3.0 * kPiForTests * radius * radius * radius;
    const double sphereArea = 4 * kPiForTests * radius * radius;
    EXPECT_NEAR(m.volume, sphereVolume, 0.05 * sphereVolume);
    EXPECT_NEAR(m.area, sphereArea, 0.05 * sphereArea);
    // The particles' own volume (N d^3) is the fluid's volume: closer still.
    EXPECT_NEAR(m.volume, double(ball.size()) * d * d * d, 0.03 * sphereVolume);

    expectUnitNormals(mesh);
    expectWindingAgreesWithNormals(mesh, plan.cellSize);
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
        const Vec3d p(mesh.positions[v]), n(mesh.normals[v]);
        const Vec3d outward = (p - centre) / length(p - centre);
        ASSERT_GT(dot(n, outward), 0.8) << "vertex " << v;
        ASSERT_NEAR(length(p - centre), radius, 0.1 * radius) << "vertex " << v;
    }
}

TEST(Surface, LatticeBoxGivesAClosedBox) {
    const double d = 0.02;
    const int counts[3] = {16, 10, 12};
    const Vec3d boxMin(-0.1, 0.05, 0.3);
    const Vec3d size(counts[0] * d, counts[1] * d, counts[2] * d);
    const HostParticles box = latticeBox(boxMin, counts, d);
    SurfacePlan plan;
    const TriangleMesh mesh = reconstructSurface(Backend::Cpu, box, SurfaceOptions{}, &plan);
    EXPECT_NEAR(plan.spacing, d, 1e-6);

    const MeshMeasures m = measureMesh(mesh);
    EXPECT_TRUE(m.closed());
    EXPECT_EQ(m.components, 1u);
    EXPECT_EQ(m.eulerCharacteristic, 2);
    const double volume = size.x * size.y * size.z;
    const double area = 2 * (size.x * size.y + size.y * size.z + size.z * size.x);
    // The kernel rounds the edges and corners off (by about the kernel radius, 2 d): that takes
    // a little volume and, on a box only 10 spacings thick, some 7% of the area.
    EXPECT_NEAR(m.volume, volume, 0.05 * volume);
    EXPECT_LT(m.area, area);
    EXPECT_GT(m.area, 0.9 * area);
    expectUnitNormals(mesh);
    expectWindingAgreesWithNormals(mesh, plan.cellSize);

    // The flat faces lie where the fluid ends, half a spacing beyond the outer particles: the
    // vertices near the middle of the top face sit at its height.
    const Vec3d centre = boxMin + size * 0.5;
    std::size_t onTop = 0;
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
        const Vec3d p(mesh.positions[v]);
        ASSERT_GT(dot(Vec3d(mesh.normals[v]), p - centre), 0) << "vertex " << v;
        if (std::abs(p.x - centre.x) < 0.25 * size.x && std::abs(p.z - centre.z) < 0.25 * size.z &&
            p.y > centre.y) {
            ++onTop;
            EXPECT_NEAR(p.y, boxMin.y + size.y, 0.1 * d);
            EXPECT_GT(mesh.normals[v].y, 0.99f);
        }
    }
    EXPECT_GT(onTop, 20u);
}

TEST(Surface, FinerCellsConvergeOnTheSameSurface) {
    const double d = 0.01, radius = 0.06;
    const HostParticles ball = latticeBall(Vec3d(), radius, d);
    SurfaceOptions coarse, fine;
    coarse.cellSize = 0.8 * d;
    fine.cellSize = 0.25 * d;
    const MeshMeasures a = measureMesh(reconstructSurface(Backend::Cpu, ball, coarse));
    const MeshMeasures b = measureMesh(reconstructSurface(Backend::Cpu, ball, fine));
    EXPECT_TRUE(a.closed());
    EXPECT_TRUE(b.closed());
    EXPECT_NEAR(a.volume, b.volume, 0.02 * b.volume);
}

TEST(Surface, IsoValueInflatesTheSurface) {
    const double d = 0.01;
    const int counts[3] = {10, 10, 10};
    const HostParticles box = latticeBox(Vec3d(), counts, d);
    SurfaceOptions plain, inflated;
    inflated.iso = 0.5;
    const MeshMeasures a = measureMesh(reconstructSurface(Backend::Cpu, box, plain));
    const MeshMeasures b = measureMesh(reconstructSurface(Backend::Cpu, box, inflated));
    EXPECT_TRUE(b.closed());
    // Half a spacing further out on every side: about (10 + 1)^3 / 10^3 of the volume.
    EXPECT_GT(b.volume, 1.2 * a.volume);
    EXPECT_LT(b.volume, 1.45 * a.volume);
}

TEST(Surface, SeparateDropsGiveSeparateClosedPieces) {
    const double d = 0.01;
    HostParticles drops = latticeBall(Vec3d(0, 0, 0), 0.05, d);
    testing::appendPositions(drops, latticeBall(Vec3d(0.2, 0, 0), 0.04, d));
    drops.push(Vec3d(0.1, 0.3, 0), Vec3d());  // a lone spray particle: a small sphere of its own
    const MeshMeasures m = measureMesh(reconstructSurface(Backend::Cpu, drops, SurfaceOptions{}));
    EXPECT_TRUE(m.closed());
    EXPECT_EQ(m.components, 3u);
    EXPECT_EQ(m.eulerCharacteristic, 6);
}

TEST(Surface, SpacingEstimateIsTheNearestNeighbourDistance) {
    const int counts[3] = {20, 5, 8};
    EXPECT_NEAR(estimateParticleSpacing(latticeBox(Vec3d(1, 2, 3), counts, 0.037)), 0.037, 1e-6);
    HostParticles one;
    one.push(Vec3d(1, 1, 1), Vec3d());
    EXPECT_EQ(estimateParticleSpacing(one), 0.0);
}

TEST(Surface, BadInputIsRefusedWithTheValue) {
    HostParticles none;
    EXPECT_THROW(planSurface(none, SurfaceOptions{}), SurfaceError);

    const int counts[3] = {4, 4, 4};
    HostParticles box = latticeBox(Vec3d(), counts, 0.01);
    box.y[5] = std::numeric_limits<Real>::quiet_NaN();
    try {
        planSurface(box, SurfaceOptions{});
        FAIL() << "a NaN position was accepted";
    } catch (const SurfaceError& e) {
        EXPECT_NE(std::string(e.what()).find("particle 5"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("nan"), std::string::npos) << e.what();
    }

    box = latticeBox(Vec3d(), counts, 0.01);
    SurfaceOptions tiny;
    tiny.cellSize = 1e-5;
    try {
        planSurface(box, tiny);
        FAIL() << "a lattice of billions of samples was accepted";
    } catch (const SurfaceError& e) {
        EXPECT_NE(std::string(e.what()).find("limit"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("1e-05"), std::string::npos) << e.what();
    }

    SurfaceOptions iso;
    iso.iso = 5;
    EXPECT_THROW(planSurface(box, iso), std::invalid_argument);
    SurfaceOptions snap;
    snap.snapFraction = 0.3;
    EXPECT_THROW(planSurface(box, snap), std::invalid_argument);
    SurfaceOptions negative;
    negative.cellSize = -1;
    EXPECT_THROW(planSurface(box, negative), std::invalid_argument);

    HostParticles samePoint;
    samePoint.push(Vec3d(1, 1, 1), Vec3d());
    samePoint.push(Vec3d(1, 1, 1), Vec3d());
    EXPECT_THROW(planSurface(samePoint, SurfaceOptions{}), SurfaceError);
    SurfaceOptions given;
    given.spacing = 0.01;
    EXPECT_TRUE(measureMesh(reconstructSurface(Backend::Cpu, samePoint, given)).closed());
}

TEST(Surface, CudaWithoutCudaIsAClearError) {
    if (cudaDeviceAvailable()) {
        GTEST_SKIP() << "a CUDA device is visible";
    }
    const int counts[3] = {4, 4, 4};
    EXPECT_THROW(
        reconstructSurface(Backend::Cuda, latticeBox(Vec3d(), counts, 0.01), SurfaceOptions{}),
        SurfaceError);
}

}  // namespace
}  // namespace weir
