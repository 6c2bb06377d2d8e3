// Inflow and outflow (issue 18), written once for CPU and CUDA. An emitter is a disc or a
// rectangle in the fluid's domain that lets fluid in at a speed along its normal: its area is
// covered by a square lattice of sites one particle spacing apart, and every d / speed seconds
// (one layer spacing at that speed) each site lets in one particle, moving at the emitter's
// velocity, at the rest density. A layer due at time t_l and let in at a step's time t > t_l is
// placed speed (t - t_l) downstream of the emitter's plane, where it would have got by then, so
// the emitted lattice keeps its spacing whatever the time step. A sink is a box: every particle
// that enters it leaves the simulation.
//
// The particles live in a fixed number of slots (the reservoir, sized at set-up for the most that
// can be alive at once). A slot that holds no particle is parked (pos.w = kParkedMark): the grid
// build leaves it out of the cells and puts it after the live particles, the stages pass over it,
// and an emitter fills parked slots from the first one after the live particles. The live count,
// the next fresh id and every emitter's layer count stay on the backend: the count changes there,
// with no host round trip a step.
#pragma once

#include <cmath>
#include <vector>

#include "core/config.h"
#include "core/vec3.h"
#include "physics/particle_view.h"

namespace weir {

struct Emitter {
    Vec3 centre;          // the centre of the emitting disc or rectangle [m]
    Vec3 normal;          // unit: the direction fluid comes in along
    Real speed = 0;       // [m/s] along the normal
    Real spacing = 0;     // the particle spacing d: between sites and between layers [m]
    Real start = 0;       // [s] the first layer is let in at `start`
    Real stop = 0;        // [s] no layer is due after `stop`
    Index firstSite = 0;  // this emitter's sites in the flow's site array
    Index siteCount = 0;
    Real density = 0;  // [kg/m^3] of the emitted fluid (the rest density)

    // Layers due by `time`: one at start, one more every d / speed, none after stop.
    WEIR_HD Index layersDue(double time) const {
        if (time < double(start)) {
            return 0;
        }
        const double until = time < double(stop) ? time : double(stop);
        return Index(std::floor((until - double(start)) * double(speed) / double(spacing))) + 1;
    }
    // When layer `layer` was due.
    WEIR_HD double layerTime(Index layer) const {
        return double(start) + double(layer) * double(spacing) / double(speed);
    }
};

// A box whose particles leave the simulation.
struct Sink {
    Vec3 lo, hi;
    WEIR_HD bool contains(const Vec3& x) const {
        return x.x >= lo.x && x.x <= hi.x && x.y >= lo.y && x.y <= hi.y && x.z >= lo.z &&
               x.z <= hi.z;
    }
};

// The flow's counts, on the backend. The live particles are slots [0, live) after each grid
// build; emitted particles get ids nextId, nextId + 1, ...
struct FlowCounters {
    Index live = 0;     // live particles (the rest of the slots are parked)
    Index nextId = 0;   // the next fresh particle id
    Index emitted = 0;  // particles let in since the start
    Index removed = 0;  // particles taken out by sinks since the start
    Index refused = 0;  // particles an emitter could not let in: no parked slot left
    // Scratch of the emitter being served: its new layers' first slot and first id, how many
    // layers it lets in this step, and the layer count due (the last new layer is due - 1).
    Index firstSlot = 0, firstId = 0, newLayers = 0, due = 0;
};

// The emitters and sinks of a simulation as the scene layer derives them.
struct FlowSetup {
    std::vector<Emitter> emitters;
    std::vector<Real4> sites;  // every emitter's sites, on its plane [m] (w unused)
    std::vector<Sink> sinks;
    Index capacity = 0;  // slots: the most particles alive at once (the initial ones included)
    bool active() const { return !emitters.empty() || !sinks.empty(); }
};

// pos.w of a parked slot (physics/particle_view.h has the other marks).
constexpr Real kParkedMark = 4;
WEIR_HD inline bool isParked(const Real4& pos) { return pos.w == kParkedMark; }
WEIR_HD inline void park(Real4& pos, Real4& vel) {
    pos = Real4{0, 0, 0, kParkedMark};
    vel = Real4{0, 0, 0, 0};
}

}  // namespace weir
