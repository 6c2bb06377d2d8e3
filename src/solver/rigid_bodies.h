// The rigid bodies of a simulation (physics/rigid_body.h) on its backend: their states, their
// boundary particles in each body's frame, and the wall grid that holds the static walls' and
// the bodies' particles together. With bodies the wall grid is no longer static: before each
// step the bodies' particles are placed where their bodies are, and all boundary particles are
// sorted into the grid's cells again (a radix sort and one pass per cell); the stages then see
// one set of boundary particles, as without bodies. After the step each body's loads are summed
// (one reduction per component) and it moves, all on the backend: no host round trip.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "core/check.h"
#include "core/config.h"
#include "grid/cell_walk.h"
#include "physics/boundary.h"
#include "physics/rigid_body.h"
#include "physics/sph_params.h"
#include "physics/time_step.h"

namespace weir {

template <class Exec>
class RigidBodies {
   public:
    template <class T>
    using Buffer = typename Exec::template Buffer<T>;

    bool active() const { return count_ > 0; }
    int count() const { return count_; }

    // The static walls (their grid gives the cells) and the bodies, uploaded once.
    void upload(Exec& exec, const BoundaryParticles& walls, const RigidBodySetup& setup) {
        count_ = int(setup.size());
        if (count_ == 0) {
            return;
        }
        staticCount_ = Index(walls.size());
        particleCount_ = Index(setup.particles.size());
        spec_ = walls.cellSpec();
        const std::size_t cells =
            std::size_t(spec_.dims[0]) * std::size_t(spec_.dims[1]) * std::size_t(spec_.dims[2]);
        WEIR_REQUIRE(cells < (std::size_t(1) << 31), "the wall grid has too many cells for bodies");
        cells_ = Index(cells);
        keyBits_ = 1;
        while ((std::size_t(1) << keyBits_) < cells) {
            ++keyBits_;
        }
        const Index total = staticCount_ + particleCount_;
        std::vector<Real4> staticVelocity = walls.velocity;
        staticVelocity.resize(walls.size(), Real4{0, 0, 0, 0});
        exec.upload(staticPos_, walls.pos.data(), walls.pos.size());
        exec.upload(staticVelocity_, staticVelocity.data(), staticVelocity.size());
        exec.upload(local_, setup.particles.data(), setup.particles.size());
        exec.upload(owner_, setup.owner.data(), setup.owner.size());
        exec.upload(bodies_, setup.bodies.data(), setup.bodies.size());
        std::vector<Index> identity(static_cast<std::size_t>(total));
        for (Index i = 0; i < total; ++i) {
            identity[std::size_t(i)] = i;
        }
        exec.upload(identity_, identity.data(), identity.size());
        first_.assign(std::size_t(count_) + 1, 0);
        for (int body : setup.owner) {
            ++first_[std::size_t(body) + 1];
        }
        for (int b = 0; b < count_; ++b) {
            first_[std::size_t(b) + 1] += first_[std::size_t(b)];
        }
        for (Buffer<Real4>* b : {&sourcePos_, &sourceVelocity_, &pos_, &velocity_}) {
            b->resize(std::size_t(total));
        }
        keys_.resize(std::size_t(total));
        sortedKeys_.resize(std::size_t(total));
        slotSource_.resize(std::size_t(total));
        cellBound_.resize(cells + 1);
        near_.resize(cells);
        loads_.resize(std::size_t(6) * std::size_t(std::max<Index>(particleCount_, 1)));
        sums_.resize(std::size_t(6) * std::size_t(count_));
    }

    // Driven bodies to their pose at the step's start, every body's particles where their body
    // is, and the wall grid sorted again.
    void place(Exec& exec, const StepClock* clock) {
        exec.stageBegin("bodies");
        RigidBody* bodies = bodies_.data();
        exec.forEach(count_, [=] WEIR_HD(Index b) {
            if (bodies[b].motion != BodyMotion::Floating) {
                placeDrivenBody(bodies[b], clock->time);
            }
        });
        const Index staticCount = staticCount_;
        const Real4 *staticPos = staticPos_.data(), *staticVelocity = staticVelocity_.data();
        const Real4* local = local_.data();
        const int* owner = owner_.data();
        Real4 *sourcePos = sourcePos_.data(), *sourceVelocity = sourceVelocity_.data();
        CellKey* keys = keys_.data();
        const GridSpec spec = spec_;
        const Index total = staticCount_ + particleCount_;
        exec.forEach(total, [=] WEIR_HD(Index i) {
            Real4 p, v;
            if (i < staticCount) {
                p = staticPos[i];
                v = staticVelocity[i];
            } else {
                const Real4 l = local[i - staticCount];
                const RigidBody& body = bodies[owner[i - staticCount]];
                const Vec3 r = rotate(body.q, l.xyz());
                p = Real4::from(body.x + r, l.w);
                v = Real4::from(body.v + cross(body.omega, r));
            }
            sourcePos[i] = p;
            sourceVelocity[i] = v;
            const CellCoord c = spec.cellOf(p.x, p.y, p.z);
            keys[i] = denseCellIndex(c.x, c.y, c.z, spec.dims[0], spec.dims[2]);
        });
        exec.sortPairs(keys_.data(), sortedKeys_.data(), identity_.data(), slotSource_.data(),
                       total, keyBits_);
        const CellKey* sorted = sortedKeys_.data();
        const Index* slotSource = slotSource_.data();
        Real4 *pos = pos_.data(), *velocity = velocity_.data();
        exec.forEach(total, [=] WEIR_HD(Index k) {
            pos[k] = sourcePos[slotSource[k]];
            velocity[k] = sourceVelocity[slotSource[k]];
        });
        Index* bound = cellBound_.data();
        exec.forEach(cells_ + 1, [=] WEIR_HD(Index c) {  // the first slot of cell c or later
            Index lo = 0, hi = total;
            while (lo < hi) {
                const Index mid = lo + (hi - lo) / 2;
                if (sorted[mid] < CellKey(c)) {
                    lo = mid + 1;
                } else {
                    hi = mid;
                }
            }
            bound[c] = lo;
        });
        unsigned char* near = near_.data();
        exec.forEach(cells_, [=] WEIR_HD(Index cell) {
            const int nx = spec.dims[0], nz = spec.dims[2];
            const int x = int(cell % nx), z = int((cell / nx) % nz), y = int(cell / nx / nz);
            unsigned char any = 0;
            for (int dy = -1; dy <= 1 && !any; ++dy) {
                for (int dz = -1; dz <= 1 && !any; ++dz) {
                    for (int dx = -1; dx <= 1 && !any; ++dx) {
                        const int cx = x + dx, cy = y + dy, cz = z + dz;
                        if (cx < 0 || cy < 0 || cz < 0 || cx >= nx || cy >= spec.dims[1] ||
                            cz >= nz) {
                            continue;
                        }
                        const CellKey k = denseCellIndex(cx, cy, cz, nx, nz);
                        any = bound[k + 1] > bound[k] ? 1 : 0;
                    }
                }
            }
            near[cell] = any;
        });
        exec.stageEnd("bodies");
    }

    // The wall grid as the stages see it (after place()).
    BoundaryView wallView() {
        BoundaryView walls;
        walls.pos = pos_.data();
        walls.velocity = velocity_.data();
        walls.near = near_.data();
        walls.cells.cellBound = cellBound_.data();
        walls.cells.spec = spec_;
        walls.count = staticCount_ + particleCount_;
        return walls;
    }

    RigidBodyView view() {
        return {bodies_.data(), count_,         slotSource_.data(), owner_.data(),
                staticCount_,   particleCount_, loads_.data()};
    }

    // After the step: each floating body's loads summed, then it moves over the step's dt under
    // them and gravity, and contacts keep it in the container and off the other bodies.
    void advance(Exec& exec, const StepClock* clock, const SphParams& params) {
        exec.stageBegin("bodies");
        const Index n = particleCount_;
        for (int b = 0; b < count_; ++b) {
            const Index first = first_[std::size_t(b)], count = first_[std::size_t(b) + 1] - first;
            for (int component = 0; component < 6 && count > 0; ++component) {
                exec.sum(loads_.data() + std::size_t(component) * std::size_t(n) + first, count,
                         sums_.data() + 6 * b + component);
            }
        }
        RigidBody* bodies = bodies_.data();
        const Real* sums = sums_.data();
        const Vec3 gravity = params.gravity, lo = params.boxMin, hi = params.boxMax;
        const int periodic = params.periodicAxes, count = count_;
        exec.forEach(1, [=] WEIR_HD(Index) {
            const Real dt = clock->dt;
            for (int b = 0; b < count; ++b) {
                RigidBody& body = bodies[b];
                const Real* s = sums + 6 * b;
                body.force = Vec3(s[0], s[1], s[2]);
                body.torque = Vec3(s[3], s[4], s[5]);
                if (body.motion == BodyMotion::Floating && dt > Real(0)) {
                    advanceFloatingBody(body, gravity, dt);
                    containBody(body, lo, hi, periodic, kContactFriction);
                }
            }
            for (int a = 0; a < count; ++a) {
                for (int b = a + 1; b < count; ++b) {
                    separateBodies(bodies[a], bodies[b]);
                }
            }
        });
        exec.stageEnd("bodies");
    }

    std::vector<RigidBody> download(Exec& exec) const {
        std::vector<RigidBody> out(static_cast<std::size_t>(count_));
        if (count_ > 0) {
            exec.download(bodies_, out.data(), out.size());
        }
        return out;
    }

    std::size_t bytesHeld() const {
        return (staticPos_.size() + staticVelocity_.size() + local_.size() + sourcePos_.size() +
                sourceVelocity_.size() + pos_.size() + velocity_.size()) *
                   sizeof(Real4) +
               (keys_.size() + sortedKeys_.size()) * sizeof(CellKey) +
               (identity_.size() + slotSource_.size() + cellBound_.size()) * sizeof(Index) +
               near_.size() + (loads_.size() + sums_.size()) * sizeof(Real) +
               bodies_.size() * sizeof(RigidBody) + owner_.size() * sizeof(int);
    }

   private:
    int count_ = 0;
    Index staticCount_ = 0, particleCount_ = 0, cells_ = 0;
    int keyBits_ = 1;
    GridSpec spec_;
    std::vector<Index> first_;  // host: each body's first particle, and the end
    Buffer<RigidBody> bodies_;
    Buffer<Real4> staticPos_, staticVelocity_, local_;
    Buffer<int> owner_;
    Buffer<Real4> sourcePos_, sourceVelocity_;  // this step's places, in source order
    Buffer<CellKey> keys_, sortedKeys_;
    Buffer<Index> identity_, slotSource_;
    Buffer<Real4> pos_, velocity_;  // in the grid's order: what the stages read
    Buffer<Index> cellBound_;
    Buffer<unsigned char> near_;
    Buffer<Real> loads_, sums_;
};

}  // namespace weir
