// Periodic boundaries (container.periodic) by ghost copies: before each step, every particle
// within kPeriodicHaloRadii smoothing radii of a periodic face gets a copy shifted by the
// container's length to beyond the opposite face, marked as a ghost (physics/particle_view.h), so
// the stages find their neighbours across the face through the ordinary neighbour search, in every
// mode, with no change to any pair term; after the step the copies are dropped, and the
// integration has wrapped the particles that left through a face (physics/collision.h). The
// ghosts are the distributed runs' ghosts (cluster/): the stages already leave them unmoved and
// uncounted. Copies of copies give the edges and corners where two or three periodic axes meet.
#pragma once

#include <sstream>

#include "core/check.h"
#include "core/config.h"
#include "grid/cell_id.h"
#include "physics/particle_view.h"
#include "physics/sph_params.h"
#include "solver/particle_store.h"

namespace weir {

// How far past a periodic face the copies reach, in smoothing radii h. A ghost within h of the
// face lends its density, velocity and pressure to the particles inside, so its own sums must be
// whole: its neighbours reach 2h. delta-SPH's ghosts also take their new velocity from their own
// force pass, and that sees boundary particles up to 2h whose extrapolated state sums the fluid
// up to 3h; the boundary particles' periodic images (scene/periodic_walls.h) reach as far.
constexpr int kPeriodicHaloRadii = 3;

// Throws SimulationError unless every periodic axis is at least two smoothing radii long (a
// particle would otherwise meet its own image within h): the message names container.periodic.
inline void checkPeriodicLengths(const SphParams& params) {
    static const char* const kAxis[3] = {"x", "y", "z"};
    for (int a = 0; a < 3; ++a) {
        const double length = double(params.boxMax[a]) - double(params.boxMin[a]);
        const double h = double(params.kernel.h);
        if (isPeriodic(params, a) && length < 2 * h * (1 - 1e-6)) {  // equal, less rounding
            std::ostringstream msg;
            msg << "container.periodic: the container is " << length << " m long along " << kAxis[a]
                << ", but a periodic axis needs at least two smoothing radii (2 h = " << 2 * h
                << " m); make the container longer along " << kAxis[a]
                << " or the particles finer, or set that axis false";
            throw SimulationError(msg.str());
        }
    }
}

// The grid of h-wide cells over the container, widened on each periodic axis to hold the ghosts
// (cells of the same size, in the same places).
inline GridSpec periodicGrid(GridSpec grid, const SphParams& params) {
    const int margin = kPeriodicHaloRadii + 1;  // + 1: cells of at least h
    for (int a = 0; a < 3; ++a) {
        if (isPeriodic(params, a)) {
            grid.origin[a] -= Real(margin) * grid.cellSize;
            grid.dims[a] += 2 * margin;
        }
    }
    return grid;
}

template <class Exec>
class PeriodicGhosts {
   public:
    explicit PeriodicGhosts(const SphParams& params)
        : params_(params), width_(Real(kPeriodicHaloRadii) * params.kernel.h) {}

    bool active() const { return params_.periodicAxes != 0; }

    // Appends the ghost copies (arriving: the next reorder makes them this step's ghosts). The
    // owned particles and the ghosts that arrived from other ranks are copied; copies made for
    // one axis are copied again for the next.
    void add(Exec& exec, ParticleStore<Exec>& store) {
        for (int a = 0; a < 3; ++a) {
            if (!isPeriodic(params_, a)) {
                continue;
            }
            const Index before = store.count();  // copies of this axis are not copied back
            addSide(exec, store, a, before, false);
            addSide(exec, store, a, before, true);
        }
    }

    // Drops every ghost (the store's count is the owned particles' again).
    void drop(Exec& exec, ParticleStore<Exec>& store) {
        if (store.ghostCount() > 0) {
            store.dropNow(exec);
        }
    }

    // (public only because CUDA lambdas need a public enclosing function)
    // Copies the particles among the first `among` within width_ of the face of axis a (the upper
    // one if `upper`) to beyond the opposite face.
    void addSide(Exec& exec, ParticleStore<Exec>& store, int a, Index among, bool upper) {
        const Real lo = params_.boxMin[a], hi = params_.boxMax[a];
        const Real length = hi - lo;
        const Real bound = upper ? hi - width_ : lo + width_;
        const Real shift = upper ? -length : length;
        const Real4* pos = store.pos();
        Index* flag = store.flagScratch(std::size_t(store.count()));
        exec.forEach(store.count(), [=] WEIR_HD(Index i) {
            const Real4 p = pos[i];
            const bool copied = p.w == Real(0) || p.w == kArrivingGhostMark;
            const Real x = a == 0 ? p.x : (a == 1 ? p.y : p.z);
            const bool near = upper ? x >= bound : x < bound;
            flag[i] = i < among && copied && near ? 1 : 0;
        });
        const Index count = store.stageGhosts(exec, flag, 0);
        if (count == 0) {
            return;
        }
        const ParticleSpans from = store.staged();
        const ParticleSpans to = store.appendSpace(exec, std::size_t(count));
        exec.forEach(count, [=] WEIR_HD(Index k) {
            Real4 p = from.pos[k];
            (a == 0 ? p.x : (a == 1 ? p.y : p.z)) += shift;
            to.pos[k] = p;
            to.vel[k] = from.vel[k];
            to.id[k] = from.id[k];
        });
    }

   private:
    SphParams params_;
    Real width_;
};

}  // namespace weir
