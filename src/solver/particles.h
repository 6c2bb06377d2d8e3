// Particle data on the host: structure of arrays as written to frames, and the packed batches
// that travel between ranks.
#pragma once

#include <cstddef>
#include <vector>

#include "core/config.h"
#include "core/vec3.h"

namespace weir {

// A rigid body's pose at a frame (physics/rigid_body.h), as frames.json records it.
struct BodyPose {
    Vec3d position;                        // centre of mass [m]
    double orientation[4] = {0, 0, 0, 1};  // quaternion x, y, z, w: the body's frame to the world
    Vec3d velocity, angularVelocity;       // [m/s], [rad/s]
};

struct HostParticles {
    std::vector<Real> x, y, z;     // position [m]
    std::vector<Real> vx, vy, vz;  // velocity [m/s]
    std::vector<Real> rho;         // density [kg/m^3]
    std::vector<Real> p;           // pressure [Pa]
    // Each particle's id, in increasing order, where the ids are not 0 .. n - 1 (a run with
    // emitters or sinks: physics/emitter.h); empty: particle k has id k.
    std::vector<Index> id;
    std::vector<BodyPose> bodies;  // the rigid bodies at this frame, in the scene's order

    std::size_t size() const { return x.size(); }
    // Particle k's id.
    Index idOf(std::size_t k) const { return id.empty() ? Index(k) : id[k]; }
    void resize(std::size_t n) {
        for (auto* a : {&x, &y, &z, &vx, &vy, &vz, &rho, &p}) {
            a->resize(n);
        }
        if (!id.empty()) {
            id.resize(n);
        }
    }
    void push(const Vec3d& pos, const Vec3d& vel) {
        x.push_back(Real(pos.x));
        y.push_back(Real(pos.y));
        z.push_back(Real(pos.z));
        vx.push_back(Real(vel.x));
        vy.push_back(Real(vel.y));
        vz.push_back(Real(vel.z));
        rho.push_back(0);
        p.push_back(0);
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
