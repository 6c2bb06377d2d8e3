// A backend's particle arrays (cell order) to a host frame in id order, on all cores.
#pragma once

#include <cstddef>

#include "core/config.h"
#include "core/vec3.h"
#include "physics/sph_params.h"
#include "solver/particles.h"

namespace weir {

// out (resized to n) gets particle i's position, velocity and density (vel[i].w) at out[ids[i]],
// with the pressure the equation of state gives its density; ids is a permutation of 0..n-1.
// Host memory only. Runs on all cores (OpenMP): at a frame of a GPU run they are idle, and the
// stepping thread waits for it (bench/NOTES.md F2: 1M particles, 11-12 ms serial, 6 on 2 cores).
void scatterToHostFrame(const Index* ids, const Real4* pos, const Real4* vel, std::size_t n,
                        const SphParams& params, HostParticles& out);

// The same for particles whose ids are unique but not 0 .. n - 1 (a run with emitters or sinks):
// out gets them in increasing id order, their ids in out.id.
void sortToHostFrame(const Index* ids, const Real4* pos, const Real4* vel, std::size_t n,
                     const SphParams& params, HostParticles& out);

}  // namespace weir
