// RankPart over a simulation on backend Exec: the exchanges as selections, compactions and
// appends on its particle store. Instantiated in rank_part_cpu.cpp and rank_part_cuda.cu.
#pragma once

#include <memory>
#include <utility>

#include "cluster/rank_part.h"
#include "core/atomics.h"
#include "solver/sph_simulation.h"

namespace weir {

template <class Exec>
class RankPartOn final : public RankPart {
   public:
    template <class T>
    using Buffer = typename Exec::template Buffer<T>;

    RankPartOn(NeighbourMode mode, SimulationSetup setup) : sim_(mode, std::move(setup)) {}

    Simulation& simulation() override { return sim_; }

    void takeLeavers(const Slab& share, ParticleBatch& leaving) override {
        ParticleStore<Exec>& store = sim_.store();
        Exec& exec = sim_.exec();
        const Index n = store.count();
        Index* leave = store.flagScratch(std::size_t(n));
        const Real4* pos = store.pos();
        exec.forEach(n, [=] WEIR_HD(Index i) {
            leave[i] = !isGhost(pos[i]) && !share.contains(share.coordinate(pos[i])) ? 1 : 0;
        });
        const Index left = store.gather(exec, leave, leaving);
        store.markRemoved(exec, leave, left);
        if (!sim_.search().dropsWhileReordering()) {
            store.dropNow(exec);  // the dense table drops them in the next grid build instead
        }
    }

    void copyBorderParticles(const Slab& share, double width, ParticleBatch& out) override {
        ParticleStore<Exec>& store = sim_.store();
        const Index n = store.count();
        Index* near = store.flagScratch(std::size_t(n));
        const Real4* pos = store.pos();
        sim_.exec().forEach(n, [=] WEIR_HD(Index i) {
            const Real c = share.coordinate(pos[i]);
            near[i] = !isGhost(pos[i]) && share.contains(c) && share.nearBorder(c, width) ? 1 : 0;
        });
        store.gather(sim_.exec(), near, out);
    }

    void append(const ParticleBatch& batch) override { sim_.store().append(sim_.exec(), batch); }

    void downloadOwned(ParticleBatch& out) override {
        ParticleStore<Exec>& store = sim_.store();
        const Index n = store.count();
        Index* owned = store.flagScratch(std::size_t(n));
        const Real4* pos = store.pos();
        sim_.exec().forEach(n, [=] WEIR_HD(Index i) { owned[i] = isGhost(pos[i]) ? 0 : 1; });
        store.gather(sim_.exec(), owned, out);
    }

    void histogram(int axis, double lo, double binWidth, std::vector<Index>& counts) override {
        Exec& exec = sim_.exec();
        const Index bins = Index(counts.size());
        binCounts_.resize(std::size_t(bins));  // kept: no allocation per rebalance check
        Index* b = binCounts_.data();
        exec.forEach(bins, [=] WEIR_HD(Index k) { b[k] = 0; });
        const Real4* pos = sim_.store().pos();
        const Slab along{axis, 0, 0};
        const double inverse = 1.0 / binWidth;
        exec.forEach(sim_.store().count(), [=] WEIR_HD(Index i) {
            if (!isGhost(pos[i])) {
                const double at = (double(along.coordinate(pos[i])) - lo) * inverse;
                const Index k = at < 0 ? 0 : (at >= double(bins) ? bins - 1 : Index(at));
                atomicFetchAdd(&b[k], Index(1));
            }
        });
        std::vector<Index> here(static_cast<std::size_t>(bins));
        exec.download(binCounts_, here.data(), here.size());
        for (std::size_t k = 0; k < counts.size(); ++k) {
            counts[k] += here[k];
        }
    }

    ParticleSpans stageWindows(const Slab& share, const std::vector<Slab>& windows,
                               std::vector<std::int64_t>& counts) override {
        ParticleStore<Exec>& store = sim_.store();
        counts.assign(windows.size(), 0);
        Index staged = 0;
        for (std::size_t k = 0; k < windows.size(); ++k) {
            const Index n = store.count();
            Index* inside = store.flagScratch(std::size_t(n));
            const Real4* pos = store.pos();
            const Slab window = windows[k];
            sim_.exec().forEach(n, [=] WEIR_HD(Index i) {
                const Real c = window.coordinate(pos[i]);
                inside[i] = !isGhost(pos[i]) && share.contains(c) && window.contains(c) ? 1 : 0;
            });
            const Index count = store.stageGhosts(sim_.exec(), inside, staged);
            counts[k] = count;
            staged += count;
        }
        return store.staged();
    }

    ParticleSpans appendSpace(std::size_t count) override {
        return sim_.store().appendSpace(sim_.exec(), count);
    }

    void restrictGrid(const Slab& share, double margin) override {
        sim_.search().restrictTo(share, margin);
    }

    void* deviceStream() override {
        if constexpr (Exec::isDevice) {
            return static_cast<void*>(sim_.exec().stream());
        } else {
            return nullptr;
        }
    }

    StepClock clock() override { return sim_.clock(); }
    StepClock clockAndFault(FaultRecord& fault) override { return sim_.clockAndFault(fault); }
    void setClock(const StepClock& clock) override { sim_.setClock(clock); }
    void stepOnce() override { sim_.stepOnce(); }

   private:
    SphSimulation<Exec> sim_;
    Buffer<Index> binCounts_;  // the histogram along the decomposition axis
};

}  // namespace weir
