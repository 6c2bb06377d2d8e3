// Eq. 2: the density of a particle, the fluid's poly6 sum plus what the walls add; shared by
// every pressure solver.
#pragma once

#include "core/config.h"
#include "core/vec3.h"
#include "physics/boundary.h"
#include "physics/kernels.h"
#include "physics/particle_view.h"
#include "physics/sph_params.h"
#include "physics/wall_weight.h"

namespace weir {

// Density of particle i: m sum_j W_ij over its candidates (poly6), plus the walls' share (the
// container planes' wall weight, or the boundary particles').
template <class Neighbours>
WEIR_HD inline Real densityAt(Index i, const ParticleView& pv, const Neighbours& nb,
                              const SphParams& params) {
    const Vec3 xi = pv.position(i);
    Real sum = 0;
    nb.forEachCandidate(
        i, [&](Index j) { sum += poly6(params.kernel, lengthSquared(xi - pv.position(j))); });
    const Real walls = params.walls == WallKind::Simple
                           ? wallDensity(params.wallWeight, params.boxMin, params.boxMax,
                                         params.restDensity, xi, params.periodicAxes)
                           : boundaryDensity(pv.boundary, params.kernel, xi);
    return params.mass * sum + walls;
}

}  // namespace weir
