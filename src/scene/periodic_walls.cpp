// Boundary particles of a container with periodic axes.
#include "scene/periodic_walls.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "solver/periodic_ghosts.h"

namespace weir {

namespace {

// Coordinates of the samples along one axis of a wall sheet, and which lie on the sheet's
// border (shared with the sheet of that axis).
struct AxisSamples {
    std::vector<double> at;
    std::vector<bool> border;
};

AxisSamples axisSamples(const Scene& scene, int axis, double d, double depth, double reach) {
    AxisSamples s;
    const double lo = scene.container.min[axis], hi = scene.container.max[axis];
    if (scene.periodic[std::size_t(axis)]) {
        // A whole number of steps over the period, images as far as `reach` past both faces.
        const long n = std::max(1L, long(std::lround((hi - lo) / d)));
        const double step = (hi - lo) / double(n);
        const long extra = long(std::ceil(reach / step));
        for (long i = -extra; i < n + extra; ++i) {
            s.at.push_back(lo + (double(i) + 0.5) * step);
            s.border.push_back(false);
        }
        return s;
    }
    // As sampleBoundary: the box widened by the layer's depth, ends included.
    const double from = lo - depth, size = hi - lo + 2 * depth;
    const long n = std::max(1L, long(std::lround(size / d)));
    for (long i = 0; i <= n; ++i) {
        s.at.push_back(from + double(i) * size / double(n));
        s.border.push_back(i == 0 || i == n);
    }
    return s;
}

}  // namespace

BoundarySamples samplePeriodicBoundary(const Scene& scene, double d, double h, int layers) {
    BoundarySamples all = sampleBoundary(scene, d, h, layers);
    if (!scene.periodic[0] && !scene.periodic[1] && !scene.periodic[2]) {
        return all;
    }
    BoundarySamples out;
    for (std::size_t i = 0; i < all.size(); ++i) {
        if (all.faces[i] < 0) {  // obstacles kept; the container's faces sampled below
            out.points.push_back(all.points[i]);
            out.faces.push_back(-1);
        }
    }
    const double reach = kPeriodicHaloRadii * h;
    for (int layer = 0; layer < layers; ++layer) {
        const double depth = (layer + 0.5) * d;
        AxisSamples along[3];
        for (int a = 0; a < 3; ++a) {
            along[a] = axisSamples(scene, a, d, depth, reach);
        }
        for (int a = 0; a < 3; ++a) {
            if (scene.periodic[std::size_t(a)]) {
                continue;  // no walls on a periodic axis
            }
            const int b = (a + 1) % 3, c = (a + 2) % 3;
            for (int side = 0; side < 2; ++side) {
                const double wall =
                    side == 0 ? scene.container.min[a] - depth : scene.container.max[a] + depth;
                for (std::size_t i = 0; i < along[b].at.size(); ++i) {
                    for (std::size_t j = 0; j < along[c].at.size(); ++j) {
                        // An edge shared with the sheet of a lower axis belongs to that sheet
                        // (its first face, as sampleBoundary names it).
                        if ((b < a && along[b].border[i]) || (c < a && along[c].border[j])) {
                            continue;
                        }
                        Vec3d p;
                        p[a] = wall;
                        p[b] = along[b].at[i];
                        p[c] = along[c].at[j];
                        out.points.push_back(p);
                        out.faces.push_back(2 * a + side);
                    }
                }
            }
        }
    }
    return out;
}

}  // namespace weir
