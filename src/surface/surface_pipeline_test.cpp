// The pipeline's device-side output path (extractSurfaceInto, what the live water look uses on
// the GPU), run through the CPU backend: particles already in the backend's memory give the mesh
// the host path gives (before slivers are removed), planned from their bounds alone.
#include "surface/surface_pipeline.h"

#include <gtest/gtest.h>

#include "core/exec_cpu.h"
#include "surface/surface_test_support.h"

namespace weir {
namespace {

// extractSurfaceInto into `kept` (reused from call to call) against the host path's mesh.
void expectTheHostPathsMesh(const HostParticles& particles, BackendMesh<CpuExec>& kept) {
    SurfaceOptions options;
    options.spacing = 0.01;
    options.removeSlivers = false;
    const SurfacePlan plan = planSurface(particles, options);
    // The same plan from the bounds alone.
    const SurfacePlan fromBounds =
        planSurfaceForBounds(plan.particleMin, plan.particleMax, options);
    EXPECT_EQ(fromBounds.origin.x, plan.origin.x);
    EXPECT_EQ(fromBounds.dims[0], plan.dims[0]);
    EXPECT_EQ(fromBounds.dims[1], plan.dims[1]);
    EXPECT_EQ(fromBounds.dims[2], plan.dims[2]);
    EXPECT_EQ(fromBounds.binSize, plan.binSize);

    CpuExec exec;
    const TriangleMesh host = extractSurface(exec, particles, plan, "host memory");
    ASSERT_GT(host.triangleCount(), 1000u);
    std::vector<Real4> packed(particles.size());
    for (std::size_t i = 0; i < particles.size(); ++i) {
        packed[i] = {particles.x[i], particles.y[i], particles.z[i], Real(0)};
    }
    const std::int64_t triangles = extractSurfaceInto(exec, packed.data(), Index(packed.size()),
                                                      fromBounds, "host memory", kept);
    EXPECT_EQ(std::size_t(triangles), host.triangleCount());
    ASSERT_EQ(std::size_t(kept.vertexCount), host.positions.size());
    ASSERT_EQ(std::size_t(kept.triangleCount), host.triangleCount());
    for (std::size_t i = 0; i < host.indices.size(); ++i) {
        ASSERT_EQ(kept.indices.data()[i], host.indices[i]) << "index " << i;
    }
    for (std::size_t v = 0; v < host.positions.size(); ++v) {
        for (int a = 0; a < 3; ++a) {
            ASSERT_EQ(kept.positions.data()[v][a], host.positions[v][a]) << "vertex " << v;
            ASSERT_EQ(kept.normals.data()[v][a], host.normals[v][a]) << "vertex " << v;
        }
    }
}

TEST(SurfacePipeline, MeshLeftInTheBackendIsTheHostPathsMesh) {
    HostParticles particles = testing::latticeBall(Vec3d(0.2, 0.2, 0.2), 0.12, 0.01);
    const int counts[3] = {30, 5, 20};
    testing::appendPositions(particles, testing::latticeBox(Vec3d(0, 0, 0), counts, 0.01));
    BackendMesh<CpuExec> kept;
    expectTheHostPathsMesh(particles, kept);
    // Again with the same mesh and working arrays: a smaller fluid, then a larger one.
    expectTheHostPathsMesh(testing::latticeBall(Vec3d(0.1, 0.3, 0.1), 0.08, 0.01), kept);
    HostParticles more = particles;
    testing::appendPositions(more, testing::latticeBall(Vec3d(0.5, 0.4, 0.3), 0.1, 0.01));
    expectTheHostPathsMesh(more, kept);

    // Bounds that are not finite, or no spacing, are refused.
    SurfaceOptions options;
    options.spacing = 0.01;
    EXPECT_THROW(planSurfaceForBounds(Vec3d(0, 0, 0), Vec3d(NAN, 1, 1), options), SurfaceError);
    SurfaceOptions noSpacing;
    EXPECT_THROW(planSurfaceForBounds(Vec3d(0, 0, 0), Vec3d(1, 1, 1), noSpacing),
                 std::invalid_argument);
}

}  // namespace
}  // namespace weir
