#include "scene/mesh_solid.h"

#include <gtest/gtest.h>

#include <cmath>

namespace weir {
namespace {

struct TriangleMesh {
    std::vector<Vec3d> vertices;
    std::vector<std::array<int, 3>> triangles;
};

// The box [0, size] as 12 outward-facing triangles, each vertex mapped by place().
template <class Place>
TriangleMesh boxMesh(const Vec3d& size, Place place) {
    TriangleMesh m;
    for (int c = 0; c < 8; ++c) {
        m.vertices.push_back(
            place(Vec3d((c & 1) ? size.x : 0, (c & 2) ? size.y : 0, (c & 4) ? size.z : 0)));
    }
    const int quads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                             {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    for (const auto& q : quads) {
        m.triangles.push_back({q[0], q[1], q[2]});
        m.triangles.push_back({q[0], q[2], q[3]});
    }
    return m;
}

TEST(MeshSolid, BoxVolumeCentroidAndInertiaAreTheBoxs) {
    const Vec3d size(2, 1, 3), at(10, -4, 7);
    const TriangleMesh box = boxMesh(size, [&](const Vec3d& p) { return p + at; });
    const MeshSolid solid = meshSolidOf(box.vertices, box.triangles);
    EXPECT_NEAR(solid.volume, 6.0, 1e-12);
    EXPECT_NEAR(solid.centroid.x, 11.0, 1e-12);
    EXPECT_NEAR(solid.centroid.y, -3.5, 1e-12);
    EXPECT_NEAR(solid.centroid.z, 8.5, 1e-12);
    const double m = 12;
    const auto inertia = inertiaTensorOf(solid, m);
    EXPECT_NEAR(inertia[0], m / 12 * (1 + 9), 1e-10);
    EXPECT_NEAR(inertia[4], m / 12 * (4 + 9), 1e-10);
    EXPECT_NEAR(inertia[8], m / 12 * (4 + 1), 1e-10);
    for (int off : {1, 2, 3, 5, 6, 7}) {
        EXPECT_NEAR(inertia[std::size_t(off)], 0, 1e-10);
    }
    EXPECT_EQ(unmatchedEdgesOf(box.vertices, box.triangles), 0u);
}

TEST(MeshSolid, TetrahedronVolumeAndCentroid) {
    const std::vector<Vec3d> v = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    const std::vector<std::array<int, 3>> t = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    const MeshSolid solid = meshSolidOf(v, t);
    EXPECT_NEAR(solid.volume, 1.0 / 6, 1e-15);
    for (int a = 0; a < 3; ++a) {
        EXPECT_NEAR(solid.centroid[a], 0.25, 1e-15);
    }
    // About the origin, integral of x^2 over this tetrahedron is 1/60 (so per unit volume 1/10),
    // of x y 1/120; the centroid's share taken off.
    EXPECT_NEAR(solid.secondMoment[0], 0.1 - 0.0625, 1e-14);
    EXPECT_NEAR(solid.secondMoment[1], 0.05 - 0.0625, 1e-14);
    EXPECT_EQ(unmatchedEdgesOf(v, t), 0u);
}

TEST(MeshSolid, InwardFacingOpenAndUnsharedSurfacesAreTold) {
    TriangleMesh box = boxMesh(Vec3d(1, 1, 1), [](const Vec3d& p) { return p; });
    TriangleMesh flipped = box;
    for (auto& t : flipped.triangles) {
        std::swap(t[1], t[2]);
    }
    EXPECT_NEAR(meshSolidOf(flipped.vertices, flipped.triangles).volume, -1.0, 1e-12);
    EXPECT_EQ(unmatchedEdgesOf(flipped.vertices, flipped.triangles), 0u);

    TriangleMesh open = box;
    open.triangles.pop_back();  // a hole: three edges now join one triangle only
    EXPECT_EQ(unmatchedEdgesOf(open.vertices, open.triangles), 3u);

    TriangleMesh oneFlipped = box;
    std::swap(oneFlipped.triangles[0][1], oneFlipped.triangles[0][2]);
    EXPECT_EQ(unmatchedEdgesOf(oneFlipped.vertices, oneFlipped.triangles), 3u);

    // As an STL stores it: every triangle with corners of its own, at the same coordinates.
    TriangleMesh unshared;
    for (const auto& t : box.triangles) {
        const int first = int(unshared.vertices.size());
        for (int k = 0; k < 3; ++k) {
            unshared.vertices.push_back(box.vertices[std::size_t(t[k])]);
        }
        unshared.triangles.push_back({first, first + 1, first + 2});
    }
    EXPECT_EQ(unmatchedEdgesOf(unshared.vertices, unshared.triangles), 0u);
    EXPECT_NEAR(meshSolidOf(unshared.vertices, unshared.triangles).volume, 1.0, 1e-12);
}

TEST(MeshSolid, PrincipalAxesOfATurnedBoxAreItsEdges) {
    // A 4 x 2 x 1 box turned by 30 degrees about z and then 50 about x.
    const double a = 30 * M_PI / 180, b = 50 * M_PI / 180;
    auto turn = [&](const Vec3d& p) {
        const Vec3d z(std::cos(a) * p.x - std::sin(a) * p.y, std::sin(a) * p.x + std::cos(a) * p.y,
                      p.z);
        return Vec3d(z.x, std::cos(b) * z.y - std::sin(b) * z.z,
                     std::sin(b) * z.y + std::cos(b) * z.z);
    };
    const Vec3d size(4, 2, 1);
    const TriangleMesh box = boxMesh(size, turn);
    const MeshSolid solid = meshSolidOf(box.vertices, box.triangles);
    const double m = 3;
    const PrincipalAxes axes = principalAxesOf(inertiaTensorOf(solid, m));
    const Vec3d edges[3] = {turn(Vec3d(1, 0, 0)), turn(Vec3d(0, 1, 0)), turn(Vec3d(0, 0, 1))};
    const double moments[3] = {m / 12 * (4 + 1), m / 12 * (16 + 1), m / 12 * (16 + 4)};
    EXPECT_NEAR(dot(cross(axes.axes[0], axes.axes[1]), axes.axes[2]), 1.0, 1e-12);
    for (int k = 0; k < 3; ++k) {
        // Each principal axis is one of the box's edges, with that edge's moment.
        int match = -1;
        for (int e = 0; e < 3; ++e) {
            if (std::abs(dot(axes.axes[std::size_t(k)], edges[e])) > 1 - 1e-9) {
                match = e;
            }
        }
        ASSERT_GE(match, 0) << "axis " << k;
        EXPECT_NEAR(axes.values[k], moments[match], 1e-9) << "axis " << k;
    }
}

}  // namespace
}  // namespace weir
