// The emitters and sinks of a simulation (physics/emitter.h) on its backend. Before each step,
// every sink parks the particles inside it, then every emitter lets in the layers that have come
// due since its last, into the parked slots after the live particles. The grid build that
// follows leaves the parked slots out and counts the live particles (solver/neighbour_search.h),
// so the count changes on the backend alone: a fixed sequence of launches a step, no host round
// trip, and the step can still be replayed as a CUDA graph.
#pragma once

#include <vector>

#include "core/atomics.h"
#include "core/check.h"
#include "core/config.h"
#include "physics/emitter.h"
#include "physics/time_step.h"
#include "solver/particle_store.h"

namespace weir {

template <class Exec>
class InflowOutflow {
   public:
    template <class T>
    using Buffer = typename Exec::template Buffer<T>;

    bool active() const { return active_; }

    // The emitters, sinks and counters, uploaded once; the store grows to the reservoir's
    // capacity, its particles keeping ids 0 .. n - 1 (emitted ones get the ids after).
    void upload(Exec& exec, const FlowSetup& setup, ParticleStore<Exec>& store) {
        active_ = setup.active();
        if (!active_) {
            return;
        }
        const Index initial = store.count();
        capacity_ = setup.capacity > initial ? setup.capacity : initial;
        emitters_ = setup.emitters;
        exec.upload(emitterBuffer_, setup.emitters.data(), setup.emitters.size());
        exec.upload(sites_, setup.sites.data(), setup.sites.size());
        exec.upload(sinks_, setup.sinks.data(), setup.sinks.size());
        std::vector<Index> none(setup.emitters.size(), 0);
        exec.upload(layersDone_, none.data(), none.size());
        FlowCounters counters;
        counters.live = initial;
        counters.nextId = initial;
        exec.upload(counters_, &counters, 1);
        sinkCount_ = int(setup.sinks.size());
        store.holdReservoir(exec, capacity_, &counters_.data()->live);
    }

    Index capacity() const { return capacity_; }
    FlowCounters counters(Exec& exec) const { return exec.readOne(counters_, 0); }

    // Sinks, then emitters, at the time the clock shows before this step.
    void apply(Exec& exec, ParticleStore<Exec>& store, const StepClock* clock) {
        exec.stageBegin("flow");
        FlowCounters* counters = counters_.data();
        if (sinkCount_ > 0) {
            Real4 *pos = store.pos(), *vel = store.vel();
            const Sink* sinks = sinks_.data();
            const int sinkCount = sinkCount_;
            exec.forEach(store.count(), [=] WEIR_HD(Index i) {
                if (isGhost(pos[i])) {
                    return;  // parked (or not this run's)
                }
                const Vec3 x = pos[i].xyz();
                for (int k = 0; k < sinkCount; ++k) {
                    if (sinks[k].contains(x)) {
                        park(pos[i], vel[i]);
                        atomicFetchAdd(&counters->removed, Index(1));
                        return;
                    }
                }
            });
        }
        const Index capacity = capacity_;
        for (std::size_t k = 0; k < emitters_.size(); ++k) {
            const Emitter* emitter = emitterBuffer_.data() + k;
            Index* done = layersDone_.data() + k;
            exec.forEach(1, [=] WEIR_HD(Index) {
                FlowCounters& c = *counters;
                const Index due = emitter->layersDue(clock->time);
                const Index wanted = due > *done ? due - *done : 0;
                const Index sites = emitter->siteCount;
                const Index room = sites > 0 ? (capacity - c.live) / sites : 0;
                const Index layers = wanted < room ? wanted : room;
                c.refused += (wanted - layers) * sites;
                c.firstSlot = c.live;
                c.firstId = c.nextId;
                c.newLayers = layers;
                c.due = due;
                c.live += c.newLayers * sites;
                c.nextId += c.newLayers * sites;
                c.emitted += c.newLayers * sites;
                *done = due > *done ? due : *done;
            });
            const Real4* sites = sites_.data() + emitters_[k].firstSite;
            Real4 *pos = store.pos(), *vel = store.vel();
            Index* id = store.id();
            exec.forEach(emitters_[k].siteCount, [=] WEIR_HD(Index s) {
                const FlowCounters& c = *counters;
                const Emitter e = *emitter;
                for (Index l = 0; l < c.newLayers; ++l) {
                    // Layer due - newLayers + l, placed where it has got to since it was due.
                    const Index layer = c.due - c.newLayers + l;
                    const Real travelled =
                        Real(double(e.speed) * (clock->time - e.layerTime(layer)));
                    const Index offset = l * e.siteCount + s;
                    const Index slot = c.firstSlot + offset;
                    pos[slot] = Real4::from(sites[s].xyz() + e.normal * travelled);
                    vel[slot] = Real4::from(e.normal * e.speed, e.density);
                    id[slot] = c.firstId + offset;
                }
            });
        }
        exec.stageEnd("flow");
    }

    std::size_t bytesHeld() const {
        return sites_.size() * sizeof(Real4) + sinks_.size() * sizeof(Sink) +
               emitterBuffer_.size() * sizeof(Emitter) + layersDone_.size() * sizeof(Index);
    }

   private:
    bool active_ = false;
    Index capacity_ = 0;
    int sinkCount_ = 0;
    std::vector<Emitter> emitters_;  // on the host too: their site ranges size the launches
    Buffer<Emitter> emitterBuffer_;
    Buffer<Real4> sites_;
    Buffer<Sink> sinks_;
    Buffer<Index> layersDone_;
    Buffer<FlowCounters> counters_;
};

}  // namespace weir
