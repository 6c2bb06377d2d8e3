// The sparse surface lattice: the same mesh as the dense lattice, memory that follows the fluid,
// and the block flags that make it exact.
#include "surface/sparse_lattice.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "core/exec_cpu.h"
#include "surface/mesh_measures.h"
#include "surface/surface_pipeline.h"
#include "surface/surface_test_support.h"

namespace weir {
namespace {

using testing::latticeBall;
using testing::latticeBox;

// Meshes a field over the whole dense lattice of the plan, as surfaces were built before the
// sparse lattice.
struct DenseSurfaceBuild {
    CpuExec* exec;
    const SurfacePlan* plan;

    template <class Field>
    TriangleMesh operator()(const Field& field, const Real4*, Index) const {
        std::vector<float> values(static_cast<std::size_t>(plan->sampleCount()));
        const SampledFieldView lattice{values.data(),       float(plan->iso), plan->dims[0],
                                       plan->dims[1],       plan->dims[2],    Vec3(plan->origin),
                                       Real(plan->cellSize)};
        sampleField(*exec, field, lattice, values.data(), float(plan->snapMargin));
        return marchingCubes(*exec, lattice);
    }
};

// A mesh as a sorted list of triangles, each its three vertices (position and normal bits) from
// the smallest one on in the winding order: equal for two meshes with the same triangles,
// whatever order their vertices and triangles come in.
using VertexKey = std::array<std::uint32_t, 6>;
using TriangleKey = std::array<VertexKey, 3>;

std::vector<TriangleKey> canonicalTriangles(const TriangleMesh& mesh) {
    const auto keyOf = [&](std::uint32_t v) {
        VertexKey key;
        for (int a = 0; a < 3; ++a) {
            const float position = mesh.positions[v][a], normal = mesh.normals[v][a];
            std::memcpy(&key[a], &position, 4);
            std::memcpy(&key[3 + a], &normal, 4);
        }
        return key;
    };
    std::vector<TriangleKey> triangles;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        TriangleKey key{keyOf(mesh.indices[3 * t]), keyOf(mesh.indices[3 * t + 1]),
                        keyOf(mesh.indices[3 * t + 2])};
        std::rotate(key.begin(), std::min_element(key.begin(), key.end()), key.end());
        triangles.push_back(key);
    }
    std::sort(triangles.begin(), triangles.end());
    return triangles;
}

// A splash: a jittered ball, a sheet one particle thick beside it and lone drops, some near the
// lattice's faces.
HostParticles splash(double d) {
    HostParticles particles = latticeBall(Vec3d(0, 0, 0), 0.06, d);
    std::mt19937 rng(11);
    testing::jitterPositions(particles, rng, 0.15 * d);
    std::uniform_real_distribution<double> jitter(-0.15 * d, 0.15 * d);
    for (int i = 0; i < 12; ++i) {
        for (int k = 0; k < 9; ++k) {
            particles.push(Vec3d(0.09 + i * d, 0.01 + jitter(rng), -0.04 + k * d), Vec3d());
        }
    }
    particles.push(Vec3d(-0.12, 0.11, 0.05), Vec3d());
    particles.push(Vec3d(0.25, -0.09, 0.0), Vec3d());
    return particles;
}

void expectSparseMeshIsTheDenseOne(SurfaceField fieldKind) {
    const double d = 0.01;
    const HostParticles particles = splash(d);
    SurfaceOptions options;
    options.field = fieldKind;
    options.spacing = d;
    options.removeSlivers = false;
    const SurfacePlan plan = planSurface(particles, options);
    // Lattices whose sample counts are not multiples of the block edge: partial blocks.
    ASSERT_TRUE(plan.dims[0] % kSurfaceBlockEdge != 0 || plan.dims[1] % kSurfaceBlockEdge != 0 ||
                plan.dims[2] % kSurfaceBlockEdge != 0);

    CpuExec exec;
    const TriangleMesh sparse = extractSurface(exec, particles, plan, "host memory");
    const TriangleMesh dense =
        withSurfaceField(exec, particles, plan, DenseSurfaceBuild{&exec, &plan});
    ASSERT_GT(dense.triangleCount(), 1000u);
    EXPECT_EQ(sparse.positions.size(), dense.positions.size());
    EXPECT_EQ(sparse.triangleCount(), dense.triangleCount());
    EXPECT_TRUE(canonicalTriangles(sparse) == canonicalTriangles(dense))
        << "the sparse lattice's triangles differ from the dense lattice's";
    const MeshMeasures m = measureMesh(sparse);
    EXPECT_TRUE(m.closed());
    EXPECT_EQ(m.components, measureMesh(dense).components);
}

TEST(SparseLattice, IsotropicMeshIsTheDenseLatticeMesh) {
    expectSparseMeshIsTheDenseOne(SurfaceField::Isotropic);
}

TEST(SparseLattice, AnisotropicMeshIsTheDenseLatticeMesh) {
    expectSparseMeshIsTheDenseOne(SurfaceField::Anisotropic);
}

TEST(SparseLattice, MemoryFollowsTheFluidNotItsBox) {
    // Two drops at opposite corners of a metre cube: the dense lattice would hold about 10^7
    // samples, the drops need a few 10^5.
    const double d = 0.01;
    HostParticles drops = latticeBall(Vec3d(0, 0, 0), 0.05, d);
    testing::appendPositions(drops, latticeBall(Vec3d(1, 1, 1), 0.05, d));
    SurfaceOptions options;
    options.spacing = d;
    const SurfacePlan box = planSurface(drops, options);
    ASSERT_GT(box.sampleCount(), 9'000'000);
    options.maxSamples = box.sampleCount() / 10;
    const MeshMeasures m = measureMesh(reconstructSurface(Backend::Cpu, drops, options));
    EXPECT_TRUE(m.closed());
    EXPECT_EQ(m.components, 2u);
    EXPECT_EQ(m.eulerCharacteristic, 4);

    options.maxSamples = 4096;
    try {
        reconstructSurface(Backend::Cpu, drops, options);
        FAIL() << "a lattice over the limit was accepted";
    } catch (const SurfaceError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("limit of 4096"), std::string::npos) << message;
        EXPECT_NE(message.find("cell size of at least"), std::string::npos) << message;
    }
}

TEST(SparseLattice, BlocksNearEveryPointAreFlagged) {
    const LatticeBlocks blocks = LatticeBlocks::of(37, 29, 21);
    EXPECT_EQ(blocks.bx, 5);
    EXPECT_EQ(blocks.by, 4);
    EXPECT_EQ(blocks.bz, 3);
    const Vec3 origin(-1, 2, 0.5);
    const Real cell = Real(0.1), reach = Real(0.35);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-0.5, 4.5);
    std::vector<Vec3> points;
    for (int i = 0; i < 8; ++i) {
        points.push_back(origin + Vec3(Real(u(rng)), Real(u(rng) * 0.8), Real(u(rng) * 0.55)));
    }
    points.push_back(origin + Vec3(100, 0, 0));  // far outside: flags nothing
    points.push_back(origin - Vec3(0, 100, 0));
    std::vector<std::int32_t> flags(static_cast<std::size_t>(blocks.count()), 0);
    for (const Vec3& p : points) {
        flagBlocksNear(p, reach, origin, cell, blocks, flags.data());
    }
    int flagged = 0;
    for (std::int32_t flag : flags) {
        flagged += flag;
    }
    EXPECT_GT(flagged, 0);
    EXPECT_LT(flagged, blocks.count());
    for (int z = 0; z < blocks.nz; ++z) {
        for (int y = 0; y < blocks.ny; ++y) {
            for (int x = 0; x < blocks.nx; ++x) {
                const Vec3 sample = origin + Vec3(Real(x), Real(y), Real(z)) * cell;
                bool near = false;
                for (const Vec3& p : points) {
                    near = near || length(sample - p) < reach;
                }
                if (near) {
                    ASSERT_EQ(flags[std::size_t(blocks.blockOf(x, y, z))], 1)
                        << "sample " << x << " " << y << " " << z;
                }
            }
        }
    }
}

}  // namespace
}  // namespace weir
