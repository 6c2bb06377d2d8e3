// One rank's share of the domain in a distributed run: the particles whose coordinate along
// `axis` lies in [lo, hi). The first and last slabs reach to -inf and +inf, so no particle is
// ever outside every slab. Host and device code (the solver selects particles by it).
#pragma once

#include <cstddef>
#include <limits>
#include <vector>

#include "core/config.h"
#include "core/vec3.h"

namespace weir {

struct Slab {
    int axis = 0;
    double lo = -std::numeric_limits<double>::infinity();
    double hi = std::numeric_limits<double>::infinity();

    WEIR_HD Real coordinate(const Real4& p) const {
        return axis == 0 ? p.x : (axis == 1 ? p.y : p.z);
    }
    WEIR_HD double coordinate(const Vec3d& p) const {
        return axis == 0 ? p.x : (axis == 1 ? p.y : p.z);
    }
    WEIR_HD bool contains(double c) const { return c >= lo && c < hi; }
    // Within `width` inside either border (a halo other ranks need), for a coordinate inside.
    WEIR_HD bool nearBorder(double c, double width) const {
        return c < lo + width || c >= hi - width;
    }
    bool everything() const {
        return lo == -std::numeric_limits<double>::infinity() &&
               hi == std::numeric_limits<double>::infinity();
    }
};

// Particles in a backend's memory (device pointers on CUDA), on their way between ranks.
struct ParticleSpans {
    Real4* pos = nullptr;
    Real4* vel = nullptr;
    Index* id = nullptr;
};

// Particles on their way between ranks, on the host: positions (w = 1 marks a ghost copy),
// velocities with density in w, and global ids (the index in the single-rank run's order).
struct ParticleBatch {
    std::vector<Real4> pos, vel;
    std::vector<Index> id;

    std::size_t size() const { return id.size(); }
    void clear() {
        pos.clear();
        vel.clear();
        id.clear();
    }
    void resize(std::size_t n) {
        pos.resize(n);
        vel.resize(n);
        id.resize(n);
    }
    void push(const ParticleBatch& from, std::size_t k) {
        pos.push_back(from.pos[k]);
        vel.push_back(from.vel[k]);
        id.push_back(from.id[k]);
    }
};

}  // namespace weir
