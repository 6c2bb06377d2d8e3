// Boundary sampling, Akinci volumes and the static boundary grid.
#include "scene/boundary.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <unordered_map>

#include "physics/kernels.h"

namespace weir {
namespace {

Vec3d cross(const Vec3d& a, const Vec3d& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
Vec3d normalize(const Vec3d& v) { return v / length(v); }

// Collects points with their container face (-1: an obstacle), dropping any closer than
// minDistance to one already kept (spatial hash).
class PointSet {
   public:
    explicit PointSet(double minDistance) : min_(minDistance), cell_(minDistance) {}

    void add(const Vec3d& p, int face = -1) {
        const long cx = cellOf(p.x), cy = cellOf(p.y), cz = cellOf(p.z);
        for (long dx = -1; dx <= 1; ++dx) {
            for (long dy = -1; dy <= 1; ++dy) {
                for (long dz = -1; dz <= 1; ++dz) {
                    auto it = cells_.find(key(cx + dx, cy + dy, cz + dz));
                    if (it == cells_.end()) {
                        continue;
                    }
                    for (std::size_t k : it->second) {
                        if (lengthSquared(samples_.points[k] - p) < min_ * min_) {
                            return;
                        }
                    }
                }
            }
        }
        cells_[key(cx, cy, cz)].push_back(samples_.points.size());
        samples_.points.push_back(p);
        samples_.faces.push_back(face);
    }
    BoundarySamples take() { return std::move(samples_); }

   private:
    long cellOf(double v) const { return long(std::floor(v / cell_)); }
    static std::uint64_t key(long x, long y, long z) {
        return (std::uint64_t(x & 0x1FFFFF) << 42) | (std::uint64_t(y & 0x1FFFFF) << 21) |
               std::uint64_t(z & 0x1FFFFF);
    }
    double min_, cell_;
    BoundarySamples samples_;
    std::unordered_map<std::uint64_t, std::vector<std::size_t>> cells_;
};

// The surface of box [lo, hi] on a lattice of spacing close to d (each axis divided evenly); for
// the container (`container`) each point names its first face, 0..5 as -x, +x, -y, +y, -z, +z.
void sampleBoxSurface(const Vec3d& lo, const Vec3d& hi, double d, bool container, PointSet& out) {
    long n[3];
    double step[3];
    for (int a = 0; a < 3; ++a) {
        const double size = hi[a] - lo[a];
        n[a] = std::max(1L, long(std::lround(size / d)));
        step[a] = size / double(n[a]);
    }
    for (long k = 0; k <= n[2]; ++k) {
        for (long j = 0; j <= n[1]; ++j) {
            const bool faceYZ = k == 0 || k == n[2] || j == 0 || j == n[1];
            for (long i = 0; i <= n[0]; ++i) {
                if (faceYZ || i == 0 || i == n[0]) {
                    const long at[3] = {i, j, k};
                    int face = -1;
                    for (int a = 0; a < 3 && container && face < 0; ++a) {
                        if (at[a] == 0 || at[a] == n[a]) {
                            face = 2 * a + (at[a] == 0 ? 0 : 1);
                        }
                    }
                    out.add({lo.x + double(i) * step[0], lo.y + double(j) * step[1],
                             lo.z + double(k) * step[2]},
                            face);
                } else {
                    i = n[0] - 1;  // skip the interior of this row
                }
            }
        }
    }
}

// A sphere by the Fibonacci lattice: near-uniform points, one per d^2 of area.
void sampleSphereSurface(const Vec3d& centre, double radius, double d, PointSet& out) {
    const long count = std::max(1L, long(std::lround(4 * kPi * radius * radius / (d * d))));
    const double golden = kPi * (3.0 - std::sqrt(5.0));
    for (long k = 0; k < count; ++k) {
        const double y = 1.0 - 2.0 * (double(k) + 0.5) / double(count);
        const double ring = std::sqrt(std::max(0.0, 1.0 - y * y));
        const double phi = golden * double(k);
        out.add(centre + Vec3d(ring * std::cos(phi), y, ring * std::sin(phi)) * radius);
    }
}

// A triangle on a barycentric lattice with edges cut into pieces no longer than d, moved by
// `offset` along its unit normal (negative: into the solid).
void sampleTriangle(const Vec3d& a, const Vec3d& b, const Vec3d& c, double d, double offset,
                    PointSet& out) {
    const Vec3d e1 = b - a, e2 = c - a;
    Vec3d normal = cross(e1, e2);
    const double area2 = length(normal);
    if (area2 <= 0) {
        return;
    }
    normal = normal / area2;
    const double longest = std::max({length(e1), length(e2), length(c - b)});
    const long n = std::max(1L, long(std::ceil(longest / d)));
    for (long i = 0; i <= n; ++i) {
        for (long j = 0; i + j <= n; ++j) {
            out.add(a + e1 * (double(i) / double(n)) + e2 * (double(j) / double(n)) +
                    normal * offset);
        }
    }
}

}  // namespace

bool insideMesh(const MeshObstacle& mesh, const Vec3d& p) {
    // Parity of crossings of the ray p + t (1, e, e^2), t > 0, slightly tilted off the axes so
    // that it does not run along edges of axis-aligned meshes.
    const Vec3d dir = normalize(Vec3d(1.0, 1.3e-4, 2.9e-5));
    int crossings = 0;
    for (const auto& t : mesh.triangles) {
        const Vec3d &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &c = mesh.vertices[t[2]];
        // Moller-Trumbore.
        const Vec3d e1 = b - a, e2 = c - a, q = cross(dir, e2);
        const double det = dot(e1, q);
        if (std::fabs(det) < 1e-300) {
            continue;
        }
        const double inv = 1.0 / det;
        const Vec3d s = p - a;
        const double u = dot(s, q) * inv;
        if (u < 0 || u > 1) {
            continue;
        }
        const Vec3d r = cross(s, e1);
        const double v = dot(dir, r) * inv;
        if (v < 0 || u + v > 1) {
            continue;
        }
        if (dot(e2, r) * inv > 0) {
            ++crossings;
        }
    }
    return (crossings & 1) != 0;
}

int boundaryLayers(double h, double d, bool fullSupport) {
    const int reach = int(std::ceil(h / d - 1e-9));
    return std::max(1, fullSupport ? reach : reach - 1);
}

std::vector<Vec3d> sampleBoundary(const Scene& scene, double d, double h) {
    return sampleBoundary(scene, d, h, boundaryLayers(h, d)).points;
}

BoundarySamples sampleBoundary(const Scene& scene, double d, double, int layers) {
    PointSet points(0.5 * d);
    for (int layer = 0; layer < layers; ++layer) {
        const double depth = (layer + 0.5) * d;  // behind the surface
        const Vec3d out(depth, depth, depth);
        sampleBoxSurface(scene.container.min - out, scene.container.max + out, d, true, points);
        for (const Box& box : scene.obstacleBoxes) {
            Vec3d inset = out;
            for (int a = 0; a < 3; ++a) {
                inset[a] = std::min(inset[a], 0.5 * (box.max[a] - box.min[a]));
            }
            sampleBoxSurface(box.min + inset, box.max - inset, d, false, points);
        }
        for (const SphereShape& s : scene.obstacleSpheres) {
            if (s.radius - depth > 0.25 * d || layer == 0) {
                sampleSphereSurface(s.center, std::max(s.radius - depth, 0.25 * s.radius), d,
                                    points);
            }
        }
        for (const MeshObstacle& mesh : scene.obstacleMeshes) {
            for (const auto& t : mesh.triangles) {
                sampleTriangle(mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]], d,
                               -depth, points);
            }
        }
    }
    return points.take();
}

BoundaryParticles buildBoundary(const std::vector<Vec3d>& points, const Box& container, double h,
                                double restDensity, double fullVolume) {
    BoundarySamples samples;
    samples.points = points;
    samples.faces.assign(points.size(), -1);
    return buildBoundary(samples, container, h, restDensity, fullVolume, BoundaryKernel::Poly6);
}

BoundaryParticles buildBoundary(const BoundarySamples& samples, const Box& container, double h,
                                double restDensity, double fullVolume, BoundaryKernel kernel,
                                const std::array<Vec3d, 6>* faceVelocity) {
    const std::vector<Vec3d>& points = samples.points;
    BoundaryParticles out;
    const Vec3d lo = container.min - Vec3d(h, h, h);
    int dims[3];
    for (int a = 0; a < 3; ++a) {
        dims[a] = std::max(1, int(std::ceil((container.max[a] - container.min[a] + 2 * h) / h)));
        out.dims[a] = dims[a];
    }
    out.origin = Vec3(lo);
    out.cellSize = Real(h);
    const std::size_t cells = std::size_t(dims[0]) * dims[1] * dims[2];
    auto cellOf = [&](const Vec3d& p) {
        int c[3];
        for (int a = 0; a < 3; ++a) {
            c[a] = std::clamp(int(std::floor((p[a] - lo[a]) / h)), 0, dims[a] - 1);
        }
        return (std::size_t(c[1]) * dims[2] + c[2]) * dims[0] + c[0];
    };
    std::vector<std::size_t> order(points.size()), cellIds(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
        cellIds[i] = cellOf(points[i]);
    }
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return cellIds[a] < cellIds[b]; });
    out.cellStart.assign(cells + 1, 0);
    for (std::size_t i = 0; i < points.size(); ++i) {
        ++out.cellStart[cellIds[i] + 1];
    }
    for (std::size_t c = 0; c < cells; ++c) {
        out.cellStart[c + 1] += out.cellStart[c];
    }
    // psi = rho0 / sum_k W_bk, over the boundary neighbours within h (itself included).
    const double poly6 = 315.0 / (64.0 * kPi * h * h * h);
    const WendlandKernel wendland = WendlandKernel::forRadius(h);
    std::vector<Vec3d> sorted(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
        sorted[i] = points[order[i]];
    }
    out.pos.resize(points.size());
    out.velocity.resize(faceVelocity != nullptr ? points.size() : 0);
    out.near.assign(cells, 0);
    for (std::size_t i = 0; i < sorted.size(); ++i) {
        const Vec3d& p = sorted[i];
        int c[3];
        for (int a = 0; a < 3; ++a) {
            c[a] = std::clamp(int(std::floor((p[a] - lo[a]) / h)), 0, dims[a] - 1);
        }
        double sum = 0;
        for (int y = std::max(0, c[1] - 1); y <= std::min(dims[1] - 1, c[1] + 1); ++y) {
            for (int z = std::max(0, c[2] - 1); z <= std::min(dims[2] - 1, c[2] + 1); ++z) {
                for (int x = std::max(0, c[0] - 1); x <= std::min(dims[0] - 1, c[0] + 1); ++x) {
                    const std::size_t cell = (std::size_t(y) * dims[2] + z) * dims[0] + x;
                    out.near[cell] = 1;
                    for (Index j = out.cellStart[cell]; j < out.cellStart[cell + 1]; ++j) {
                        const double r2 = lengthSquared(sorted[j] - p);
                        if (r2 < h * h) {
                            const double t = 1.0 - r2 / (h * h);
                            sum += kernel == BoundaryKernel::Poly6
                                       ? poly6 * t * t * t
                                       : double(wendland.value(Real(std::sqrt(r2))));
                        }
                    }
                }
            }
        }
        // Akinci's psi, capped at a full neighbourhood's (see scene/boundary.h).
        const double psi = std::min(restDensity / sum, restDensity * fullVolume);
        out.pos[i] = {Real(p.x), Real(p.y), Real(p.z), Real(psi)};
        if (faceVelocity != nullptr) {
            const int face = samples.faces[order[i]];
            const Vec3d v = face >= 0 ? (*faceVelocity)[std::size_t(face)] : Vec3d();
            out.velocity[i] = {Real(v.x), Real(v.y), Real(v.z), 0};
        }
    }
    return out;
}

}  // namespace weir
