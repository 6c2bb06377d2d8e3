// The linear hierarchy's host build (the same WEIR_HD steps the CUDA build runs): Morton codes
// interleave the axes' bits; the nearest hit it finds is the nearest of all triangles (brute
// force) for random rays; every triangle sits in one leaf inside its boxes; its depth fits the
// tracer's stack, even where many triangles share a key point; and the tracer walks it.
#include "raytrace/lbvh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "raytrace/path_tracer.h"
#include "raytrace/raytrace_test_support.h"
#include "raytrace/tracing_scene.h"

namespace weir {
namespace {

using namespace weir::testing;

// n small triangles scattered in a box, some large ones across it, some sharing an edge.
std::vector<BvhTriangle> randomTriangles(std::size_t n, std::mt19937& rng, float sx = 1,
                                         float sy = 1, float sz = 1) {
    std::uniform_real_distribution<float> unit(0.0f, 1.0f), small(-0.03f, 0.03f),
        large(-0.4f, 0.4f);
    std::vector<BvhTriangle> triangles;
    for (std::size_t t = 0; t < n; ++t) {
        const Vec3f centre(unit(rng) * sx, unit(rng) * sy, unit(rng) * sz);
        auto& spread = t % 50 == 0 ? large : small;
        Vec3f p[3];
        for (Vec3f& c : p) {
            c = centre + Vec3f(spread(rng), spread(rng), spread(rng));
        }
        triangles.push_back({p[0], p[1] - p[0], p[2] - p[0]});
        if (t % 7 == 0) {  // a neighbour across the edge p0 .. p1
            const Vec3f q = centre + Vec3f(small(rng), small(rng), small(rng));
            triangles.push_back({p[1], p[0] - p[1], q - p[1]});
        }
    }
    return triangles;
}

RayHit bruteForce(const std::vector<BvhTriangle>& triangles, const Ray& ray) {
    RayHit best;
    best.t = INFINITY;
    for (std::size_t t = 0; t < triangles.size(); ++t) {
        float hitT, u, v;
        if (intersectTriangle(triangles[t], ray, 0.0f, best.t, hitT, u, v)) {
            best = {hitT, std::int32_t(t), u, v};
        }
    }
    return best;
}

// Random rays (a quarter along an axis) against the hierarchy and all triangles.
void expectNearestHits(const HostLbvh& lbvh, const std::vector<BvhTriangle>& triangles,
                       std::mt19937& rng, int rays, int* hitsOut = nullptr) {
    std::uniform_real_distribution<float> around(-0.5f, 1.5f), normal(-1.0f, 1.0f);
    int hits = 0;
    for (int r = 0; r < rays; ++r) {
        Ray ray;
        ray.origin = Vec3f(around(rng), around(rng), around(rng));
        Vec3f d(normal(rng), normal(rng), normal(rng));
        if (r % 4 == 0) {
            d = Vec3f();
            d[r / 4 % 3] = r % 8 == 0 ? 1.0f : -1.0f;
        }
        if (!(length(d) > 0.05f)) {
            continue;
        }
        ray.direction = normalized(d);
        const RayHit want = bruteForce(triangles, ray);
        const RayHit got = closestHit(lbvh.view(), ray, 0.0f, INFINITY);
        if (want.triangle < 0) {
            EXPECT_LT(got.triangle, 0) << "ray " << r << " hit where no triangle is";
            continue;
        }
        ++hits;
        ASSERT_GE(got.triangle, 0) << "ray " << r << " missed triangle " << want.triangle;
        EXPECT_FLOAT_EQ(got.t, want.t) << "ray " << r;
        if (std::int32_t(lbvh.order[std::size_t(got.triangle)]) != want.triangle) {
            EXPECT_NEAR(got.t, want.t, 1e-6f * want.t) << "ray " << r;  // a shared edge
        }
    }
    if (hitsOut != nullptr) {
        *hitsOut = hits;
    }
}

// Every triangle in exactly one leaf, inside every box on its way up; each slot used once.
void expectWellFormed(const HostLbvh& lbvh, std::size_t triangleCount) {
    const auto& nodes = lbvh.nodes;
    ASSERT_EQ(nodes.size(), triangleCount == 0 ? 0 : 2 * triangleCount - 1);
    ASSERT_EQ(lbvh.triangles.size(), triangleCount);
    std::vector<int> seen(triangleCount, 0), visited(nodes.size(), 0);
    std::vector<std::int32_t> stack{0};
    while (!stack.empty() && !nodes.empty()) {
        const std::int32_t index = stack.back();
        stack.pop_back();
        ASSERT_GE(index, 0);
        ASSERT_LT(std::size_t(index), nodes.size());
        ++visited[std::size_t(index)];
        const BvhNode& n = nodes[std::size_t(index)];
        auto inside = [&](const Vec3f& lo, const Vec3f& hi) {
            for (int a = 0; a < 3; ++a) {
                if (lo[a] < n.lo[a] || hi[a] > n.hi[a]) {
                    return false;
                }
            }
            return true;
        };
        if (n.count > 0) {
            ASSERT_EQ(n.count, 1);
            Vec3f lo, hi;
            triangleBox(lbvh.triangles[std::size_t(n.first)], lo, hi);
            EXPECT_TRUE(inside(lo, hi));
            ++seen[lbvh.order[std::size_t(n.first)]];
        } else {
            for (std::int32_t child : {n.first, n.first + 1}) {
                ASSERT_LT(std::size_t(child), nodes.size());
                const BvhNode& c = nodes[std::size_t(child)];
                EXPECT_TRUE(inside(c.lo, c.hi)) << "node " << index << " child " << child;
                stack.push_back(child);
            }
        }
    }
    for (std::size_t t = 0; t < triangleCount; ++t) {
        ASSERT_EQ(seen[t], 1) << "triangle " << t;
    }
    for (std::size_t k = 0; k < visited.size(); ++k) {
        ASSERT_EQ(visited[k], 1) << "node slot " << k;
    }
    EXPECT_LE(lbvh.depth(), kBvhMaxDepth);
}

TEST(Lbvh, MortonCodesInterleaveTheAxes) {
    EXPECT_EQ(spreadBits10(0x3FFu), 0x09249249u);
    EXPECT_EQ(spreadBits10(1u), 1u);
    EXPECT_EQ(spreadBits10(2u), 8u);
    EXPECT_EQ(spreadBits10(0x200u), 1u << 27);
    const Vec3f lo(0, 0, 0), scale = mortonScale(lo, Vec3f(1, 1, 1));
    EXPECT_EQ(scale.x, 1024.0f);
    // x is the highest bit of each triple, then y, then z.
    EXPECT_EQ(mortonCode(Vec3f(0.5f, 0, 0), lo, scale), 1u << 29);
    EXPECT_EQ(mortonCode(Vec3f(0, 0.5f, 0), lo, scale), 1u << 28);
    EXPECT_EQ(mortonCode(Vec3f(0, 0, 0.5f), lo, scale), 1u << 27);
    EXPECT_EQ(mortonCode(Vec3f(1, 1, 1), lo, scale), (1u << 30) - 1);  // the top end: cell 1023
    EXPECT_EQ(mortonCode(Vec3f(-1, 2, 0), lo, scale), mortonCode(Vec3f(0, 1, 0), lo, scale));
    // A flat axis puts every point in its cell 0.
    EXPECT_EQ(mortonScale(lo, Vec3f(1, 0, 1)).y, 0.0f);
}

TEST(Lbvh, NearestHitIsTheNearestOfAllTriangles) {
    std::mt19937 rng(19);
    const std::vector<BvhTriangle> triangles = randomTriangles(3000, rng);
    const HostLbvh lbvh = buildLbvhOnHost(triangles);
    expectWellFormed(lbvh, triangles.size());
    int hits = 0;
    expectNearestHits(lbvh, triangles, rng, 4000, &hits);
    EXPECT_GT(hits, 500);
}

TEST(Lbvh, FlatAndThinSetsAndSmallCounts) {
    std::mt19937 rng(5);
    // A sheet (every key point at one height: a flat axis) and a thin rod.
    for (const auto& scale : {Vec3f(1, 0, 1), Vec3f(1, 0.01f, 0.01f)}) {
        std::vector<BvhTriangle> triangles = randomTriangles(500, rng, scale.x, scale.y, scale.z);
        const HostLbvh lbvh = buildLbvhOnHost(triangles);
        expectWellFormed(lbvh, triangles.size());
        expectNearestHits(lbvh, triangles, rng, 1000);
    }
    for (std::size_t n : {0u, 1u, 2u, 3u, 5u}) {
        std::vector<BvhTriangle> triangles = randomTriangles(n, rng);
        triangles.resize(n);  // without the neighbours it adds
        const HostLbvh lbvh = buildLbvhOnHost(triangles);
        expectWellFormed(lbvh, n);
        expectNearestHits(lbvh, triangles, rng, 200);
    }
}

TEST(Lbvh, TrianglesSharingOneKeyPointMakeABalancedSubtree) {
    // 4096 copies of one triangle: one Morton code, told apart by their index alone.
    const BvhTriangle one{Vec3f(0.2f, 0.3f, 0.4f), Vec3f(0.1f, 0, 0), Vec3f(0, 0.1f, 0.05f)};
    const std::vector<BvhTriangle> triangles(4096, one);
    const HostLbvh lbvh = buildLbvhOnHost(triangles);
    expectWellFormed(lbvh, triangles.size());
    EXPECT_EQ(lbvh.depth(), 12);  // log2(4096)
}

// The tracer walks the linear hierarchy as it walks the offline one: the same pixels (up to a tie
// between triangles at one distance), and paths added frame by frame (firstSample) make the
// image of all of them at once.
TEST(Lbvh, TracerSeesTheOfflineSceneThroughIt) {
    const TriangleMesh ball = waterBall(Vec3f(0.5f, 0.35f, 0.5f), 0.25f, 24, 12);
    TracingSceneDescription description;
    description.water = &ball;
    description.container = {{0, 0, 0}, {1, 1, 1}};
    description.obstacleBoxes = {{{0.3, 0, 0.3}, {0.7, 0.1, 0.7}}};
    description.cameraEye = Vec3d(0.5, 1.4, 2.2);
    const TracingScene scene(description);
    const HostLbvh lbvh = buildLbvhOnHost(scene.bvh().triangles());
    std::vector<TriangleShading> shading(lbvh.order.size());
    for (std::size_t k = 0; k < shading.size(); ++k) {
        shading[k] = scene.shading()[lbvh.order[k]];
    }
    TracingSceneView linear = scene.view();
    linear.bvh = lbvh.view();
    linear.shading = shading.data();

    PinholeCamera camera;
    camera.eye = Vec3f(description.cameraEye);
    camera.forward = normalized(Vec3f(0.5f, 0.35f, 0.5f) - camera.eye);
    camera.right = normalized(cross(camera.forward, Vec3f(0, 1, 0)));
    camera.up = cross(camera.right, camera.forward);
    const int width = 40, height = 30;
    camera.aspect = float(width) / float(height);
    const WaterLook look;
    int same = 0, progressive = 0;
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const Vec3f offline = tracePixel(scene.view(), look, camera, width, height, x, y, 4);
            const Vec3f live = tracePixel(linear, look, camera, width, height, x, y, 4);
            same += length(offline - live) <= 1e-5f * (1.0f + length(offline));
            const Vec3f firstTwo = tracePixel(linear, look, camera, width, height, x, y, 2, 0);
            const Vec3f lastTwo = tracePixel(linear, look, camera, width, height, x, y, 2, 2);
            progressive +=
                length((firstTwo + lastTwo) * 0.5f - live) <= 1e-5f * (1.0f + length(live));
        }
    }
    EXPECT_GT(same, width * height * 98 / 100);
    EXPECT_EQ(progressive, width * height);
}

}  // namespace
}  // namespace weir
