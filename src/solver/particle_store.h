// The particles of one simulation in one backend's memory: position, velocity (density in its
// fourth component) and id arrays, the scratch they are reordered into, and the operations on
// them that every pressure solver and the distributed runs share: reorder into cell order,
// compaction, gathering to the host, growth and appending. A pressure solver's own per-particle
// arrays live with the solver (solver/pressure_solver.h).
#pragma once

#include <cstddef>
#include <vector>

#include "core/check.h"
#include "core/config.h"
#include "core/vec3.h"
#include "physics/emitter.h"
#include "physics/eos.h"
#include "physics/particle_view.h"
#include "solver/host_frame.h"
#include "solver/particles.h"

namespace weir {

template <class Exec>
class ParticleStore {
   public:
    template <class T>
    using Buffer = typename Exec::template Buffer<T>;

    // Moves particle `from`'s data to place `to` of the reorder scratch, turning an arriving ghost
    // into this step's (physics/particle_view.h). Passed by value into the grid build's kernels.
    struct Placer {
        const Real4 *pos, *vel;
        const Index* id;
        Real4 *newPos, *newVel;
        Index* newId;
        WEIR_HD void operator()(Index from, Index to) const {
            Real4 p = pos[from];
            p.w = p.w == kArrivingGhostMark ? kGhostMark : p.w;
            newPos[to] = p;
            newVel[to] = vel[from];
            newId[to] = id[from];
        }
    };
    // Whether a reorder that can drop particles drops particle i: last step's ghosts and the
    // particles marked removed, when any are held (a single run's never are), and parked slots
    // when the store holds a reservoir (physics/emitter.h).
    struct Dropper {
        const Real4* pos;
        bool active;
        WEIR_HD bool operator()(Index i) const {
            return active &&
                   (pos[i].w == kGhostMark || pos[i].w == kRemovedMark || pos[i].w == kParkedMark);
        }
    };

    Index count() const { return n_; }
    Real4* pos() { return pos_.data(); }
    Real4* vel() { return vel_.data(); }
    Index* id() { return id_.data(); }
    const Real4* pos() const { return pos_.data(); }
    const Real4* vel() const { return vel_.data(); }
    const Index* id() const { return id_.data(); }
    // The arrays a reorder or an integration writes into, swapped in by commit*().
    Real4* nextPos() { return sortedPos_.data(); }
    Real4* nextVel() { return sortedVel_.data(); }

    // Takes n particles from the host; ids: their global ids (empty: 0 .. n - 1).
    void upload(Exec& exec, const HostParticles& host, const std::vector<Index>& ids) {
        n_ = Index(host.size());
        std::vector<Real4> pos(static_cast<std::size_t>(n_)), vel(static_cast<std::size_t>(n_));
        std::vector<Index> id(static_cast<std::size_t>(n_));
        for (Index i = 0; i < n_; ++i) {
            pos[i] = {host.x[i], host.y[i], host.z[i], 0};
            vel[i] = {host.vx[i], host.vy[i], host.vz[i], host.rho[i]};
            id[i] = ids.empty() ? i : ids[std::size_t(i)];
        }
        exec.upload(pos_, pos.data(), pos.size());
        exec.upload(vel_, vel.data(), vel.size());
        exec.upload(id_, id.data(), id.size());
    }

    // Room for n particles (and `spare` more before the arrays must grow), to be filled on the
    // backend (a seeder: solver/simulation_setup.h).
    void allocate(Index n, std::size_t spare = 0) {
        n_ = n;
        for (std::size_t size : {std::size_t(n) + spare, std::size_t(n)}) {
            pos_.resize(size);
            vel_.resize(size);
            id_.resize(size);
        }
    }

    // Sizes the scratch that reorders and fused passes write into to the particle count (the id
    // scratch only when the neighbour search reorders).
    void fitScratch(bool reorders) {
        reorders_ = reorders;
        sortedPos_.resize(std::size_t(n_));
        sortedVel_.resize(std::size_t(n_));
        if (reorders) {
            sortedId_.resize(std::size_t(n_));
        }
    }

    // Copies the particles to the host in id order (ids 0 .. n - 1), with the pressure that the
    // equation of state gives their density. With a reservoir, the `live` first slots (the live
    // particles after a step), in id order with their ids in out.id (host_frame.h). From the GPU
    // through host arrays kept for the next frame (allocating and clearing 36 B a particle each
    // frame cost as much as the copy); on the CPU straight from the particle arrays.
    void download(Exec& exec, HostParticles& out, const SphParams& params, Index live = -1) {
        const std::size_t n = std::size_t(live >= 0 ? live : n_);
        const auto toFrame = [&](const Index* id, const Real4* pos, const Real4* vel) {
            if (live >= 0) {
                sortToHostFrame(id, pos, vel, n, params, out);
            } else {
                scatterToHostFrame(id, pos, vel, n, params, out);
            }
        };
        if constexpr (Exec::isDevice) {
            hostId_.resize(n);
            hostPos_.resize(n);
            hostVel_.resize(n);
            exec.download(id_, hostId_.data(), n);
            exec.download(pos_, hostPos_.data(), n);
            exec.download(vel_, hostVel_.data(), n);
            toFrame(hostId_.data(), hostPos_.data(), hostVel_.data());
        } else {
            toFrame(id_.data(), pos_.data(), vel_.data());
        }
    }

    // ---- Reorder into cell order ----

    Placer placer() {
        return {pos_.data(),       vel_.data(),       id_.data(),
                sortedPos_.data(), sortedVel_.data(), sortedId_.data()};
    }
    Dropper dropper() const {
        return {pos_.data(), dropPending_ > 0 || heldGhosts_ > 0 || live_ != nullptr};
    }

    // ---- A reservoir of slots for a count that changes on the backend (physics/emitter.h) ----

    // Grows the store to `capacity` slots, the ones past the particles parked; `live`: the
    // backend's live count, which reorders keep (the particles are then slots [0, *live)).
    void holdReservoir(Exec& exec, Index capacity, Index* live) {
        const Index n = n_;
        if (capacity > n) {
            growKeeping(exec, pos_, std::size_t(capacity));
            growKeeping(exec, vel_, std::size_t(capacity));
            growKeeping(exec, id_, std::size_t(capacity));
            Real4 *pos = pos_.data(), *vel = vel_.data();
            Index* id = id_.data();
            exec.forEach(capacity - n, [=] WEIR_HD(Index k) {
                park(pos[n + k], vel[n + k]);
                id[n + k] = -1;
            });
            n_ = capacity;
        }
        live_ = live;
        fitScratch(reorders_);
    }
    bool holdsReservoir() const { return live_ != nullptr; }
    // After a reorder that dropped the parked slots and kept `*kept` particles: the slots past
    // them are parked, and the live count is *kept.
    void parkPastKept(Exec& exec, const Index* kept) {
        Real4 *pos = pos_.data(), *vel = vel_.data();
        Index *live = live_, *id = id_.data();
        exec.forEach(n_, [=] WEIR_HD(Index k) {
            const Index keptCount = *kept;
            if (k == 0) {
                *live = keptCount;
            }
            if (k >= keptCount) {
                park(pos[k], vel[k]);
                id[k] = -1;
            }
        });
    }

    // After the placer has run for every kept particle: the scratch becomes the particles.
    // dropped: whether the reorder dropped what dropper() named (those are then gone).
    void commitReorder(bool dropped) {
        pos_.swap(sortedPos_);
        vel_.swap(sortedVel_);
        id_.swap(sortedId_);
        if (dropped) {
            n_ -= dropPending_ + heldGhosts_;
            dropPending_ = 0;
            heldGhosts_ = 0;
        }
        heldGhosts_ += arrivingGhosts_;
        arrivingGhosts_ = 0;
    }

    // After a pass that wrote every particle's new position and velocity to nextPos(), nextVel().
    void commitMotion() {
        pos_.swap(sortedPos_);
        vel_.swap(sortedVel_);
    }

    // ---- Changes of the particle count (distributed runs, cluster/) ----

    // Ghosts held now (this step's and those arrived for the next).
    Index ghostCount() const { return heldGhosts_ + arrivingGhosts_; }

    // Marks the particles whose flag went up in a compaction's prefix sum `flag` (compactInto)
    // as removed: `count` of them, dropped by the next reorder that drops.
    void markRemoved(Exec& exec, const Index* flag, Index count) {
        Real4* pos = pos_.data();
        exec.forEach(n_, [=] WEIR_HD(Index i) {
            if (flag[i] > (i > 0 ? flag[i - 1] : 0)) {
                pos[i].w = kRemovedMark;
            }
        });
        dropPending_ += count;
    }

    // Drops at once the ghosts and the particles marked removed (for searches that do not drop
    // while they reorder).
    void dropNow(Exec& exec) {
        Index* keep = flagScratch(std::size_t(n_));
        const Real4* pos = pos_.data();
        exec.forEach(n_, [=] WEIR_HD(Index i) { keep[i] = isGhost(pos[i]) ? 0 : 1; });
        const Index kept = compactInto(exec, keep, sortedPos_, sortedVel_, sortedId_, 0);
        pos_.swap(sortedPos_);
        vel_.swap(sortedVel_);
        id_.swap(sortedId_);
        n_ = kept;
        heldGhosts_ = arrivingGhosts_ = dropPending_ = 0;
        fitScratch(reorders_);
    }

    // Appends particles from the host: arrivals (owned) or ghost copies (pos.w arriving).
    void append(Exec& exec, const ParticleBatch& batch) {
        const Index m = Index(batch.size());
        if (m == 0) {
            return;
        }
        const std::size_t total = std::size_t(n_) + std::size_t(m);
        growKeeping(exec, pos_, total);
        growKeeping(exec, vel_, total);
        growKeeping(exec, id_, total);
        exec.uploadAtAsync(pos_, std::size_t(n_), batch.pos.data(), std::size_t(m));
        exec.uploadAtAsync(vel_, std::size_t(n_), batch.vel.data(), std::size_t(m));
        exec.uploadAtAsync(id_, std::size_t(n_), batch.id.data(), std::size_t(m));
        exec.synchronize();  // one wait for the three
        for (const Real4& p : batch.pos) {
            arrivingGhosts_ += isGhost(p) ? 1 : 0;
        }
        n_ = Index(total);
        fitScratch(reorders_);
    }

    // Room for `count` more arriving ghosts at the end, to be written there on the backend.
    ParticleSpans appendSpace(Exec& exec, std::size_t count) {
        const std::size_t at = std::size_t(n_), total = at + count;
        arrivingGhosts_ += Index(count);
        growKeeping(exec, pos_, total);
        growKeeping(exec, vel_, total);
        growKeeping(exec, id_, total);
        n_ = Index(total);
        fitScratch(reorders_);
        return {pos_.data() + at, vel_.data() + at, id_.data() + at};
    }

    // A flag per particle (kept between calls: no allocation per exchange).
    Index* flagScratch(std::size_t n) {
        flags_.resize(n);
        return flags_.data();
    }

    // Moves the particles whose flag is 1 into (toPos, toVel, toId) from `offset` on, in order;
    // returns how many. Turns `flag` (from flagScratch) into its prefix sum.
    Index compactInto(Exec& exec, Index* flag, Buffer<Real4>& toPos, Buffer<Real4>& toVel,
                      Buffer<Index>& toId, Index offset) {
        const Index n = n_;
        if (n == 0) {
            return 0;
        }
        exec.inclusiveScan(flag, flag, n);
        const Index count = exec.readOne(flags_, std::size_t(flag - flags_.data()) + n - 1);
        growKeeping(exec, toPos, std::size_t(offset + count));
        growKeeping(exec, toVel, std::size_t(offset + count));
        growKeeping(exec, toId, std::size_t(offset + count));
        const Real4 *pos = pos_.data(), *vel = vel_.data();
        const Index* id = id_.data();
        Real4 *outPos = toPos.data(), *outVel = toVel.data();
        Index* outId = toId.data();
        exec.forEach(n, [=] WEIR_HD(Index i) {
            const Index before = i > 0 ? flag[i - 1] : 0;
            if (flag[i] > before) {
                outPos[offset + before] = pos[i];
                outVel[offset + before] = vel[i];
                outId[offset + before] = id[i];
            }
        });
        return count;
    }

    // Copies the particles whose flag is 1 to the host, appended to `out`; returns how many.
    Index gather(Exec& exec, Index* flag, ParticleBatch& out) {
        const Index count = compactInto(exec, flag, stagePos_, stageVel_, stageId_, 0);
        const std::size_t at = out.size();
        out.resize(at + std::size_t(count));
        exec.downloadFromAsync(stagePos_, 0, out.pos.data() + at, std::size_t(count));
        exec.downloadFromAsync(stageVel_, 0, out.vel.data() + at, std::size_t(count));
        exec.downloadFromAsync(stageId_, 0, out.id.data() + at, std::size_t(count));
        exec.synchronize();  // one wait for the three
        return count;
    }

    // Copies of the flagged particles into the staging arrays from `offset` on (for a transport
    // that sends from the backend's memory), marked as arriving ghosts; returns how many.
    Index stageGhosts(Exec& exec, Index* flag, Index offset) {
        const Index count = compactInto(exec, flag, stagePos_, stageVel_, stageId_, offset);
        Real4* marked = stagePos_.data() + offset;
        exec.forEach(count, [=] WEIR_HD(Index i) { marked[i].w = kArrivingGhostMark; });
        return count;
    }
    ParticleSpans staged() { return {stagePos_.data(), stageVel_.data(), stageId_.data()}; }

    // Resizes `buffer` to n elements keeping its first min(size, n) (a little spare on growth).
    template <class T>
    static void growKeeping(Exec& exec, Buffer<T>& buffer, std::size_t n) {
        if (n <= buffer.capacity()) {
            buffer.resize(n);
            return;
        }
        Buffer<T> bigger;
        bigger.resize(n + n / 16);  // both held while copying: spare little at a billion
        const T* from = buffer.data();
        T* to = bigger.data();
        exec.forEach(Index(buffer.size()), [=] WEIR_HD(Index i) { to[i] = from[i]; });
        bigger.resize(n);
        buffer.swap(bigger);
    }

    std::size_t bytesHeld() const {
        return (pos_.size() + vel_.size() + sortedPos_.size() + sortedVel_.size() +
                stagePos_.size() + stageVel_.size()) *
                   sizeof(Real4) +
               (id_.size() + sortedId_.size() + stageId_.size() + flags_.size()) * sizeof(Index);
    }

   private:
    Index n_ = 0;
    bool reorders_ = false;
    Index heldGhosts_ = 0;      // ghosts of this step (mark 1)
    Index arrivingGhosts_ = 0;  // ghosts appended for the next step (mark 2)
    Index dropPending_ = 0;     // owned particles marked removed (mark 3)
    Index* live_ = nullptr;     // the backend's live count, with a reservoir (holdReservoir)
    Buffer<Real4> pos_, vel_, sortedPos_, sortedVel_;
    Buffer<Index> id_, sortedId_;
    Buffer<Index> flags_;                // selection flags and their sums
    Buffer<Real4> stagePos_, stageVel_;  // particles on their way to the host or other ranks
    Buffer<Index> stageId_;
    // A GPU run's particles on their way to a host frame (download), kept between frames.
    std::vector<Real4> hostPos_, hostVel_;
    std::vector<Index> hostId_;
};

}  // namespace weir
