// The tracing scene's build: every surface as triangles with normals, then one hierarchy.
#include "raytrace/tracing_scene.h"

#include <algorithm>
#include <cmath>

#include "raytrace/surface_triangles.h"
#include "scene/shape_tessellation.h"

namespace weir {

namespace {

// Triangles gathered before the hierarchy is built over them.
struct TriangleSoup {
    std::vector<Vec3f> positions;
    std::vector<std::uint32_t> indices;
    std::vector<TriangleShading> shading;

    void add(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& na, const Vec3d& nb,
             const Vec3d& nc, TriangleKind kind) {
        const auto first = std::uint32_t(positions.size());
        for (const Vec3d* p : {&a, &b, &c}) {
            positions.push_back(Vec3f(*p));
        }
        indices.insert(indices.end(), {first, first + 1, first + 2});
        shading.push_back({Vec3f(na), Vec3f(nb), Vec3f(nc), kind});
    }
    // A flat triangle: its face normal at every corner (degenerate ones are left out).
    void addFlat(const Vec3d& a, const Vec3d& b, const Vec3d& c, TriangleKind kind) {
        const Vec3d n = cross(b - a, c - a);
        const double area = length(n);
        if (area > 0) {
            add(a, b, c, n / area, n / area, n / area, kind);
        }
    }
};

// A shape's triangles in its own frame, then placed by a map (identity for static obstacles).
template <class Place, class Turn>
void addBox(TriangleSoup& soup, const Box& box, TriangleKind kind, Place place, Turn) {
    for (int axis = 0; axis < 3; ++axis) {
        for (int side = 0; side < 2; ++side) {
            Vec3d corner[4];
            boxFaceCorners(box, axis, side, corner);
            // Counter-clockwise seen from outside: the face normal points out.
            const int order[2][6] = {{0, 3, 2, 0, 2, 1}, {0, 1, 2, 0, 2, 3}};
            for (int t = 0; t < 2; ++t) {
                const int* k = order[side] + 3 * t;
                soup.addFlat(place(corner[k[0]]), place(corner[k[1]]), place(corner[k[2]]), kind);
            }
        }
    }
}

template <class Place, class Turn>
void addSphere(TriangleSoup& soup, const SphereShape& sphere, TriangleKind kind, Place place,
               Turn turn) {
    constexpr int kSlices = 64, kStacks = 32;
    auto unit = [&](int i, int j) { return sphereLatticeNormal(i, j, kSlices, kStacks); };
    for (int j = 0; j < kStacks; ++j) {
        for (int i = 0; i < kSlices; ++i) {
            const Vec3d n[4] = {unit(i, j), unit(i + 1, j), unit(i + 1, j + 1), unit(i, j + 1)};
            for (int t = 0; t < 2; ++t) {
                const int k[3] = {0, t == 0 ? 1 : 2, t == 0 ? 2 : 3};
                const Vec3d p0 = sphere.center + n[k[0]] * sphere.radius,
                            p1 = sphere.center + n[k[1]] * sphere.radius,
                            p2 = sphere.center + n[k[2]] * sphere.radius;
                if (length(cross(p1 - p0, p2 - p0)) > 0) {
                    soup.add(place(p0), place(p1), place(p2), turn(n[k[0]]), turn(n[k[1]]),
                             turn(n[k[2]]), kind);
                }
            }
        }
    }
}

template <class Place, class Turn>
void addMesh(TriangleSoup& soup, const MeshObstacle& mesh, const Vec3d& shift, TriangleKind kind,
             Place place, Turn) {
    for (const auto& t : mesh.triangles) {
        soup.addFlat(place(mesh.vertices[std::size_t(t[0])] - shift),
                     place(mesh.vertices[std::size_t(t[1])] - shift),
                     place(mesh.vertices[std::size_t(t[2])] - shift), kind);
    }
}

}  // namespace

std::uint32_t wallsSeenFrom(const Box& container, const Vec3d& eye) {
    std::uint32_t walls = 0;
    for (int axis : {0, 2}) {
        if (eye[axis] > container.min[axis]) {
            walls |= wallBit(axis, 0);
        }
        if (eye[axis] < container.max[axis]) {
            walls |= wallBit(axis, 1);
        }
    }
    return walls;
}

TracingScene::TracingScene(const TracingSceneDescription& d) {
    const Box& box = d.container;
    view_.containerLo = Vec3f(box.min);
    view_.containerHi = Vec3f(box.max);
    view_.walls = wallsSeenFrom(box, d.cameraEye);
    const double size = length(box.max - box.min);
    view_.rayEpsilon = float(std::max(1e-6, 2e-5 * size));

    TriangleSoup soup;
    if (d.water != nullptr) {
        const TriangleMesh& mesh = *d.water;
        const bool smooth = mesh.normals.size() == mesh.positions.size();
        for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
            Vec3f corners[3], normals[3];
            for (int c = 0; c < 3; ++c) {
                const std::uint32_t v = mesh.indices[3 * t + std::size_t(c)];
                corners[c] = mesh.positions[v];
                normals[c] = smooth ? mesh.normals[v] : Vec3f();
            }
            Vec3f faceNormal;
            if (!faceNormalOf(corners, faceNormal)) {
                continue;
            }
            bool onContainer = false;
            if (d.contactDistance > 0) {
                onContainer =
                    faceLiesOnPlane(corners, faceNormal, 1, box.min.y, -1, d.contactDistance);
                for (int axis : {0, 2}) {
                    for (int side = 0; side < 2 && !onContainer; ++side) {
                        onContainer = (view_.walls & wallBit(axis, side)) != 0 &&
                                      faceLiesOnPlane(corners, faceNormal, axis,
                                                      side ? box.max[axis] : box.min[axis],
                                                      side ? 1 : -1, d.contactDistance);
                    }
                }
            }
            if (onContainer) {
                ++contactTrianglesLeftOut_;
                continue;
            }
            for (Vec3f& n : normals) {
                const float l = length(n);
                n = l > 0 ? n / l : faceNormal;
            }
            soup.add(Vec3d(corners[0]), Vec3d(corners[1]), Vec3d(corners[2]), Vec3d(normals[0]),
                     Vec3d(normals[1]), Vec3d(normals[2]), TriangleKind::Water);
            ++waterTriangles_;
        }
    }

    const auto same = [](const Vec3d& p) { return p; };
    for (const Box& b : d.obstacleBoxes) {
        addBox(soup, b, TriangleKind::Obstacle, same, same);
    }
    for (const SphereShape& s : d.obstacleSpheres) {
        addSphere(soup, s, TriangleKind::Obstacle, same, same);
    }
    for (const MeshObstacle& m : d.obstacleMeshes) {
        addMesh(soup, m, Vec3d(), TriangleKind::Obstacle, same, same);
    }
    // A rigid body: its shape about its centre of mass, turned by the pose's quaternion (the
    // body's frame to the world) and moved to the pose's position.
    for (std::size_t i = 0; i < std::min(d.bodies.size(), d.bodyPoses.size()); ++i) {
        const BodySpec& body = d.bodies[i];
        const BodyPose& pose = d.bodyPoses[i];
        const double* q = pose.orientation;
        const Vec3d u(q[0], q[1], q[2]);
        const auto turn = [u, w = q[3]](const Vec3d& v) {
            const Vec3d t = cross(u, v) * 2.0;
            return v + t * w + cross(u, t);
        };
        const auto place = [&](const Vec3d& p) { return turn(p) + pose.position; };
        if (body.isMesh) {
            addMesh(soup, body.mesh, body.centre(), TriangleKind::Body, place, turn);
        } else if (body.isSphere) {
            addSphere(soup, {Vec3d(), body.sphere.radius}, TriangleKind::Body, place, turn);
        } else {
            const Vec3d half = (body.box.max - body.box.min) * 0.5;
            addBox(soup, {half * -1.0, half}, TriangleKind::Body, place, turn);
        }
    }

    // Spray, foam and bubbles: octahedra, cheap and without a facing direction. Foam is drawn
    // largest, so that it pokes through the surface it floats on (the surface lies about half a
    // spacing outside the outermost particles' centres).
    if (d.whitewater != nullptr && d.whitewaterSize > 0) {
        const DiffuseParticles& w = *d.whitewater;
        const Vec3d axes[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
        for (std::size_t k = 0; k < w.size(); ++k) {
            const double scale = w.kindOf(k) == DiffuseKind::Foam    ? 1.0
                                 : w.kindOf(k) == DiffuseKind::Spray ? 0.7
                                                                     : 0.5;
            const double r = d.whitewaterSize * scale;
            const Vec3d c(w.x[k], w.y[k], w.z[k]);
            for (int octant = 0; octant < 8; ++octant) {
                const Vec3d a = axes[0] * ((octant & 1) ? r : -r);
                const Vec3d b = axes[1] * ((octant & 2) ? r : -r);
                const Vec3d e = axes[2] * ((octant & 4) ? r : -r);
                // Wound counter-clockwise seen from outside in every octant.
                const bool flip = ((octant & 1) != 0) ^ ((octant & 2) != 0) ^ ((octant & 4) != 0);
                if (flip) {
                    soup.addFlat(c + a, c + b, c + e, TriangleKind::Whitewater);
                } else {
                    soup.addFlat(c + a, c + e, c + b, TriangleKind::Whitewater);
                }
            }
        }
    }

    bvh_ = Bvh(soup.positions, soup.indices);
    shading_.resize(soup.shading.size());
    for (std::size_t k = 0; k < shading_.size(); ++k) {
        shading_[k] = soup.shading[bvh_.order()[k]];
    }
}

TracingSceneView TracingScene::view() const {
    TracingSceneView v = view_;
    v.bvh = bvh_.view();
    v.shading = shading_.data();
    return v;
}

}  // namespace weir
