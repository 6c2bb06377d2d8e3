// Sliver cleanup: marching cubes' needles and caps on a dam break's frames (both surface fields)
// and a hand-made needle are removed; the meshes stay closed, consistently wound and in place.
#include "surface/sliver_cleanup.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
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

}  // namespace
}  // namespace weir
