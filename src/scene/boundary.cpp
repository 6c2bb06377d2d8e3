// Boundary sampling, Akinci volumes and the static boundary grid.
#include "scene/boundary.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <string>
#include <unordered_map>
#include <utility>

#include "physics/kernels.h"

namespace weir {
namespace {

Vec3d normalize(const Vec3d& v) { return v / length(v); }

// Pieces a mesh triangle's longest edge may be cut into for boundary sampling (its n^2 / 2 points
// inside the container are sampled; past this, the mesh is far too coarse for the spacing).
constexpr double kMaxTriangleDivisions = 1e5;

bool insideRegion(const Vec3d& p, const Box& region) {
    return p.x >= region.min.x && p.x <= region.max.x && p.y >= region.min.y &&
           p.y <= region.max.y && p.z >= region.min.z && p.z <= region.max.z;
}

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
    // Clamped as a double first (no out-of-range conversion): the key wraps at 2^21 cells anyway.
    long cellOf(double v) const { return long(std::clamp(std::floor(v / cell_), -1e15, 1e15)); }
    static std::uint64_t key(long x, long y, long z) {
        return (std::uint64_t(x & 0x1FFFFF) << 42) | (std::uint64_t(y & 0x1FFFFF) << 21) |
               std::uint64_t(z & 0x1FFFFF);
    }
    double min_, cell_;
    BoundarySamples samples_;
    std::unordered_map<std::uint64_t, std::vector<std::size_t>> cells_;
};

// The lattice of a box surface [lo, hi] at spacing close to d (each axis divided evenly into
// n pieces), and the index range [first, last] of its points inside `region` on each axis.
struct BoxLattice {
    long n[3];
    double step[3];
    long first[3], last[3];

    BoxLattice(const Vec3d& lo, const Vec3d& hi, double d, const Box& region) {
        for (int a = 0; a < 3; ++a) {
            const double size = hi[a] - lo[a];
            // Sizes and spacings are bounded by the scene reader: n fits a long.
            n[a] = std::max(1L, long(std::lround(std::min(size / d, 1e15))));
            step[a] = size / double(n[a]);
            if (!(step[a] > 0)) {  // a flat box (an obstacle thinner than its inset)
                first[a] = 0;
                last[a] = lo[a] >= region.min[a] && lo[a] <= region.max[a] ? n[a] : -1;
                continue;
            }
            const double from = std::ceil((region.min[a] - lo[a]) / step[a]);
            const double to = std::floor((region.max[a] - lo[a]) / step[a]);
            first[a] = long(std::clamp(from, 0.0, double(n[a]) + 1));
            last[a] = long(std::clamp(to, -1.0, double(n[a])));
        }
    }
    bool empty() const { return first[0] > last[0] || first[1] > last[1] || first[2] > last[2]; }
    // Points of the surface in the region: those of the clipped range less its interior ones.
    double count() const {
        if (empty()) {
            return 0;
        }
        double all = 1, interior = 1;
        for (int a = 0; a < 3; ++a) {
            all *= double(last[a] - first[a] + 1);
            interior *=
                double(std::max(0L, std::min(last[a], n[a] - 1) - std::max(first[a], 1L) + 1));
        }
        return all - interior;
    }
};

// The surface of box [lo, hi] on a lattice of spacing close to d (each axis divided evenly), the
// points inside `region` only; for the container (`container`) each point names its first face,
// 0..5 as -x, +x, -y, +y, -z, +z.
void sampleBoxSurface(const Vec3d& lo, const Vec3d& hi, double d, bool container, const Box& region,
                      PointSet& out) {
    const BoxLattice lattice(lo, hi, d, region);
    if (lattice.empty()) {
        return;
    }
    const long* n = lattice.n;
    const double* step = lattice.step;
    for (long k = lattice.first[2]; k <= lattice.last[2]; ++k) {
        for (long j = lattice.first[1]; j <= lattice.last[1]; ++j) {
            const bool faceYZ = k == 0 || k == n[2] || j == 0 || j == n[1];
            for (long i = lattice.first[0]; i <= lattice.last[0]; ++i) {
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
                    i = std::max(i, n[0] - 1);  // skip the interior of this row
                }
            }
        }
    }
}

// The Fibonacci lattice of a sphere (one point per d^2 of area, point k at height
// 1 - 2 (k + 1/2) / count of the unit sphere): the range of k whose heights meet `region`.
struct SphereBand {
    double count = 0, first = 0, last = -1;

    SphereBand(const Vec3d& centre, double radius, double d, const Box& region) {
        count = std::max(1.0, std::round(std::min(4 * kPi * radius * radius / (d * d), 1e18)));
        const double yLo = (region.min.y - centre.y) / radius;  // y = 1 - 2 (k + 1/2) / count
        const double yHi = (region.max.y - centre.y) / radius;
        bool meets = true;
        for (int a = 0; a < 3; ++a) {
            meets =
                meets && centre[a] + radius >= region.min[a] && centre[a] - radius <= region.max[a];
        }
        if (meets) {
            first = std::max(0.0, std::floor((1.0 - yHi) * count / 2 - 0.5));
            last = std::min(count - 1, std::ceil((1.0 - yLo) * count / 2 - 0.5));
        }
    }
    double points() const { return std::max(0.0, last - first + 1); }
};

// A sphere by the Fibonacci lattice: near-uniform points, one per d^2 of area (those in `region`).
void sampleSphereSurface(const Vec3d& centre, double radius, double d, const Box& region,
                         PointSet& out) {
    const SphereBand band(centre, radius, d, region);
    const double golden = kPi * (3.0 - std::sqrt(5.0));
    for (double k = band.first; k <= band.last; ++k) {
        const double y = 1.0 - 2.0 * (k + 0.5) / band.count;
        const double ring = std::sqrt(std::max(0.0, 1.0 - y * y));
        const double phi = golden * k;
        const Vec3d p = centre + Vec3d(ring * std::cos(phi), y, ring * std::sin(phi)) * radius;
        if (insideRegion(p, region)) {
            out.add(p);
        }
    }
}

// A triangle on a barycentric lattice with edges cut into n pieces no longer than d, moved by
// `offset` along its unit normal (negative: into the solid): point (i, j) is
// a + e1 i / n + e2 j / n + offset normal, i + j <= n. Only the points inside `region` count:
// for each i, the range of j that meets it, so a triangle far larger than the container costs
// n steps and the points inside, not n^2.
struct TriangleLattice {
    Vec3d origin, e1, e2;
    long n = 0;  // 0: degenerate, no points

    TriangleLattice(const Vec3d& a, const Vec3d& b, const Vec3d& c, double d, double offset,
                    const std::string& mesh) {
        e1 = b - a;
        e2 = c - a;
        Vec3d normal = cross(e1, e2);
        const double area2 = length(normal);
        if (!(area2 > 0)) {
            return;
        }
        origin = a + normal / area2 * offset;
        const double pieces = std::ceil(std::max({length(e1), length(e2), length(c - b)}) / d);
        if (!(pieces <= kMaxTriangleDivisions)) {
            throw SceneError("mesh obstacle " + mesh + ": a triangle " + std::to_string(pieces) +
                             " spacings long, more than the " +
                             std::to_string(long(kMaxTriangleDivisions)) +
                             " that boundary sampling allows per edge; split it into smaller "
                             "triangles, scale the mesh down or use a larger particles.spacing");
        }
        n = std::max(1L, long(pieces));
    }
    Vec3d point(long i, long j) const {
        return origin + e1 * (double(i) / double(n)) + e2 * (double(j) / double(n));
    }
    // The j of row i whose points lie in region (first > last: none).
    std::pair<long, long> row(long i, const Box& region) const {
        double lo = 0, hi = double(n - i);
        const Vec3d start = origin + e1 * (double(i) / double(n));
        for (int a = 0; a < 3 && lo <= hi; ++a) {
            const double slope = e2[a] / double(n);  // per j
            const double below = region.min[a] - start[a], above = region.max[a] - start[a];
            if (slope == 0) {
                if (below > 0 || above < 0) {
                    hi = -1;
                }
                continue;
            }
            const double j0 = below / slope, j1 = above / slope;
            lo = std::max(lo, std::ceil(std::min(j0, j1) - 1e-9));
            hi = std::min(hi, std::floor(std::max(j0, j1) + 1e-9));
        }
        return lo <= hi ? std::pair<long, long>{long(lo), long(hi)} : std::pair<long, long>{0, -1};
    }
    double count(const Box& region) const {
        double total = 0;
        for (long i = 0; i < n + (n > 0 ? 1 : 0); ++i) {
            const auto [first, last] = row(i, region);
            total += double(last - first + 1);
        }
        return total;
    }
};

void sampleTriangle(const TriangleLattice& lattice, const Box& region, PointSet& out) {
    for (long i = 0; i < lattice.n + (lattice.n > 0 ? 1 : 0); ++i) {
        const auto [first, last] = lattice.row(i, region);
        for (long j = first; j <= last; ++j) {
            const Vec3d p = lattice.point(i, j);
            if (insideRegion(p, region)) {  // the row's range is rounded outwards
                out.add(p);
            }
        }
    }
}

}  // namespace

namespace {

// The inside test's ray p + t dir, t > 0: along +x, slightly tilted off the axes so that it does
// not run along edges of axis-aligned meshes.
const Vec3d kRay = normalize(Vec3d(1.0, 1.3e-4, 2.9e-5));

// Whether the ray from p crosses triangle t (Moller-Trumbore).
bool rayCrosses(const MeshObstacle& mesh, const std::array<int, 3>& t, const Vec3d& p) {
    const Vec3d &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &c = mesh.vertices[t[2]];
    const Vec3d e1 = b - a, e2 = c - a, q = cross(kRay, e2);
    const double det = dot(e1, q);
    if (std::fabs(det) < 1e-300) {
        return false;
    }
    const double inv = 1.0 / det;
    const Vec3d s = p - a;
    const double u = dot(s, q) * inv;
    if (u < 0 || u > 1) {
        return false;
    }
    const Vec3d r = cross(s, e1);
    const double v = dot(kRay, r) * inv;
    if (v < 0 || u + v > 1) {
        return false;
    }
    return dot(e2, r) * inv > 0;
}

}  // namespace

// The triangles of a mesh binned by their (y, z) bounds on a uniform grid over the mesh's: the
// ray runs along +x and drifts by 1.3e-4 of its length in y (less in z), so only the triangles
// binned in the few cells it passes over can be crossed.
struct MeshIndex {
    Vec3d lo, hi;  // the mesh's bounds, widened by a hair
    double cell[2] = {1, 1};
    int dims[2] = {1, 1};
    std::vector<std::array<int, 4>> cells;  // per triangle: first y, last y, first z, last z
    std::vector<std::size_t> start;         // per cell (y fastest) into `triangles`
    std::vector<int> triangles;

    int cellOf(double v, int axis) const {  // axis 0: y, 1: z
        const double c = std::floor((v - lo[axis + 1]) / cell[axis]);
        return int(std::clamp(c, 0.0, double(dims[axis] - 1)));
    }
};

void buildMeshIndex(MeshObstacle& mesh) {
    auto index = std::make_shared<MeshIndex>();
    index->lo = Vec3d(1e300, 1e300, 1e300);
    index->hi = -index->lo;
    for (const Vec3d& v : mesh.vertices) {
        for (int a = 0; a < 3; ++a) {
            index->lo[a] = std::min(index->lo[a], v[a]);
            index->hi[a] = std::max(index->hi[a], v[a]);
        }
    }
    const std::size_t count = mesh.triangles.size();
    if (count == 0) {
        mesh.index = std::move(index);
        return;
    }
    const Vec3d pad = (index->hi - index->lo) * 1e-9 + Vec3d(1e-12, 1e-12, 1e-12);
    index->lo = index->lo - pad;
    index->hi = index->hi + pad;
    // About one triangle per cell; coarser while big triangles would be binned too many times.
    int side = int(std::clamp(std::sqrt(double(count)), 1.0, 1024.0));
    for (;; side = std::max(1, side / 2)) {
        for (int a = 0; a < 2; ++a) {
            index->dims[a] = side;
            index->cell[a] = (index->hi[a + 1] - index->lo[a + 1]) / side;
        }
        index->cells.resize(count);
        double entries = 0;
        for (std::size_t t = 0; t < count; ++t) {
            double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
            for (int corner : mesh.triangles[t]) {
                for (int a = 0; a < 2; ++a) {
                    lo[a] = std::min(lo[a], mesh.vertices[std::size_t(corner)][a + 1]);
                    hi[a] = std::max(hi[a], mesh.vertices[std::size_t(corner)][a + 1]);
                }
            }
            std::array<int, 4>& c = index->cells[t];
            c = {index->cellOf(lo[0] - pad.y, 0), index->cellOf(hi[0] + pad.y, 0),
                 index->cellOf(lo[1] - pad.z, 1), index->cellOf(hi[1] + pad.z, 1)};
            entries += double(c[1] - c[0] + 1) * double(c[3] - c[2] + 1);
        }
        if (side == 1 || entries <= 16.0 * double(count) + 1e6) {
            break;
        }
    }
    const std::size_t cellCount = std::size_t(index->dims[0]) * std::size_t(index->dims[1]);
    index->start.assign(cellCount + 1, 0);
    auto forCells = [&](const std::array<int, 4>& c, auto&& f) {
        for (int z = c[2]; z <= c[3]; ++z) {
            for (int y = c[0]; y <= c[1]; ++y) {
                f(std::size_t(z) * std::size_t(index->dims[0]) + std::size_t(y));
            }
        }
    };
    for (const auto& c : index->cells) {
        forCells(c, [&](std::size_t cell) { ++index->start[cell + 1]; });
    }
    for (std::size_t c = 0; c < cellCount; ++c) {
        index->start[c + 1] += index->start[c];
    }
    index->triangles.resize(index->start[cellCount]);
    std::vector<std::size_t> next(index->start.begin(), index->start.end() - 1);
    for (std::size_t t = 0; t < count; ++t) {
        forCells(index->cells[t],
                 [&](std::size_t cell) { index->triangles[next[cell]++] = int(t); });
    }
    mesh.index = std::move(index);
}

namespace {

// The squared distance from p to triangle (a, b, c): its closest point by the Voronoi region p
// falls in (Ericson, Real-Time Collision Detection, 5.1.5).
double triangleDistanceSquared(const Vec3d& p, const Vec3d& a, const Vec3d& b, const Vec3d& c) {
    const Vec3d ab = b - a, ac = c - a, ap = p - a;
    const double d1 = dot(ab, ap), d2 = dot(ac, ap);
    if (d1 <= 0 && d2 <= 0) {
        return lengthSquared(ap);
    }
    const Vec3d bp = p - b;
    const double d3 = dot(ab, bp), d4 = dot(ac, bp);
    if (d3 >= 0 && d4 <= d3) {
        return lengthSquared(bp);
    }
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) {
        return lengthSquared(ap - ab * (d1 / (d1 - d3)));
    }
    const Vec3d cp = p - c;
    const double d5 = dot(ab, cp), d6 = dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) {
        return lengthSquared(cp);
    }
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) {
        return lengthSquared(ap - ac * (d2 / (d2 - d6)));
    }
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
        return lengthSquared(bp - (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))));
    }
    const double denom = 1.0 / (va + vb + vc);
    return lengthSquared(ap - ab * (vb * denom) - ac * (vc * denom));
}

}  // namespace

bool nearMesh(const MeshObstacle& mesh, const Vec3d& p, double distance) {
    const double d2 = distance * distance;
    auto near = [&](const std::array<int, 3>& t) {
        return triangleDistanceSquared(p, mesh.vertices[std::size_t(t[0])],
                                       mesh.vertices[std::size_t(t[1])],
                                       mesh.vertices[std::size_t(t[2])]) < d2;
    };
    const MeshIndex* index = mesh.index.get();
    if (index == nullptr) {
        for (const auto& t : mesh.triangles) {
            if (near(t)) {
                return true;
            }
        }
        return false;
    }
    for (int a = 0; a < 3; ++a) {
        if (p[a] < index->lo[a] - distance || p[a] > index->hi[a] + distance) {
            return false;
        }
    }
    // The cells over p's (y, z) widened by the distance: every triangle that comes that close.
    const int y0 = index->cellOf(p.y - distance, 0), y1 = index->cellOf(p.y + distance, 0);
    const int z0 = index->cellOf(p.z - distance, 1), z1 = index->cellOf(p.z + distance, 1);
    for (int z = z0; z <= z1; ++z) {
        for (int y = y0; y <= y1; ++y) {
            const std::size_t cell = std::size_t(z) * std::size_t(index->dims[0]) + std::size_t(y);
            for (std::size_t k = index->start[cell]; k < index->start[cell + 1]; ++k) {
                const int t = index->triangles[k];
                const std::array<int, 4>& c = index->cells[std::size_t(t)];
                if (y != std::max(y0, c[0]) || z != std::max(z0, c[2])) {
                    continue;  // tested in an earlier cell
                }
                if (near(mesh.triangles[std::size_t(t)])) {
                    return true;
                }
            }
        }
    }
    return false;
}

bool insideMesh(const MeshObstacle& mesh, const Vec3d& p) {
    // Parity of the ray's crossings of the surface.
    int crossings = 0;
    const MeshIndex* index = mesh.index.get();
    if (index != nullptr && index->start.empty()) {
        return false;  // no triangles
    }
    if (index == nullptr) {
        for (const auto& t : mesh.triangles) {
            crossings += rayCrosses(mesh, t, p) ? 1 : 0;
        }
        return (crossings & 1) != 0;
    }
    // The ray meets the mesh's bounds, if at all, for t up to where it leaves them along x.
    if (!(p.x <= index->hi.x && p.y <= index->hi.y && p.z <= index->hi.z)) {
        return false;
    }
    const double reach = (index->hi.x - p.x) / kRay.x;
    const double yEnd = p.y + kRay.y * reach, zEnd = p.z + kRay.z * reach;
    if (yEnd < index->lo.y || zEnd < index->lo.z) {
        return false;
    }
    const int y0 = index->cellOf(p.y, 0), y1 = index->cellOf(yEnd, 0);
    const int z0 = index->cellOf(p.z, 1), z1 = index->cellOf(zEnd, 1);
    for (int z = z0; z <= z1; ++z) {
        for (int y = y0; y <= y1; ++y) {
            const std::size_t cell = std::size_t(z) * std::size_t(index->dims[0]) + std::size_t(y);
            for (std::size_t k = index->start[cell]; k < index->start[cell + 1]; ++k) {
                const int t = index->triangles[k];
                const std::array<int, 4>& c = index->cells[std::size_t(t)];
                // A triangle binned in several of these cells is tested in the first only.
                if (y != std::max(y0, c[0]) || z != std::max(z0, c[2])) {
                    continue;
                }
                crossings += rayCrosses(mesh, mesh.triangles[std::size_t(t)], p) ? 1 : 0;
            }
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

namespace {

// Every surface that sampleBoundary samples, each with the region its points are kept in:
// visit.box(lo, hi, container), visit.sphere(centre, radius), visit.triangle(lattice), with the
// region passed to each.
template <class Visit>
void forEachBoundarySurface(const Scene& scene, double d, double h, int layers, Visit& visit) {
    // Fluid stays in the container; a boundary point counts for it within h, and its volume psi
    // for the points within h: nothing past 2 h and the layers outside the container matters.
    const double margin = 2 * h + (layers + 1) * d;
    const Box region{scene.container.min - Vec3d(margin, margin, margin),
                     scene.container.max + Vec3d(margin, margin, margin)};
    for (int layer = 0; layer < layers; ++layer) {
        const double depth = (layer + 0.5) * d;  // behind the surface
        const Vec3d out(depth, depth, depth);
        visit.box(scene.container.min - out, scene.container.max + out, true, region);
        for (const Box& box : scene.obstacleBoxes) {
            Vec3d inset = out;
            for (int a = 0; a < 3; ++a) {
                inset[a] = std::min(inset[a], 0.5 * (box.max[a] - box.min[a]));
            }
            visit.box(box.min + inset, box.max - inset, false, region);
        }
        for (const SphereShape& s : scene.obstacleSpheres) {
            if (s.radius - depth > 0.25 * d || layer == 0) {
                visit.sphere(s.center, std::max(s.radius - depth, 0.25 * s.radius), region);
            }
        }
        for (const MeshObstacle& mesh : scene.obstacleMeshes) {
            for (const auto& t : mesh.triangles) {
                const Vec3d &a = mesh.vertices[std::size_t(t[0])],
                            &b = mesh.vertices[std::size_t(t[1])],
                            &c = mesh.vertices[std::size_t(t[2])];
                bool meets = true;  // the triangle's bounds meet the region
                for (int axis = 0; axis < 3 && meets; ++axis) {
                    meets = std::max({a[axis], b[axis], c[axis]}) + depth >= region.min[axis] &&
                            std::min({a[axis], b[axis], c[axis]}) - depth <= region.max[axis];
                }
                if (meets) {
                    visit.triangle(TriangleLattice(a, b, c, d, -depth, mesh.file), region);
                }
            }
        }
    }
}

}  // namespace

double boundarySampleBound(const Scene& scene, double d, double h, int layers) {
    struct Count {
        double d, total = 0;
        void box(const Vec3d& lo, const Vec3d& hi, bool, const Box& region) {
            total += BoxLattice(lo, hi, d, region).count();
        }
        void sphere(const Vec3d& centre, double radius, const Box& region) {
            total += SphereBand(centre, radius, d, region).points();
        }
        void triangle(const TriangleLattice& lattice, const Box& region) {
            total += lattice.count(region);
        }
    } count{d};
    forEachBoundarySurface(scene, d, h, layers, count);
    return count.total;
}

BoundarySamples sampleBoundary(const Scene& scene, double d, double h, int layers) {
    struct Sample {
        double d;
        PointSet points;
        void box(const Vec3d& lo, const Vec3d& hi, bool container, const Box& region) {
            sampleBoxSurface(lo, hi, d, container, region, points);
        }
        void sphere(const Vec3d& centre, double radius, const Box& region) {
            sampleSphereSurface(centre, radius, d, region, points);
        }
        void triangle(const TriangleLattice& lattice, const Box& region) {
            sampleTriangle(lattice, region, points);
        }
    } sample{d, PointSet(0.5 * d)};
    forEachBoundarySurface(scene, d, h, layers, sample);
    return sample.points.take();
}

BoundarySamples sampleBodySurface(const BodySpec& body, double d, int layers) {
    if (body.isMesh) {
        // Each layer is the mesh's triangles moved in by its depth, kept only where the point is
        // inside the solid and that deep from every part of its surface: nested offset surfaces,
        // as a box's layers are nested boxes. (An offset triangle spans its whole face, so near
        // an edge it would reach the neighbouring faces' planes, or through them at a sharp
        // one: particles on the surface push the fluid off a body's own d/2 clearance.)
        const MeshObstacle& mesh = body.mesh;
        const Box bounds = body.bounds();
        const Box region{bounds.min - Vec3d(d, d, d), bounds.max + Vec3d(d, d, d)};
        auto latticeOf = [&](const std::array<int, 3>& t, double offset) {
            return TriangleLattice(mesh.vertices[std::size_t(t[0])],
                                   mesh.vertices[std::size_t(t[1])],
                                   mesh.vertices[std::size_t(t[2])], d, offset, mesh.file);
        };
        PointSet points(0.5 * d);
        for (int layer = 0; layer < layers; ++layer) {
            const double depth = (layer + 0.5) * d;
            for (const auto& t : mesh.triangles) {
                const TriangleLattice lattice = latticeOf(t, -depth);
                for (long i = 0; i < lattice.n + (lattice.n > 0 ? 1 : 0); ++i) {
                    const auto [first, last] = lattice.row(i, region);
                    for (long j = first; j <= last; ++j) {
                        const Vec3d p = lattice.point(i, j);
                        if (insideRegion(p, region) && insideMesh(mesh, p) &&
                            !nearMesh(mesh, p, depth * (1 - 1e-3))) {
                            points.add(p);
                        }
                    }
                }
            }
        }
        BoundarySamples out = points.take();
        if (out.points.empty()) {  // thinner than a spacing: one sheet, its mid-surface's points
            PointSet sheet(0.5 * d);
            for (const auto& t : mesh.triangles) {
                sampleTriangle(latticeOf(t, 0.0), region, sheet);
            }
            out = sheet.take();
        }
        return out;
    }
    Scene alone;
    alone.container = body.bounds();
    if (body.isSphere) {
        alone.obstacleSpheres.push_back(body.sphere);
    } else {
        alone.obstacleBoxes.push_back(body.box);
    }
    struct Sample {
        double d;
        PointSet points;
        void box(const Vec3d& lo, const Vec3d& hi, bool container, const Box& region) {
            if (!container) {  // the scene's container is only the body's bounds
                sampleBoxSurface(lo, hi, d, false, region, points);
            }
        }
        void sphere(const Vec3d& centre, double radius, const Box& region) {
            sampleSphereSurface(centre, radius, d, region, points);
        }
        void triangle(const TriangleLattice&, const Box&) {}
    } sample{d, PointSet(0.5 * d)};
    forEachBoundarySurface(alone, d, d, layers, sample);
    return sample.points.take();
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
        const double cellsAlong = std::ceil((container.max[a] - container.min[a] + 2 * h) / h);
        if (!(cellsAlong <= double(1 << 21))) {  // the setup's grid allows 2^20
            throw SceneError("the boundary grid would need " + std::to_string(cellsAlong) +
                             " cells of " + std::to_string(h) + " m along axis " +
                             std::to_string(a) + ", more than the 2097152 allowed");
        }
        dims[a] = std::max(1, int(cellsAlong));
        out.dims[a] = dims[a];
    }
    out.origin = Vec3(lo);
    out.cellSize = Real(h);
    const std::size_t cells = std::size_t(dims[0]) * dims[1] * dims[2];
    // Clamped as a double: a point far outside (or NaN) lands in an edge cell.
    auto axisCell = [&](const Vec3d& p, int a) {
        const double c = std::floor((p[a] - lo[a]) / h);
        return c >= double(dims[a] - 1) ? dims[a] - 1 : (c >= 0 ? int(c) : 0);
    };
    auto cellOf = [&](const Vec3d& p) {
        int c[3];
        for (int a = 0; a < 3; ++a) {
            c[a] = axisCell(p, a);
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
            c[a] = axisCell(p, a);
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
