// A neighbour list: for each particle the indices of the particles within the smoothing radius,
// found once by a walk of a neighbour view (the dense table's rows, the paper's cells) and then
// read by every later pass of the same positions. An iterative pressure solver makes dozens of
// passes over fixed positions a step (DFSPH's sweeps); each walk of the dense table visits about
// four candidates for every neighbour, the list only the neighbours.
//
// The list holds at most `capacity` entries a particle. A particle with more neighbours (a clump)
// is marked and walks the view it was built from instead, so nothing is ever missed; a list of
// capacity 0 holds nothing and every particle walks the view (no memory for a list).
#pragma once

#include <cstddef>
#include <cstdint>

#include "core/config.h"
#include "core/team.h"
#include "core/vec3.h"

namespace weir {

// The list's view for the stages: forEachCandidate and forEachNearPoint like the view `Inner` it
// was built from. Entry k of particle i lies at i * particleStride + k * entryStride: on a GPU
// the entries of one k are adjacent across particles (a warp's loads coalesce), on a CPU one
// particle's entries are adjacent (its thread reads one line).
template <class Inner>
struct ListedNeighbours {
    Inner inner;           // the view the list was built from (and the overflow's walk)
    const Index* entries;  // the listed neighbours
    const int* counts;     // particle i's neighbours; more than capacity: not listed
    std::int64_t particleStride, entryStride;
    int capacity;  // 0: nothing listed

    // Calls f(j) for the particles j within the radius of particle i (i itself excluded), or for
    // every candidate of the inner view where i is not listed. A team's lanes split the entries.
    template <class F, int TeamSize = 1>
    WEIR_HD void forEachCandidate(Index i, F&& f, Team<TeamSize> team = {}) const {
        const int count = capacity > 0 ? counts[i] : capacity + 1;
        if (count > capacity) {
            inner.forEachCandidate(i, f, team);
            return;
        }
        const Index* own = entries + std::int64_t(i) * particleStride;
        for (int k = team.first(); k < count; k += TeamSize) {
            f(own[std::int64_t(k) * entryStride]);
        }
    }

    // Calls f(j) for every particle j that can lie within the radius of the point p (the inner
    // view's walk: the list only knows particles' neighbours).
    template <class F>
    WEIR_HD void forEachNearPoint(const Vec3& p, F&& f) const {
        inner.forEachNearPoint(p, f);
    }
};

// Builds and holds the list on a backend (its buffers grow, never shrink).
template <class Exec>
class NeighbourList {
   public:
    template <class T>
    using Buffer = typename Exec::template Buffer<T>;

    // Entries a particle may list: a lattice at h = 2 d has 32 neighbours within h; compression,
    // splashes and a wall's corner add some. Particles past it walk the grid.
    static constexpr int kCapacity = 48;

    // Bytes a particle's list takes.
    static constexpr std::size_t bytesPerParticle() {
        return std::size_t(kCapacity) * sizeof(Index) + sizeof(int);
    }

    // Lists the neighbours within sqrt(radius2) of each of the n particles at `pos` (the positions
    // `inner` was built over), or, with `enabled` false, a view that walks `inner` only.
    template <class Inner>
    ListedNeighbours<Inner> build(Exec& exec, const Inner& inner, const Real4* pos, Index n,
                                  Real radius2, bool enabled) {
        ListedNeighbours<Inner> view{inner, nullptr, nullptr, 0, 0, 0};
        if (!enabled || n == 0) {
            return view;
        }
        const std::size_t need = std::size_t(n) * kCapacity;
        if (entries_.size() < need) {
            entries_.resize(need);
        }
        if (counts_.size() < std::size_t(n)) {
            counts_.resize(std::size_t(n));
        }
        view.entries = entries_.data();
        view.counts = counts_.data();
        view.capacity = kCapacity;
        view.particleStride = Exec::isDevice ? 1 : kCapacity;
        view.entryStride = Exec::isDevice ? std::int64_t(n) : 1;
        Index* entries = entries_.data();
        int* counts = counts_.data();
        const std::int64_t particleStride = view.particleStride, entryStride = view.entryStride;
        exec.stageBegin("neighbour list");
        exec.forEach(n, [=] WEIR_HD(Index i) {
            const Vec3 xi = pos[i].xyz();
            Index* own = entries + std::int64_t(i) * particleStride;
            int count = 0;
            inner.forEachCandidate(i, [&](Index j) {
                if (j != i && lengthSquared(xi - pos[j].xyz()) < radius2) {
                    if (count < kCapacity) {
                        own[std::int64_t(count) * entryStride] = j;
                    }
                    ++count;
                }
            });
            counts[i] = count;
        });
        exec.stageEnd("neighbour list");
        return view;
    }

    std::size_t bytesHeld() const {
        return entries_.size() * sizeof(Index) + counts_.size() * sizeof(int);
    }

   private:
    Buffer<Index> entries_;
    Buffer<int> counts_;
};

}  // namespace weir
