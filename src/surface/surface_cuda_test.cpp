// On a GPU, the CUDA surface path gives the CPU path's mesh, with either field: the same stages
// over the same lattice, so the same triangles in the same order, vertices within float rounding (a
// field sample within rounding of the iso-value could flip a cube's case: then the measures still
// agree).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "surface/mesh_measures.h"
#include "surface/surface.h"
#include "surface/surface_test_support.h"

namespace weir {
namespace {

using namespace weir::testing;

// Two drops and a slab: several pieces, flat and curved parts.
HostParticles dropsAndSlab() {
    HostParticles particles = latticeBall(Vec3d(0.1, 0.3, 0.1), 0.08, 0.01);
    const HostParticles second = latticeBall(Vec3d(0.35, 0.25, 0.12), 0.05, 0.01);
    const int counts[3] = {30, 6, 20};
    const HostParticles slab = latticeBox(Vec3d(0, 0, 0), counts, 0.01);
    for (const HostParticles* more : {&second, &slab}) {
        for (std::size_t i = 0; i < more->size(); ++i) {
            particles.push(Vec3d(more->x[i], more->y[i], more->z[i]), Vec3d());
        }
    }
    return particles;
}

void expectCudaMatchesCpu(SurfaceField field) {
    if (!cudaDeviceAvailable()) {
        GTEST_SKIP() << "no CUDA device visible: the CUDA surface path runs on GPU machines only";
    }
    const HostParticles particles = dropsAndSlab();
    SurfaceOptions options;
    options.spacing = 0.01;
    options.field = field;
    SurfacePlan plan;
    const TriangleMesh cpu = reconstructSurface(Backend::Cpu, particles, options, &plan);
    const TriangleMesh gpu = reconstructSurface(Backend::Cuda, particles, plan);
    ASSERT_GT(cpu.triangleCount(), 1000u);
    EXPECT_NEAR(double(gpu.vertexCount()), double(cpu.vertexCount()), 1e-3 * cpu.vertexCount());
    if (gpu.indices == cpu.indices) {
        double worst = 0, worstNormal = 0;
        for (std::size_t i = 0; i < cpu.vertexCount(); ++i) {
            worst = std::max(worst, length(Vec3d(gpu.positions[i]) - Vec3d(cpu.positions[i])));
            worstNormal =
                std::max(worstNormal, length(Vec3d(gpu.normals[i]) - Vec3d(cpu.normals[i])));
        }
        EXPECT_LT(worst, 1e-3 * plan.cellSize);
        EXPECT_LT(worstNormal, 1e-3);
    } else {
        std::printf(
            "note: the CUDA mesh's triangles differ from the CPU's (a case flipped by "
            "rounding); comparing measures only\n");
    }
    const MeshMeasures a = measureMesh(cpu), b = measureMesh(gpu);
    EXPECT_TRUE(b.closed());
    EXPECT_EQ(a.components, b.components);
    EXPECT_NEAR(b.volume / a.volume, 1.0, 1e-4);
    EXPECT_NEAR(b.area / a.area, 1.0, 1e-4);
}

TEST(SurfaceCuda, MatchesTheCpuMesh) { expectCudaMatchesCpu(SurfaceField::Isotropic); }

// The anisotropy pass (covariance, Jacobi rotations, smoothed centres) and the anisotropic field
// run the same code on the GPU: the same mesh.
TEST(SurfaceCuda, AnisotropicMatchesTheCpuMesh) { expectCudaMatchesCpu(SurfaceField::Anisotropic); }

}  // namespace
}  // namespace weir
