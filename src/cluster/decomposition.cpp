// Slab decomposition along one axis, balanced by particle counts.
#include "cluster/decomposition.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

namespace weir {

std::int64_t AxisHistogram::total() const {
    return std::accumulate(counts.begin(), counts.end(), std::int64_t(0));
}

Decomposition::Decomposition(int axis, std::vector<double> innerBorders)
    : axis_(axis), inner_(std::move(innerBorders)) {
    if (axis < 0 || axis > 2) {
        throw std::invalid_argument("decomposition axis " + std::to_string(axis) +
                                    " is not 0, 1 or 2");
    }
    for (std::size_t k = 1; k < inner_.size(); ++k) {
        if (!(inner_[k] >= inner_[k - 1])) {
            throw std::invalid_argument("decomposition borders must not decrease");
        }
    }
}

Slab Decomposition::slab(int rank) const {
    Slab s;
    s.axis = axis_;
    if (rank > 0) {
        s.lo = inner_[std::size_t(rank - 1)];
    }
    if (rank < ranks() - 1) {
        s.hi = inner_[std::size_t(rank)];
    }
    return s;
}

int Decomposition::ownerOf(double c, int fallback) const {
    if (std::isnan(c)) {
        return fallback;
    }
    // Slab r is [inner[r-1], inner[r]): the owner is the number of borders <= c.
    return int(std::upper_bound(inner_.begin(), inner_.end(), c) - inner_.begin());
}

int longestAxis(const Vec3& boxMin, const Vec3& boxMax) {
    int best = 0;
    for (int a = 1; a < 3; ++a) {
        if (boxMax[a] - boxMin[a] > boxMax[best] - boxMin[best]) {
            best = a;
        }
    }
    return best;
}

Decomposition balancedDecomposition(const AxisHistogram& histogram, int ranks) {
    if (ranks < 1) {
        throw std::invalid_argument("a decomposition needs at least one rank, not " +
                                    std::to_string(ranks));
    }
    const std::size_t bins = histogram.counts.size();
    const std::int64_t total = histogram.total();
    std::vector<double> inner;
    if (total == 0 || bins == 0) {
        const double extent = histogram.binWidth * double(std::max<std::size_t>(bins, 1));
        for (int k = 1; k < ranks; ++k) {
            inner.push_back(histogram.lo + extent * k / ranks);
        }
        return Decomposition(histogram.axis, inner);
    }
    // Border k where the running count reaches k/ranks of the total, linear within its bin.
    std::int64_t before = 0;
    std::size_t b = 0;
    for (int k = 1; k < ranks; ++k) {
        const double wanted = double(total) * k / ranks;
        while (b < bins && double(before + histogram.counts[b]) < wanted) {
            before += histogram.counts[b];
            ++b;
        }
        if (b == bins) {
            inner.push_back(histogram.lo + histogram.binWidth * double(bins));
            continue;
        }
        const double inBin = double(histogram.counts[b]);
        const double fraction = inBin > 0 ? (wanted - double(before)) / inBin : 0.0;
        inner.push_back(histogram.lo + histogram.binWidth * (double(b) + fraction));
    }
    return Decomposition(histogram.axis, inner);
}

double imbalance(const std::vector<std::int64_t>& perRank) {
    if (perRank.empty()) {
        return 1;
    }
    const std::int64_t total = std::accumulate(perRank.begin(), perRank.end(), std::int64_t(0));
    if (total == 0) {
        return 1;
    }
    const std::int64_t most = *std::max_element(perRank.begin(), perRank.end());
    return double(most) * double(perRank.size()) / double(total);
}

std::vector<std::int64_t> countsPerRank(const AxisHistogram& histogram,
                                        const Decomposition& decomposition) {
    std::vector<std::int64_t> perRank(std::size_t(decomposition.ranks()), 0);
    for (std::size_t b = 0; b < histogram.counts.size(); ++b) {
        const double centre = histogram.lo + histogram.binWidth * (double(b) + 0.5);
        perRank[std::size_t(decomposition.ownerOf(centre, 0))] += histogram.counts[b];
    }
    return perRank;
}

}  // namespace weir
