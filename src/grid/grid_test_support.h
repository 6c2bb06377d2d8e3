// Shared by the CPU and CUDA grid tests: random particles and brute-force neighbour sets.
#pragma once

#include <random>
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

}  // namespace weir::testing
