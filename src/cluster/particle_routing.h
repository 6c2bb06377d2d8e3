// Which rank each particle goes to between steps, and particles packed into messages.
#pragma once

#include <vector>

#include "cluster/communicator.h"
#include "cluster/decomposition.h"
#include "solver/particles.h"

namespace weir {

// Particles that left rank `self`'s slab, sorted by their new owner (by position: a particle
// that crossed several borders in one step goes straight to the slab it is in now).
std::vector<ParticleBatch> routeLeavers(const ParticleBatch& leaving,
                                        const Decomposition& decomposition, int self);

// Ghost copies (position w = 1) of rank `self`'s particles near its borders, for every other
// rank whose slab widened by `width` holds them (several ranks where slabs are thinner than
// `width`, none for a particle deep inside).
std::vector<ParticleBatch> routeGhosts(const ParticleBatch& nearBorders,
                                       const Decomposition& decomposition, int self, double width);

Bytes packParticles(const ParticleBatch& batch);
// Appends the particles of `message` to `into`; throws on a malformed message.
void unpackParticles(const Bytes& message, ParticleBatch& into);

}  // namespace weir
