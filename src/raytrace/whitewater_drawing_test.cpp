// The water look's spray, foam and bubbles: a closed octahedron per diffuse particle, wound
// outwards, foam the largest and bubbles the smallest; and a ray that meets one sees a white
// matte surface.
#include <gtest/gtest.h>

#include <cmath>

#include "raytrace/path_tracer.h"
#include "raytrace/tracing_scene.h"

namespace weir {
namespace {

TEST(WhitewaterDrawing, EachDiffuseParticleIsAClosedOutwardOctahedronSizedByKind) {
    DiffuseParticles whitewater;
    whitewater.push(0.2f, 0.5f, 0.5f, 0, 0, 0, DiffuseKind::Spray, 1);
    whitewater.push(0.5f, 0.5f, 0.5f, 0, 0, 0, DiffuseKind::Foam, 1);
    whitewater.push(0.8f, 0.5f, 0.5f, 0, 0, 0, DiffuseKind::Bubble, 1);
    TracingSceneDescription description;
    description.container = {{0, 0, 0}, {1, 1, 1}};
    description.cameraEye = Vec3d(0.5, 0.5, 3);
    description.whitewater = &whitewater;
    description.whitewaterSize = 0.01;
    const TracingScene scene(description);
    ASSERT_EQ(scene.shading().size(), 24u);
    const double expectedReach[3] = {0.007, 0.01, 0.005};  // spray, foam, bubbles
    double area[3] = {0, 0, 0};
    for (std::size_t k = 0; k < scene.shading().size(); ++k) {
        EXPECT_EQ(scene.shading()[k].kind, TriangleKind::Whitewater);
        const BvhTriangle& t = scene.bvh().triangles()[k];
        const Vec3f centroid = t.v0 + (t.e1 + t.e2) * (1.0f / 3.0f);
        const int which = centroid.x < 0.35f ? 0 : centroid.x < 0.65f ? 1 : 2;
        const Vec3f centre = Vec3f(whitewater.x[std::size_t(which)], 0.5f, 0.5f);
        const Vec3f n = cross(t.e1, t.e2);
        EXPECT_GT(dot(n, centroid - centre), 0.0f) << "triangle " << k << " faces inwards";
        for (const Vec3f& corner : {t.v0, t.v0 + t.e1, t.v0 + t.e2}) {
            EXPECT_NEAR(length(corner - centre), expectedReach[which], 1e-6);
        }
        area[which] += 0.5 * double(length(n));
    }
    // Closed: 8 faces of an octahedron of reach r have the area 4 sqrt(3) r^2.
    for (int kind = 0; kind < 3; ++kind) {
        EXPECT_NEAR(area[kind], 4 * std::sqrt(3.0) * expectedReach[kind] * expectedReach[kind],
                    1e-3 * area[kind]);
    }

    // A ray straight at the foam (just off its tip) meets a white matte surface: the face
    // |dx| + |dy| + |dz| = r.
    const WaterLook look;
    const SurfaceHit hit =
        nearestSurface(scene.view(), look, Ray{Vec3f(0.501f, 0.5003f, 2.0f), Vec3f(0, 0, -1)});
    EXPECT_EQ(hit.type, SurfaceType::Matte);
    EXPECT_NEAR(hit.t, 2.0f - (0.5f + 0.01f - 0.0013f), 1e-5f);
    EXPECT_GT(hit.albedo.x, 0.85f);
    EXPECT_GT(hit.albedo.z, 0.85f);
}

}  // namespace
}  // namespace weir
