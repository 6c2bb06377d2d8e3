// The live look's surface triangles (surface_triangles.h, run per thread on the GPU) are the
// offline scene's water triangles: the same faces kept (those on the floor and the walls that are
// there left out), the same corners and edges, the same unit vertex normals.
#include "raytrace/surface_triangles.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <vector>

#include "raytrace/interactive_water.h"
#include "surface/surface.h"
#include "surface/surface_test_support.h"

namespace weir {
namespace {

using TriangleBits = std::array<std::uint32_t, 18>;  // corner, edges, three normals

TriangleBits bitsOf(const BvhTriangle& t, const TriangleShading& s) {
    const Vec3f parts[6] = {t.v0, t.e1, t.e2, s.n0, s.n1, s.n2};
    TriangleBits bits;
    std::memcpy(bits.data(), parts, sizeof parts);
    return bits;
}

TEST(SurfaceTriangles, KeptFacesAreTheOfflineScenesWaterTriangles) {
    // A ball resting on the floor and a slab against two walls: faces on the floor and walls.
    const double d = 0.02;
    HostParticles particles = testing::latticeBall(Vec3d(0.5, 0.2, 0.5), 0.19, d);
    const int counts[3] = {20, 5, 10};
    testing::appendPositions(particles, testing::latticeBox(Vec3d(0, 0, 0), counts, d));
    SurfaceOptions options;
    options.spacing = d;
    const TriangleMesh mesh = reconstructSurface(Backend::Cpu, particles, options);

    TracingSceneDescription description;
    description.water = &mesh;
    description.container = {{0, 0, 0}, {1, 1, 1}};
    description.cameraEye = Vec3d(0.5, 1.4, 2.2);
    description.contactDistance = d;
    const TracingScene scene(description);
    ASSERT_GT(scene.contactTrianglesLeftOut(), 100u);

    const SurfaceMeshView view{mesh.positions.data(), mesh.normals.data(), mesh.indices.data()};
    const ContactRule rule{description.container.min, description.container.max,
                           wallsSeenFrom(description.container, description.cameraEye),
                           description.contactDistance};
    EXPECT_EQ(rule.walls, scene.view().walls);
    std::vector<TriangleBits> live, offline;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        BvhTriangle triangle;
        TriangleShading shading;
        if (keptSurfaceTriangle(view, std::int64_t(t), rule, triangle, shading)) {
            live.push_back(bitsOf(triangle, shading));
        }
    }
    for (std::size_t k = 0; k < scene.shading().size(); ++k) {
        if (scene.shading()[k].kind == TriangleKind::Water) {
            offline.push_back(bitsOf(scene.bvh().triangles()[k], scene.shading()[k]));
        }
    }
    EXPECT_EQ(live.size(), scene.waterTriangles());
    std::sort(live.begin(), live.end());
    std::sort(offline.begin(), offline.end());
    EXPECT_TRUE(live == offline) << "the kept triangles differ from the offline scene's";
}

TEST(SurfaceTriangles, FacesWithCoincidentCornersAreDegenerateWhateverTheRounding) {
    // Two corners at one point: the cross product is 0 here, but a GPU's fused multiply-adds
    // leave a residue of about 1e-8 of an edge squared; that residue must not keep the face.
    const Vec3f a(0.1f, 0.2f, 0.3f), b(0.7f, 0.25f, 0.35f);
    Vec3f normal;
    const Vec3f coincident[3] = {a, b, b};
    EXPECT_FALSE(faceNormalOf(coincident, normal));
    const Vec3f nudged[3] = {a, b, b + Vec3f(0, 1e-8f, 0)};  // a residue-sized sliver
    EXPECT_FALSE(faceNormalOf(nudged, normal));
    const Vec3f thin[3] = {a, b, b + Vec3f(0, 1e-3f, 0)};  // thin but real: kept
    ASSERT_TRUE(faceNormalOf(thin, normal));
    EXPECT_NEAR(length(normal), 1.0f, 1e-6f);
    EXPECT_NEAR(dot(normal, b - a), 0.0f, 1e-6f);
}

}  // namespace
}  // namespace weir
