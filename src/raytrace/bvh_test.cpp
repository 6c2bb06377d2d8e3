// The triangle hierarchy: the nearest hit it finds is the nearest of all triangles (brute force)
// for random rays through a random mesh, axis-parallel rays included; its leaves hold every
// triangle once and its boxes hold their contents.
#include "raytrace/bvh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace weir {
namespace {

struct RandomMesh {
    std::vector<Vec3f> positions;
    std::vector<std::uint32_t> indices;
};

// n small triangles scattered in the unit cube, some large ones across it, and a few sharing an
// edge (a closed surface's triangles meet so).
RandomMesh randomMesh(std::size_t n, std::mt19937& rng) {
    std::uniform_real_distribution<float> unit(0.0f, 1.0f), small(-0.06f, 0.06f),
        large(-0.4f, 0.4f);
    RandomMesh mesh;
    for (std::size_t t = 0; t < n; ++t) {
        const Vec3f centre(unit(rng), unit(rng), unit(rng));
        auto& spread = t % 50 == 0 ? large : small;
        const auto first = std::uint32_t(mesh.positions.size());
        for (int c = 0; c < 3; ++c) {
            mesh.positions.push_back(centre + Vec3f(spread(rng), spread(rng), spread(rng)));
        }
        mesh.indices.insert(mesh.indices.end(), {first, first + 1, first + 2});
        if (t % 7 == 0) {  // a neighbour across the edge first .. first + 1
            mesh.positions.push_back(centre + Vec3f(small(rng), small(rng), small(rng)));
            mesh.indices.insert(mesh.indices.end(), {first + 1, first, first + 3});
        }
    }
    return mesh;
}

RayHit bruteForce(const RandomMesh& mesh, const Ray& ray) {
    RayHit best;
    best.t = INFINITY;
    for (std::size_t t = 0; t < mesh.indices.size() / 3; ++t) {
        const Vec3f& a = mesh.positions[mesh.indices[3 * t]];
        const BvhTriangle tri{a, mesh.positions[mesh.indices[3 * t + 1]] - a,
                              mesh.positions[mesh.indices[3 * t + 2]] - a};
        float hitT, u, v;
        if (intersectTriangle(tri, ray, 0.0f, best.t, hitT, u, v)) {
            best = {hitT, std::int32_t(t), u, v};
        }
    }
    return best;
}

TEST(Bvh, NearestHitIsTheNearestOfAllTriangles) {
    std::mt19937 rng(19);
    const RandomMesh mesh = randomMesh(3000, rng);
    const Bvh bvh(mesh.positions, mesh.indices);
    ASSERT_GT(bvh.nodes().size(), 100u);
    std::uniform_real_distribution<float> around(-0.5f, 1.5f), normal(-1.0f, 1.0f);
    int hits = 0, misses = 0;
    for (int r = 0; r < 4000; ++r) {
        Ray ray;
        ray.origin = Vec3f(around(rng), around(rng), around(rng));
        Vec3f d(normal(rng), normal(rng), normal(rng));
        if (r % 4 == 0) {  // along an axis: the slab test's 1/0 = inf
            const int axis = r / 4 % 3;
            d = Vec3f();
            d[axis] = r % 8 == 0 ? 1.0f : -1.0f;
        }
        if (!(length(d) > 0.05f)) {
            continue;
        }
        ray.direction = normalized(d);
        const RayHit want = bruteForce(mesh, ray);
        const RayHit got = closestHit(bvh.view(), ray, 0.0f, INFINITY);
        if (want.triangle < 0) {
            EXPECT_LT(got.triangle, 0) << "ray " << r << " hit where no triangle is";
            ++misses;
            continue;
        }
        ++hits;
        ASSERT_GE(got.triangle, 0) << "ray " << r << " missed triangle " << want.triangle;
        EXPECT_FLOAT_EQ(got.t, want.t) << "ray " << r;
        // The same triangle, unless two lie at the same distance (a shared edge).
        if (std::int32_t(bvh.order()[std::size_t(got.triangle)]) != want.triangle) {
            EXPECT_NEAR(got.t, want.t, 1e-6f * want.t) << "ray " << r;
        }
    }
    EXPECT_GT(hits, 1000);
    EXPECT_GT(misses, 100);
}

TEST(Bvh, LeavesHoldEveryTriangleOnceInsideTheirBoxes) {
    std::mt19937 rng(7);
    const RandomMesh mesh = randomMesh(2000, rng);
    const Bvh bvh(mesh.positions, mesh.indices);
    const auto& nodes = bvh.nodes();
    std::vector<int> seen(mesh.indices.size() / 3, 0);
    std::vector<std::int32_t> stack{0};
    while (!stack.empty()) {
        const BvhNode n = nodes[std::size_t(stack.back())];
        stack.pop_back();
        // Within float rounding: a corner is rebuilt as v0 + edge.
        auto inside = [&](const Vec3f& p) {
            for (int a = 0; a < 3; ++a) {
                if (p[a] < n.lo[a] - 1e-6f || p[a] > n.hi[a] + 1e-6f) {
                    return false;
                }
            }
            return true;
        };
        if (n.count > 0) {
            EXPECT_LE(n.count, Bvh::kMaxLeafSize);
            for (std::int32_t k = n.first; k < n.first + n.count; ++k) {
                const BvhTriangle& t = bvh.triangles()[std::size_t(k)];
                EXPECT_TRUE(inside(t.v0) && inside(t.v0 + t.e1) && inside(t.v0 + t.e2));
                ++seen[bvh.order()[std::size_t(k)]];
            }
        } else {
            for (std::int32_t child : {n.first, n.first + 1}) {
                const BvhNode& c = nodes[std::size_t(child)];
                EXPECT_TRUE(inside(c.lo) && inside(c.hi));
                stack.push_back(child);
            }
        }
    }
    for (std::size_t t = 0; t < seen.size(); ++t) {
        ASSERT_EQ(seen[t], 1) << "triangle " << t;
    }
    EXPECT_LE(bvh.depth(), kBvhMaxDepth);
}

TEST(Bvh, EmptyHierarchyHitsNothing) {
    const Bvh bvh({}, {});
    const Ray ray{Vec3f(0, 0, 0), Vec3f(0, 0, 1)};
    EXPECT_LT(closestHit(bvh.view(), ray, 0.0f, INFINITY).triangle, 0);
}

}  // namespace
}  // namespace weir
