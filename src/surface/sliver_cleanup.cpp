// removeSlivers: bad triangles found in parallel, then fixed one at a time by local collapses and
// flips over a vertex-to-triangle table.
#include "surface/sliver_cleanup.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <deque>
#include <limits>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "core/vec3.h"
#include "surface/mesh_measures.h"

namespace weir {

namespace {

constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

Vec3d crossProduct(const Vec3d& a, const Vec3d& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

struct TriangleShape {
    double edge[3];   // edge k runs from corner k to corner k + 1
    double angle[3];  // at corner k, in degrees
    double minEdge() const { return std::min({edge[0], edge[1], edge[2]}); }
    double minAngle() const { return std::min({angle[0], angle[1], angle[2]}); }
    double maxAngle() const { return std::max({angle[0], angle[1], angle[2]}); }
};

TriangleShape shapeOf(const Vec3d p[3]) {
    TriangleShape s;
    for (int k = 0; k < 3; ++k) {
        s.edge[k] = length(p[(k + 1) % 3] - p[k]);
    }
    for (int k = 0; k < 3; ++k) {
        s.angle[k] = cornerAngleDegrees(p[k], p[(k + 1) % 3], p[(k + 2) % 3]);
    }
    return s;
}

// Whether the triangle has an edge under minEdge or an angle under kSliverAngleDegrees: shapeOf's
// test without its arc cosines (an angle is under the bound where its cosine is above the
// bound's), for the pass over every triangle.
bool isSliver(const Vec3d p[3], double minEdge) {
    static const double cosineBound = std::cos(kSliverAngleDegrees * 3.14159265358979323846 / 180);
    const Vec3d e[3] = {p[1] - p[0], p[2] - p[1], p[0] - p[2]};
    const double length2[3] = {lengthSquared(e[0]), lengthSquared(e[1]), lengthSquared(e[2])};
    const double minEdge2 = minEdge * minEdge;
    if (length2[0] < minEdge2 || length2[1] < minEdge2 || length2[2] < minEdge2) {
        return true;
    }
    for (int k = 0; k < 3; ++k) {  // the angle at corner k, between -e[k + 2] and e[k]
        const double cosine = -dot(e[(k + 2) % 3], e[k]);
        if (cosine > 0 &&
            cosine * cosine > cosineBound * cosineBound * length2[k] * length2[(k + 2) % 3]) {
            return true;
        }
    }
    return false;
}

// Rings of vertices around the bad triangles whose triangle lists the cleaner builds: the cleaner
// works on the vertices of the first kKnownRings rings (their lists complete) and leaves alone
// any operation that would read or change a vertex beyond them, so that its setup costs a few
// parallel passes over the mesh, not a vertex-to-triangle table of the whole mesh.
constexpr int kKnownRings = 3;

class SliverCleaner {
   public:
    SliverCleaner(TriangleMesh& mesh, double cellSize)
        : mesh_(mesh),
          minEdge_(kSliverEdgeFraction * cellSize),
          triangles_(mesh.triangleCount()),
          alive_(triangles_, 1) {}

    // Builds the triangle lists of the vertices within kKnownRings rings of the bad triangles
    // (ring 0: their corners; ring r + 1: the other corners of the triangles at ring r).
    void learnAround(const std::vector<std::uint32_t>& bad) {
        keepOrphans();
        lists_.clear();
        std::vector<std::uint8_t> ring(mesh_.vertexCount(), 0);  // 0: none, else ring + 1
        for (std::uint32_t t : bad) {
            for (int k = 0; k < 3; ++k) {
                ring[corners(t)[k]] = 1;
            }
        }
        const std::int64_t triangles = std::int64_t(triangles_);
        std::uint8_t* rings = ring.data();
        const std::uint32_t* indices = mesh_.indices.data();
        for (int r = 1; r < kKnownRings; ++r) {
            // A triangle with a corner in an earlier ring brings its other corners into ring r;
            // marks made in this pass (r + 1) do not count in it, so the result is the same
            // whatever the threads' order.
#pragma omp parallel for schedule(static)
            for (std::int64_t t = 0; t < triangles; ++t) {
                if (!alive_[std::size_t(t)]) {
                    continue;
                }
                const std::uint32_t* c = indices + 3 * t;
                bool near = false;
                for (int k = 0; k < 3; ++k) {
                    const std::uint8_t m = __atomic_load_n(&rings[c[k]], __ATOMIC_RELAXED);
                    near = near || (m != 0 && m <= r);
                }
                if (near) {
                    for (int k = 0; k < 3; ++k) {
                        if (__atomic_load_n(&rings[c[k]], __ATOMIC_RELAXED) == 0) {
                            __atomic_store_n(&rings[c[k]], std::uint8_t(r + 1), __ATOMIC_RELAXED);
                        }
                    }
                }
            }
        }
        // Each known vertex's triangles, in triangle order.
        std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>> found(
            static_cast<std::size_t>(omp_get_max_threads()));
#pragma omp parallel
        {
            auto& mine = found[std::size_t(omp_get_thread_num())];
#pragma omp for schedule(static)
            for (std::int64_t t = 0; t < triangles; ++t) {
                if (!alive_[std::size_t(t)]) {
                    continue;
                }
                for (int k = 0; k < 3; ++k) {
                    const std::uint32_t v = indices[3 * t + k];
                    if (rings[v] != 0) {
                        mine.emplace_back(v, std::uint32_t(t));
                    }
                }
            }
        }
        std::size_t pairCount = 0;
        for (const auto& pairs : found) {
            pairCount += pairs.size();
        }
        lists_.reserve(pairCount / 4);
        // The threads' static chunks, in thread order, are in triangle order: each list comes
        // out sorted.
        for (const auto& pairs : found) {
            for (const auto& [v, t] : pairs) {
                lists_[v].push_back(t);
            }
        }
    }

    bool isBad(std::uint32_t t) const {
        if (!alive_[t]) {
            return false;
        }
        const std::uint32_t* c = corners(t);
        const Vec3d p[3] = {position(c[0]), position(c[1]), position(c[2])};
        return isSliver(p, minEdge_);
    }

    // Fixes what it can of the bad triangles (learnAround them first) and returns those still
    // bad.
    std::vector<std::uint32_t> fix(const std::vector<std::uint32_t>& bad,
                                   SliverCleanupReport& report) {
        reachedBeyond_ = false;
        std::deque<std::uint32_t> queue(bad.begin(), bad.end());
        // The triangles that can be bad at the end: the bad ones and every one an operation
        // reshaped (a collapse touches all triangles of the merged vertex, a flip its two).
        std::vector<std::uint32_t> candidates(bad.begin(), bad.end());
        std::size_t budget = 8 * bad.size() + 64;  // every operation removes or reshapes a sliver
        while (!queue.empty() && budget > 0) {
            const std::uint32_t t = queue.front();
            queue.pop_front();
            if (!isBad(t)) {
                continue;
            }
            --budget;
            std::vector<std::uint32_t> touched;
            if (fixTriangle(t, report, touched)) {
                candidates.insert(candidates.end(), touched.begin(), touched.end());
                for (std::uint32_t u : touched) {
                    if (isBad(u)) {
                        queue.push_back(u);
                    }
                }
            }
        }
        // What no operation could fix is a speck: a closed piece of a few triangles around one
        // lattice sample barely past the iso-value (a tetrahedron a hundredth of a cell across,
        // where every collapse would break the link condition). It goes, whole.
        std::sort(candidates.begin(), candidates.end());
        candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
        for (std::uint32_t t : candidates) {
            if (isBad(t) && removeSpeck(t)) {
                ++report.specks;
            }
        }
        std::vector<std::uint32_t> left;
        for (std::uint32_t t : candidates) {
            if (isBad(t)) {
                left.push_back(t);
            }
        }
        return left;
    }

    bool anyDead() const { return removedAny_; }
    // Whether the last fix left a triangle because an operation would have reached past the
    // known rings (another round, with rings around what is left, may then fix it).
    bool reachedBeyond() const { return reachedBeyond_; }

    // Drops the dead triangles and the vertices no triangle uses: each hole takes the last
    // triangle (vertex) still used, so that this costs what died, plus one parallel pass over
    // the indices to rename the vertices that moved.
    void compact() {
        std::sort(dead_.begin(), dead_.end());
        dead_.erase(std::unique(dead_.begin(), dead_.end()), dead_.end());
        std::uint32_t* indices = mesh_.indices.data();
        std::size_t count = triangles_;
        for (std::uint32_t hole : dead_) {
            while (count > 0 && !alive_[count - 1]) {
                --count;
            }
            if (hole >= count) {
                break;
            }
            std::copy(indices + 3 * (count - 1), indices + 3 * count, indices + 3 * hole);
            alive_[hole] = 1;
            alive_[count - 1] = 0;
            --count;
        }
        while (count > 0 && !alive_[count - 1]) {
            --count;
        }
        mesh_.indices.resize(3 * count);

        // A known vertex with no triangle left (a collapsed edge's first end, a speck's) is
        // unused; every other vertex keeps its triangles.
        keepOrphans();
        std::vector<std::uint32_t> unused = orphans_;
        std::sort(unused.begin(), unused.end());
        unused.erase(std::unique(unused.begin(), unused.end()), unused.end());
        std::unordered_set<std::uint32_t> holes(unused.begin(), unused.end());  // still empty
        std::size_t vertices = mesh_.vertexCount();
        const auto trimTail = [&] {
            while (vertices > 0 && holes.count(std::uint32_t(vertices - 1)) != 0) {
                holes.erase(std::uint32_t(vertices - 1));
                --vertices;
            }
        };
        std::vector<std::pair<std::uint32_t, std::uint32_t>> moves;  // (from, to)
        for (std::uint32_t hole : unused) {
            trimTail();
            if (hole >= vertices) {
                break;
            }
            const std::uint32_t last = std::uint32_t(vertices - 1);
            mesh_.positions[hole] = mesh_.positions[last];
            mesh_.normals[hole] = mesh_.normals[last];
            moves.emplace_back(last, hole);
            holes.erase(hole);
            --vertices;
        }
        trimTail();
        if (!moves.empty()) {
            std::vector<char> moved(mesh_.vertexCount(), 0);
            std::unordered_map<std::uint32_t, std::uint32_t> to;
            for (const auto& [from, hole] : moves) {
                moved[from] = 1;
                to[from] = hole;
            }
            const std::int64_t entries = std::int64_t(mesh_.indices.size());
#pragma omp parallel for schedule(static)
            for (std::int64_t i = 0; i < entries; ++i) {
                if (moved[indices[i]]) {
                    indices[i] = to.at(indices[i]);
                }
            }
        }
        mesh_.positions.resize(vertices);
        mesh_.normals.resize(vertices);
    }

   private:
    TriangleMesh& mesh_;
    double minEdge_;
    std::size_t triangles_;
    std::vector<char> alive_;
    // The triangles of each vertex the cleaner knows (learnAround); a vertex not here is beyond
    // its reach, and no operation touches it.
    std::unordered_map<std::uint32_t, std::vector<std::uint32_t>> lists_;
    bool removedAny_ = false;
    std::vector<std::uint32_t> dead_;     // triangles removed
    std::vector<std::uint32_t> orphans_;  // vertices left without a triangle

    // Notes the known vertices left without a triangle before the lists are rebuilt (a vertex
    // no alive triangle uses is in no later round's lists).
    void keepOrphans() {
        for (const auto& [v, list] : lists_) {
            if (list.empty()) {
                orphans_.push_back(v);
            }
        }
    }

    bool reachedBeyond_ = false;  // an operation was refused for a vertex beyond the rings

    bool known(std::uint32_t v) {
        const bool isKnown = lists_.count(v) != 0;
        reachedBeyond_ = reachedBeyond_ || !isKnown;
        return isKnown;
    }

    std::uint32_t* corners(std::uint32_t t) { return &mesh_.indices[3 * std::size_t(t)]; }
    const std::uint32_t* corners(std::uint32_t t) const {
        return &mesh_.indices[3 * std::size_t(t)];
    }
    Vec3d position(std::uint32_t v) const { return Vec3d(mesh_.positions[v]); }

    TriangleShape shape(std::uint32_t t) const {
        const std::uint32_t* c = corners(t);
        const Vec3d p[3] = {position(c[0]), position(c[1]), position(c[2])};
        return shapeOf(p);
    }

    std::vector<std::uint32_t> trianglesOf(std::uint32_t v) const {
        const auto it = lists_.find(v);
        return it != lists_.end() ? it->second : std::vector<std::uint32_t>{};
    }
    void setTrianglesOf(std::uint32_t v, std::vector<std::uint32_t> list) {
        lists_[v] = std::move(list);
    }

    std::vector<std::uint32_t> neighboursOf(std::uint32_t v) const {
        std::vector<std::uint32_t> out;
        for (std::uint32_t t : trianglesOf(v)) {
            for (int k = 0; k < 3; ++k) {
                if (corners(t)[k] != v) {
                    out.push_back(corners(t)[k]);
                }
            }
        }
        std::sort(out.begin(), out.end());
        out.erase(std::unique(out.begin(), out.end()), out.end());
        return out;
    }

    // The triangles holding both a and b.
    std::vector<std::uint32_t> edgeTriangles(std::uint32_t a, std::uint32_t b) const {
        std::vector<std::uint32_t> out;
        for (std::uint32_t t : trianglesOf(a)) {
            const std::uint32_t* c = corners(t);
            if (c[0] == b || c[1] == b || c[2] == b) {
                out.push_back(t);
            }
        }
        return out;
    }

    Vec3d normalWith(std::uint32_t t, std::uint32_t moved, const Vec3d& to) const {
        const std::uint32_t* c = corners(t);
        Vec3d p[3];
        for (int k = 0; k < 3; ++k) {
            p[k] = c[k] == moved ? to : position(c[k]);
        }
        return crossProduct(p[1] - p[0], p[2] - p[0]);
    }

    bool fixTriangle(std::uint32_t t, SliverCleanupReport& report,
                     std::vector<std::uint32_t>& touched) {
        const TriangleShape s = shape(t);
        const std::uint32_t* c = corners(t);
        int order[3] = {0, 1, 2};  // edges, shortest first
        std::sort(order, order + 3, [&](int x, int y) { return s.edge[x] < s.edge[y]; });
        // A cap (an angle near 180 degrees, no edge too short) is fixed by a flip of its longest
        // edge; a needle, or a cap that cannot be flipped, by collapsing its shortest edge, else
        // the next; failing those (the link condition), by a flip of any edge that improves it.
        if (s.minEdge() >= minEdge_ && s.maxAngle() > 150 && flip(t, order[2], report, touched)) {
            return true;
        }
        for (int k : order) {
            if (collapse(c[k], c[(k + 1) % 3], report, touched)) {
                return true;
            }
        }
        for (int k : {order[2], order[1], order[0]}) {
            if (flip(t, k, report, touched)) {
                return true;
            }
        }
        return false;
    }

    // Removes the piece of the mesh that holds triangle t if it has at most kSpeckTriangles
    // triangles and fits in a box whose diagonal is under kSpeckExtent cells.
    bool removeSpeck(std::uint32_t t) {
        constexpr std::size_t kSpeckTriangles = 16;
        constexpr double kSpeckExtent = 0.1;
        std::vector<std::uint32_t> piece{t};
        Vec3d low = position(corners(t)[0]), high = low;
        for (std::size_t k = 0; k < piece.size(); ++k) {
            for (int c = 0; c < 3; ++c) {
                const std::uint32_t v = corners(piece[k])[c];
                if (!known(v)) {
                    return false;
                }
                for (int axis = 0; axis < 3; ++axis) {
                    low[axis] = std::min(low[axis], position(v)[axis]);
                    high[axis] = std::max(high[axis], position(v)[axis]);
                }
                for (std::uint32_t u : trianglesOf(v)) {
                    if (std::find(piece.begin(), piece.end(), u) == piece.end()) {
                        piece.push_back(u);
                    }
                }
            }
            if (piece.size() > kSpeckTriangles) {
                return false;
            }
        }
        if (!(length(high - low) < kSpeckExtent * minEdge_ / kSliverEdgeFraction)) {
            return false;
        }
        for (std::uint32_t u : piece) {
            alive_[u] = 0;
            dead_.push_back(u);
            removedAny_ = true;
            for (int c = 0; c < 3; ++c) {
                setTrianglesOf(corners(u)[c], {});
            }
        }
        return true;
    }

    // Collapses edge (a, b) into b, moved to the edge's midpoint.
    bool collapse(std::uint32_t a, std::uint32_t b, SliverCleanupReport& report,
                  std::vector<std::uint32_t>& touched) {
        if (!known(a) || !known(b)) {
            return false;
        }
        const std::vector<std::uint32_t> shared = edgeTriangles(a, b);
        if (shared.size() != 2) {
            return false;
        }
        std::uint32_t opposite[2];
        for (int k = 0; k < 2; ++k) {
            const std::uint32_t* c = corners(shared[std::size_t(k)]);
            opposite[k] = c[0] != a && c[0] != b ? c[0] : (c[1] != a && c[1] != b ? c[1] : c[2]);
            if (!known(opposite[k])) {
                return false;
            }
        }
        const std::vector<std::uint32_t> na = neighboursOf(a), nb = neighboursOf(b);
        std::vector<std::uint32_t> common;
        std::set_intersection(na.begin(), na.end(), nb.begin(), nb.end(),
                              std::back_inserter(common));
        std::uint32_t expected[2] = {std::min(opposite[0], opposite[1]),
                                     std::max(opposite[0], opposite[1])};
        if (common.size() != 2 || common[0] != expected[0] || common[1] != expected[1]) {
            return false;  // link condition: the collapse would pinch the surface
        }
        if (na.size() + nb.size() - 4 < 3) {  // b's neighbours after: (na + nb) - {a, b} - common
            return false;
        }
        for (std::uint32_t o : opposite) {
            if (neighboursOf(o).size() < 4) {  // it loses a neighbour and must keep three
                return false;
            }
        }
        const Vec3d to = (position(a) + position(b)) * 0.5;
        const std::vector<std::uint32_t> ta = trianglesOf(a), tb = trianglesOf(b);
        for (const std::vector<std::uint32_t>* list : {&ta, &tb}) {
            for (std::uint32_t t : *list) {
                if (t == shared[0] || t == shared[1]) {
                    continue;
                }
                const std::uint32_t moved = std::find(ta.begin(), ta.end(), t) != ta.end() ? a : b;
                const Vec3d before = normalWith(t, moved, position(moved));
                const Vec3d after = normalWith(t, moved, to);
                if (dot(before, after) <= 0 && length(before) > 1e-6 * minEdge_ * minEdge_) {
                    return false;  // it would turn over
                }
            }
        }
        // Done: the two triangles of the edge die, a's others take b.
        for (std::uint32_t dead : shared) {
            alive_[dead] = 0;
            dead_.push_back(dead);
            removedAny_ = true;
            for (int k = 0; k < 3; ++k) {
                const std::uint32_t v = corners(dead)[k];
                if (v != a && v != b) {
                    std::vector<std::uint32_t> list = trianglesOf(v);
                    list.erase(std::remove(list.begin(), list.end(), dead), list.end());
                    setTrianglesOf(v, std::move(list));
                }
            }
        }
        std::vector<std::uint32_t> merged;
        for (const std::vector<std::uint32_t>* list : {&ta, &tb}) {
            for (std::uint32_t t : *list) {
                if (alive_[t] && std::find(merged.begin(), merged.end(), t) == merged.end()) {
                    merged.push_back(t);
                    std::uint32_t* c = corners(t);
                    for (int k = 0; k < 3; ++k) {
                        c[k] = c[k] == a ? b : c[k];
                    }
                }
            }
        }
        setTrianglesOf(a, {});
        setTrianglesOf(b, merged);
        mesh_.positions[b] = Vec3f(to);
        const Vec3f n = mesh_.normals[a] + mesh_.normals[b];
        const float norm = length(n);
        mesh_.normals[b] = norm > 0 ? n / norm : mesh_.normals[b];
        touched = merged;
        ++report.collapses;
        return true;
    }

    // Flips the edge that starts at corner k of triangle t.
    bool flip(std::uint32_t t, int k, SliverCleanupReport& report,
              std::vector<std::uint32_t>& touched) {
        const std::uint32_t* c1 = corners(t);
        const std::uint32_t q = c1[k], r = c1[(k + 1) % 3], p = c1[(k + 2) % 3];
        if (!known(q) || !known(r) || !known(p)) {
            return false;
        }
        const std::vector<std::uint32_t> shared = edgeTriangles(q, r);
        if (shared.size() != 2) {
            return false;
        }
        const std::uint32_t u = shared[0] == t ? shared[1] : shared[0];
        const std::uint32_t* c2 = corners(u);
        int at = 0;  // u runs r -> q -> s
        while (c2[at] != r) {
            ++at;
        }
        if (c2[(at + 1) % 3] != q) {
            return false;  // wound the same way: leave it
        }
        const std::uint32_t s = c2[(at + 2) % 3];
        if (!known(s)) {
            return false;
        }
        const std::vector<std::uint32_t> np = neighboursOf(p);
        if (s == p || std::binary_search(np.begin(), np.end(), s)) {
            return false;  // the new edge exists already
        }
        if (neighboursOf(q).size() < 4 || neighboursOf(r).size() < 4) {
            return false;
        }
        const Vec3d pp = position(p), pq = position(q), pr = position(r), ps = position(s);
        const Vec3d oldNormal =
            crossProduct(pq - pp, pr - pp) + crossProduct(pq - pr, ps - pr);  // t and u
        const Vec3d n1 = crossProduct(pq - pp, ps - pp), n2 = crossProduct(ps - pp, pr - pp);
        if (dot(n1, oldNormal) <= 0 || dot(n2, oldNormal) <= 0) {
            return false;
        }
        const Vec3d before[2][3] = {{pp, pq, pr}, {pr, pq, ps}};
        const Vec3d after[2][3] = {{pp, pq, ps}, {pp, ps, pr}};
        const double oldMin =
            std::min(shapeOf(before[0]).minAngle(), shapeOf(before[1]).minAngle());
        const double newMin = std::min(shapeOf(after[0]).minAngle(), shapeOf(after[1]).minAngle());
        if (!(newMin > oldMin)) {
            return false;
        }
        std::uint32_t* w1 = corners(t);
        std::uint32_t* w2 = corners(u);
        w1[0] = p, w1[1] = q, w1[2] = s;
        w2[0] = p, w2[1] = s, w2[2] = r;
        auto replace = [&](std::uint32_t v, std::uint32_t drop, std::uint32_t add) {
            std::vector<std::uint32_t> list = trianglesOf(v);
            if (drop != kNone) {
                list.erase(std::remove(list.begin(), list.end(), drop), list.end());
            }
            if (add != kNone) {
                list.push_back(add);
            }
            setTrianglesOf(v, std::move(list));
        };
        replace(r, t, kNone);  // t no longer holds r
        replace(q, u, kNone);  // u no longer holds q
        replace(s, kNone, t);
        replace(p, kNone, u);
        touched = {t, u};
        ++report.flips;
        return true;
    }
};

}  // namespace

SliverCleanupReport removeSlivers(TriangleMesh& mesh, double cellSize) {
    SliverCleanupReport report;
    const std::size_t triangles = mesh.triangleCount();
    if (triangles == 0) {
        return report;
    }
    const double minEdge = kSliverEdgeFraction * cellSize;
    std::vector<char> bad(triangles, 0);
#pragma omp parallel for schedule(static)
    for (std::int64_t t = 0; t < std::int64_t(triangles); ++t) {
        const std::uint32_t* v = &mesh.indices[3 * std::size_t(t)];
        const Vec3d p[3] = {Vec3d(mesh.positions[v[0]]), Vec3d(mesh.positions[v[1]]),
                            Vec3d(mesh.positions[v[2]])};
        bad[std::size_t(t)] = isSliver(p, minEdge);
    }
    std::vector<std::uint32_t> badList;
    for (std::size_t t = 0; t < triangles; ++t) {
        if (bad[t]) {
            badList.push_back(std::uint32_t(t));
        }
    }
    report.badTriangles = badList.size();
    if (badList.empty()) {
        return report;
    }
    // Rounds: what a round leaves (an operation that would have reached past the known rings) is
    // tried again with rings around it.
    SliverCleaner cleaner(mesh, cellSize);
    std::vector<std::uint32_t> left = badList;
    for (int round = 0; round < 3 && !left.empty(); ++round) {
        cleaner.learnAround(left);
        left = cleaner.fix(left, report);
        if (!cleaner.reachedBeyond()) {
            break;
        }
    }
    report.left = left.size();
    if (cleaner.anyDead()) {
        cleaner.compact();
    }
    return report;
}

}  // namespace weir
