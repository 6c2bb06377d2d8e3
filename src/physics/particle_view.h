// The particles as the per-particle stages see them: structure-of-arrays views in the grid's
// cell order, and the marks that tell a ghost copy from an owned particle.
#pragma once

#include "core/config.h"
#include "core/vec3.h"
#include "physics/boundary.h"

namespace weir {

// Vector attributes are padded to four components: one aligned 16-byte load per neighbour on the
// GPU. The density rides in the velocity's fourth component, so the force loop reads two vectors
// per neighbour; the density stage reads only positions, so writing it there races with nothing.
struct ParticleView {
    Real4* pos;          // x, y, z, mark (isGhost)
    Real4* vel;          // vx, vy, vz, density
    Real4* acc;          // ax, ay, az, unused (methods that keep an acceleration)
    Real* pressureTerm;  // what the force stage needs of each particle's pressure (the method's)
    Index count;
    BoundaryView boundary;  // static wall particles (physics/boundary.h); empty: none

    WEIR_HD Real density(Index i) const { return vel[i].w; }
    WEIR_HD Vec3 position(Index i) const { return pos[i].xyz(); }
    WEIR_HD Vec3 velocity(Index i) const { return vel[i].xyz(); }
};

// pos.w marks a particle that is not simply owned. A ghost is a copy of another rank's particle
// near this rank's border (distributed runs, cluster/): it lends its density and velocity to the
// owned particles' sums but is neither moved, nor checked, nor counted in the time step here; its
// owner does that. 1: a ghost of this step; 2: one just arrived for the next step (the next
// reorder turns it into 1 and drops the 1s of the step before); 3: an owned particle to be dropped
// at the next reorder (it left for another rank).
constexpr Real kGhostMark = 1;
constexpr Real kArrivingGhostMark = 2;
constexpr Real kRemovedMark = 3;
WEIR_HD inline bool isGhost(const Real4& pos) { return pos.w != Real(0); }

}  // namespace weir
