// Sliver cleanup: marching cubes' needles and caps on a dam break's frames (both surface fields)
// and a hand-made needle are removed; the meshes stay closed, consistently wound and in place.
#include "surface/sliver_cleanup.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <random>
#include <vector>

#include "scene/setup.h"
#include "solver/simulation.h"
#include "surface/mesh_measures.h"
#include "surface/surface.h"
#include "surface/surface_test_support.h"

namespace weir {
namespace {

using namespace weir::testing;

void expectNoSlivers(const TriangleMesh& mesh, double cellSize, const char* what) {
    const MeshQuality q = measureQuality(mesh, kSliverEdgeFraction * cellSize, kSliverAngleDegrees);
    EXPECT_GE(q.minEdge, kSliverEdgeFraction * cellSize) << what;
    EXPECT_GE(q.minAngleDegrees, kSliverAngleDegrees) << what;
    EXPECT_EQ(q.shortEdges, 0u) << what;
    EXPECT_EQ(q.smallAngles, 0u) << what;
}

// A square whose upper half is fanned around vertex 4, a thousandth of the side from vertex 0,
// closed into a double-sided sheet (a pillow) so that every edge has two triangles.
TEST(SliverCleanup, CollapsesANeedleAndKeepsThePillowClosed) {
    TriangleMesh mesh;
    mesh.positions = {{0, 0, 0},         {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.0005f, 0.001f, 0},
                      {0.5f, 0.5f, 0.3f}};
    for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
        mesh.normals.push_back({0, 0, 1});
    }
    // Bottom (wound downwards) and a tent over it through vertex 5.
    mesh.indices = {0, 2, 1, 0, 3, 4, 3, 2, 4, 2, 0, 4,  // bottom: 0-4 is a needle's short edge
                    0, 1, 5, 1, 2, 5, 2, 3, 5, 3, 0, 5};
    MeshMeasures before = measureMesh(mesh);
    ASSERT_TRUE(before.closed());
    const double cell = 1.0;
    ASSERT_LT(measureQuality(mesh, 0.01, 1).minEdge, 0.01);
    const SliverCleanupReport report = removeSlivers(mesh, cell);
    EXPECT_GT(report.badTriangles, 0u);
    EXPECT_EQ(report.collapses, 1u);
    EXPECT_EQ(report.left, 0u);
    const MeshMeasures after = measureMesh(mesh);
    EXPECT_TRUE(after.closed());
    EXPECT_EQ(after.eulerCharacteristic, 2);
    EXPECT_EQ(mesh.vertexCount(), 5u);
    EXPECT_NEAR(after.volume, before.volume, 1e-3 * std::abs(before.volume));
    expectNoSlivers(mesh, cell, "pillow");
}

// A dam break in motion, meshed with and without the cleanup, with both fields: marching cubes
// leaves slivers; the cleanup removes them all, keeps every mesh closed with the same pieces and
// holes (less any speck it removed), and moves the volume by next to nothing.
TEST(SliverCleanup, DamBreakFramesHaveNoSlivers) {
    SetupOptions setupOptions;
    setupOptions.particleCount = 1200;
    SetupReport report;
    auto sim = makeSimulation(Backend::Cpu, NeighbourMode::Auto,
                              buildSetup(builtinScene("dam_break"), setupOptions, &report));
    std::size_t slivers = 0, meshes = 0;
    for (double time : {0.2, 0.4}) {
        sim->advanceTo(time);
        HostParticles frame;
        sim->download(frame);
        for (SurfaceField field : {SurfaceField::Isotropic, SurfaceField::Anisotropic}) {
            SurfaceOptions raw, clean;
            raw.spacing = clean.spacing = report.spacing;
            raw.field = clean.field = field;
            raw.removeSlivers = false;
            SurfacePlan plan;
            const TriangleMesh before = reconstructSurface(Backend::Cpu, frame, raw, &plan);
            const TriangleMesh after = reconstructSurface(Backend::Cpu, frame, clean);
            const MeshQuality q0 =
                measureQuality(before, kSliverEdgeFraction * plan.cellSize, kSliverAngleDegrees);
            const MeshQuality q1 =
                measureQuality(after, kSliverEdgeFraction * plan.cellSize, kSliverAngleDegrees);
            std::printf(
                "t = %.2f s, %s: before %zu short edges, %zu small-angle triangles, min edge "
                "%.2e cell, min angle %.4f deg; after %zu, %zu, %.2e cell, %.2f deg\n",
                time, surfaceFieldName(field), q0.shortEdges, q0.smallAngles,
                q0.minEdge / plan.cellSize, q0.minAngleDegrees, q1.shortEdges, q1.smallAngles,
                q1.minEdge / plan.cellSize, q1.minAngleDegrees);
            slivers += q0.shortEdges + q0.smallAngles;
            ++meshes;
            const MeshMeasures m0 = measureMesh(before), m1 = measureMesh(after);
            EXPECT_TRUE(m0.closed());
            EXPECT_TRUE(m1.closed())
                << m1.boundaryEdges << " boundary, " << m1.nonManifoldEdges << " non-manifold, "
                << m1.misorientedEdges << " misoriented edges";
            // Specks (closed pieces under a tenth of a cell) may go: each a sphere.
            TriangleMesh cleaned = before;
            const SliverCleanupReport fixed = removeSlivers(cleaned, plan.cellSize);
            EXPECT_EQ(fixed.left, 0u);
            EXPECT_EQ(cleaned.indices, after.indices);
            EXPECT_EQ(m1.components + fixed.specks, m0.components);
            EXPECT_EQ(m1.eulerCharacteristic + 2 * std::int64_t(fixed.specks),
                      m0.eulerCharacteristic);
            EXPECT_NEAR(m1.volume, m0.volume, 1e-4 * m0.volume);
            expectNoSlivers(after, plan.cellSize, surfaceFieldName(field));
        }
    }
    EXPECT_EQ(meshes, 4u);
    EXPECT_GT(slivers, 0u) << "no slivers to remove: the test checks nothing";
}

// Snapping the field off the iso-value (snappedOffIso) keeps marching cubes' vertices off the
// lattice's samples: the same triangles between the same edges, vertices moved a little, and
// (isotropic field) none of the slivers that vertices near samples make.
TEST(SliverCleanup, SnappingOffTheIsoValueLeavesTheMeshAndRemovesItsSlivers) {
    const double d = 0.01;
    HostParticles ball = testing::latticeBall(Vec3d(0, 0, 0), 0.09, d);
    std::mt19937 rng(5);
    testing::jitterPositions(ball, rng, 0.2 * d);
    SurfaceOptions unsnapped;
    unsnapped.spacing = d;
    unsnapped.removeSlivers = false;
    unsnapped.snapFraction = 0;
    SurfaceOptions snapped = unsnapped;
    snapped.snapFraction = kSurfaceSnapFraction;
    SurfacePlan plan;
    const TriangleMesh a = reconstructSurface(Backend::Cpu, ball, unsnapped, &plan);
    const TriangleMesh b = reconstructSurface(Backend::Cpu, ball, snapped);
    ASSERT_EQ(a.indices, b.indices);
    ASSERT_EQ(a.positions.size(), b.positions.size());
    double largest = 0, sum = 0;
    for (std::size_t v = 0; v < a.positions.size(); ++v) {
        const double moved = length(Vec3d(a.positions[v]) - Vec3d(b.positions[v]));
        largest = std::max(largest, moved);
        sum += moved;
    }
    const double mean = sum / double(a.positions.size());
    std::printf("%zu vertices moved by %.4f cell on average, %.4f at most\n", a.positions.size(),
                mean / plan.cellSize, largest / plan.cellSize);
    // A vertex moves along its edge, by at most half a cell (where both of the edge's ends lie
    // within the margin of iso, it goes to the middle); on average by much less.
    EXPECT_LT(mean, 0.02 * plan.cellSize);
    EXPECT_LE(largest, 0.5001 * plan.cellSize);
    const double minEdge = kSliverEdgeFraction * plan.cellSize;
    const MeshQuality before = measureQuality(a, minEdge, kSliverAngleDegrees);
    const MeshQuality after = measureQuality(b, minEdge, kSliverAngleDegrees);
    std::printf(
        "unsnapped: %zu short edges, %zu small angles; snapped: %zu, %zu (min angle "
        "%.2f deg)\n",
        before.shortEdges, before.smallAngles, after.shortEdges, after.smallAngles,
        after.minAngleDegrees);
    EXPECT_GT(before.shortEdges + before.smallAngles, 0u) << "no slivers: the test checks nothing";
    EXPECT_EQ(after.shortEdges + after.smallAngles, 0u);
}

}  // namespace
}  // namespace weir
