// Routing particles between ranks, and their message format: a count, then positions,
// velocities and ids as arrays.
#include "cluster/particle_routing.h"

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>

#include "physics/particle_view.h"

namespace weir {

std::vector<ParticleBatch> routeLeavers(const ParticleBatch& leaving,
                                        const Decomposition& decomposition, int self) {
    std::vector<ParticleBatch> out(std::size_t(decomposition.ranks()));
    const Slab along = decomposition.slab(self);
    for (std::size_t k = 0; k < leaving.size(); ++k) {
        const int owner = decomposition.ownerOf(along.coordinate(leaving.pos[k]), self);
        out[std::size_t(owner)].push(leaving, k);
    }
    return out;
}

std::vector<ParticleBatch> routeGhosts(const ParticleBatch& nearBorders,
                                       const Decomposition& decomposition, int self, double width) {
    std::vector<ParticleBatch> out(std::size_t(decomposition.ranks()));
    const Slab along = decomposition.slab(self);
    for (std::size_t k = 0; k < nearBorders.size(); ++k) {
        const double c = along.coordinate(nearBorders.pos[k]);
        decomposition.forEachRankNear(c, width, self, [&](int r) {
            ParticleBatch& to = out[std::size_t(r)];
            to.push(nearBorders, k);
            to.pos.back().w = kArrivingGhostMark;  // a ghost there
        });
    }
    return out;
}

namespace {

template <class T>
void put(Bytes& out, const T* data, std::size_t n) {
    const std::size_t at = out.size();
    out.resize(at + n * sizeof(T));
    if (n > 0) {
        std::memcpy(out.data() + at, data, n * sizeof(T));
    }
}

template <class T>
void take(const Bytes& in, std::size_t& at, T* data, std::size_t n) {
    if (at + n * sizeof(T) > in.size()) {
        throw std::runtime_error("a particle message from another rank is cut short (" +
                                 std::to_string(in.size()) + " bytes)");
    }
    if (n > 0) {
        std::memcpy(data, in.data() + at, n * sizeof(T));
    }
    at += n * sizeof(T);
}

}  // namespace

Bytes packParticles(const ParticleBatch& batch) {
    Bytes out;
    const std::uint64_t n = batch.size();
    out.reserve(sizeof n + n * (2 * sizeof(Real4) + sizeof(Index)));
    put(out, &n, 1);
    put(out, batch.pos.data(), n);
    put(out, batch.vel.data(), n);
    put(out, batch.id.data(), n);
    return out;
}

void unpackParticles(const Bytes& message, ParticleBatch& into) {
    if (message.empty()) {
        return;
    }
    std::size_t at = 0;
    std::uint64_t n = 0;
    take(message, at, &n, 1);
    const std::size_t first = into.size();
    into.resize(first + n);
    take(message, at, into.pos.data() + first, n);
    take(message, at, into.vel.data() + first, n);
    take(message, at, into.id.data() + first, n);
    if (at != message.size()) {
        throw std::runtime_error("a particle message from another rank has " +
                                 std::to_string(message.size() - at) + " bytes too many");
    }
}

}  // namespace weir
