// Shared by the CPU and CUDA grid tests: random particles, brute-force neighbour sets, the
// order a stable sort gives.
#pragma once

#include <algorithm>
#include <random>
#include <utility>
#include <vector>

#include "core/config.h"
#include "core/vec3.h"

namespace weir::testing {

struct Cloud {
    std::vector<Real> x, y, z;

    std::vector<Real4> packed() const {
        std::vector<Real4> pos(x.size());
        for (std::size_t i = 0; i < x.size(); ++i) {
            pos[i] = {x[i], y[i], z[i], 0};
        }
        return pos;
    }
};

// n uniform random points in [0, size)^3, a few of them exactly on the far walls.
inline Cloud randomCloud(int n, Real size, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<Real> u(0, size);
    Cloud c;
    for (int i = 0; i < n; ++i) {
        c.x.push_back(i % 97 == 0 ? size : u(rng));
        c.y.push_back(u(rng));
        c.z.push_back(i % 89 == 0 ? Real(0) : u(rng));
    }
    return c;
}

// Sorted list of j != i with |x_i - x_j| < h, by O(N^2) search.
inline std::vector<std::vector<int>> bruteNeighbourSets(const Cloud& c, Real h) {
    int n = int(c.x.size());
    std::vector<std::vector<int>> sets(n);
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
            Real dx = c.x[i] - c.x[j], dy = c.y[i] - c.y[j], dz = c.z[i] - c.z[j];
            if (j != i && dx * dx + dy * dy + dz * dz < h * h) {
                sets[i].push_back(j);
            }
        }
    }
    return sets;
}

// (key, index) pairs in the order of std::stable_sort by key: what sortPairs must give.
template <class Key>
std::vector<std::pair<Key, Index>> stableSorted(const std::vector<Key>& keys) {
    std::vector<std::pair<Key, Index>> pairs(keys.size());
    for (std::size_t i = 0; i < keys.size(); ++i) {
        pairs[i] = {keys[i], Index(i)};
    }
    std::stable_sort(pairs.begin(), pairs.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    return pairs;
}

// Clumps of particles along a box long on one axis (a few hundred particles in 1250 cells of h):
// around the 1024th cell, where a 10-bit coordinate would wrap, at both ends and scattered.
inline Cloud clumpsAlong(int longAxis, Real length, Real width, Real h, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<Real> u(0, 1);
    const Real centres[] = {Real(0),          3 * h,    1000 * h, 1023 * h,
                            Real(1023.9) * h, 1024 * h, 1025 * h, Real(0.5) * length,
                            length - 2 * h,   length};
    Cloud cloud;
    std::vector<Real>* axes[3] = {&cloud.x, &cloud.y, &cloud.z};
    for (Real centre : centres) {
        for (int k = 0; k < 60; ++k) {
            for (int a = 0; a < 3; ++a) {
                // Within 1.5 h of the centre along the long axis, anywhere across the others.
                Real v = a == longAxis
                             ? std::clamp(centre + 3 * h * (u(rng) - Real(0.5)), Real(0), length)
                             : width * u(rng);
                axes[a]->push_back(v);
            }
        }
    }
    return cloud;
}

}  // namespace weir::testing
