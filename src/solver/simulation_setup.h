// Everything a simulation needs to start, as the scene layer derives it (scene/setup.h):
// parameters, grid, walls, obstacles, and the initial particles, given on the host or placed by
// a seeder on the simulation's own backend (a billion particles are seeded on the GPU itself).
#pragma once

#include <algorithm>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/config.h"
#include "core/slab.h"
#include "grid/cell_id.h"
#include "physics/boundary.h"
#include "physics/collision.h"
#include "physics/emitter.h"
#include "physics/rigid_body.h"
#include "physics/sph_params.h"
#include "solver/particles.h"

namespace weir {

class CpuExec;
class CudaExec;
template <class Exec>
class ParticleStore;

// Places a simulation's initial particles on its backend, in a fixed order that gives each its
// id. The scene layer implements it (scene/lattice_seeder.h); the solver only calls it.
class ParticleSeeder {
   public:
    virtual ~ParticleSeeder() = default;
    // Particles of the whole seeding.
    virtual std::int64_t count() const = 0;
    // Particles this seeder places, about (all of them, or a slab's share), for memory checks.
    virtual std::int64_t expectedCount() const = 0;
    // The largest initial speed, m/s (the first time step sees it).
    virtual double maxSpeed() const = 0;
    // The same seeding restricted to the particles inside `share` (a rank of a distributed run:
    // ids stay those of the whole seeding); `expected`: about how many that is.
    virtual std::shared_ptr<const ParticleSeeder> within(const Slab& share,
                                                         std::int64_t expected) const = 0;
    // Calls visit(coordinate along axis, weight) for a sample of the particles, each standing
    // for `weight` of them (a distributed run's first decomposition).
    virtual void sample(int axis, const std::function<void(double, std::int64_t)>& visit) const = 0;
    // Fills the store (sized by allocate()) on the backend.
    virtual void seed(CpuExec& exec, ParticleStore<CpuExec>& store) const = 0;
    virtual void seed(CudaExec& exec, ParticleStore<CudaExec>& store) const = 0;
};

struct SimulationSetup {
    SphParams params;
    GridSpec grid;       // the container in cells of the smoothing radius h
    std::string method;  // the pressure solver (solver/methods.h); empty: the default
    std::vector<ObstacleBox> obstacleBoxes;
    std::vector<ObstacleSphere> obstacleSpheres;
    BoundaryParticles boundary;  // walls.model "particles": static wall particles and their grid
    RigidBodySetup bodies;       // rigid bodies (their particles join the walls' each step)
    FlowSetup flow;              // emitters and sinks (the particle count changes on the backend)
    HostParticles particles;     // the initial particles, on the host; or:
    std::shared_ptr<const ParticleSeeder> seeder;  // ... placed by a seeder on the backend
    // Global ids of `particles` (a distributed run's share); empty: 0 .. n - 1.
    std::vector<Index> particleIds;

    std::int64_t particleCount() const {
        return particles.size() > 0 ? std::int64_t(particles.size())
                                    : (seeder ? seeder->count() : 0);
    }
    // Particle slots: the particles, or the reservoir of a run with emitters or sinks.
    std::int64_t slotCount() const {
        return std::max<std::int64_t>(particleCount(), flow.active() ? flow.capacity : 0);
    }
    // Particle slots this process will hold: all of them, or its share's.
    std::int64_t countHere() const {
        const std::int64_t held = particles.size() > 0 ? std::int64_t(particles.size())
                                                       : (seeder ? seeder->expectedCount() : 0);
        return std::max<std::int64_t>(held, flow.active() ? flow.capacity : 0);
    }
};

}  // namespace weir
