// The neighbour search of a simulation, its mode chosen once: the paper's sorted grid with its
// cell and 26-neighbour tables (§6.2), weir's dense cell table, or brute force. It groups the
// particle store by cell each step and hands the stages the view of the chosen structure, so a
// pressure solver writes its stages once for all three.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <variant>

#include "core/check.h"
#include "core/config.h"
#include "core/slab.h"
#include "grid/cell_id.h"
#include "grid/dense_grid.h"
#include "grid/neighbour_grid.h"
#include "solver/particle_store.h"

namespace weir {

// Grid: the sorted grid with the paper's cell table and 26-neighbour table (§6.2).
// Dense: the same grouping with a dense table over every cell (grid/dense_grid.h), faster.
// Brute: O(N^2). Auto: Dense where its table is small enough, else Grid.
enum class NeighbourMode { Grid, Dense, Brute, Auto };

NeighbourMode parseNeighbourMode(const std::string& name);
// Auto made concrete for a grid of h-wide cells and n particles.
NeighbourMode resolveNeighbourMode(NeighbourMode mode, const GridSpec& grid, std::int64_t n);
const char* neighbourModeName(NeighbourMode mode);

// Cells per smoothing radius of the dense table for a grid of h-wide cells and n particles (1
// where even the grid of h cells is too big for it: the dense table is then unused).
inline int denseReach(const GridSpec& radiusGrid, std::int64_t n) {
    return std::max(1, denseCellsPerRadius(radiusGrid, n));
}

template <class Exec>
class NeighbourSearch {
   public:
    // mode: resolved already (not Auto); radiusGrid: the container's grid of h-wide cells.
    NeighbourSearch(NeighbourMode mode, const GridSpec& radiusGrid, std::int64_t particles, Real h)
        : mode_(mode), h_(h) {
        WEIR_REQUIRE(mode != NeighbourMode::Auto, "the neighbour mode is resolved first");
        if (mode == NeighbourMode::Grid) {
            structure_.template emplace<NeighbourGrid<Exec>>(radiusGrid);
        } else if (mode == NeighbourMode::Dense) {
            const int reach = denseReach(radiusGrid, particles);
            denseFull_ = denseGridSpec(radiusGrid, reach);
            structure_.template emplace<DenseGrid<Exec>>(denseFull_, reach);
        }
    }

    NeighbourMode mode() const { return mode_; }
    // Whether update() reorders the particles (all but brute force).
    bool reorders() const { return mode_ != NeighbourMode::Brute; }
    // Whether update() drops the particles the store's dropper names while it reorders (the
    // dense table's counting sort); otherwise the store drops them at once (dropNow).
    bool dropsWhileReordering() const { return mode_ == NeighbourMode::Dense; }
    // Whether a step of this search can be captured in a CUDA graph: the paper's grid reads its
    // number of occupied cells back to the host every build.
    bool capturable() const { return mode_ != NeighbourMode::Grid; }

    // What a reorder does besides moving the store's particles: nothing.
    struct NothingElse {
        WEIR_HD void operator()(Index, Index) const {}
    };

    // Groups the store's particles by cell and reorders them into cell order (the dense table:
    // dropping what the store's dropper names), then runs once() on one thread of the backend:
    // inside the build's first pass where there is one (a launch fewer per step). also(from, to)
    // runs in the pass that moves each particle, for a method's own per-particle data (brute
    // force, which does not reorder: also(i, i), in a pass of its own).
    template <class Once, class Also = NothingElse>
    void update(Exec& exec, ParticleStore<Exec>& store, Once once, Also also = {}) {
        const Index n = store.count();
        const auto placer = store.placer();
        auto place = [=] WEIR_HD(Index from, Index to) {
            placer(from, to);
            also(from, to);
        };
        if (auto* dense = std::get_if<DenseGrid<Exec>>(&structure_)) {
            exec.stageBegin("grid");
            // The counting sort places each particle's data as it finds its place: no separate
            // reorder pass.
            const auto dropper = store.dropper();
            dense->build(exec, store.pos(), n, place, dropper, once);
            store.commitReorder(dropper.active);
            if (store.holdsReservoir()) {  // the live particles are counted on the backend
                store.parkPastKept(exec, dense->cellBound().data() + totalCells(dense->spec()));
                exec.stageEnd("grid");
                return;
            }
            exec.stageEnd("grid");
            checkKept(exec, *dense, store.count(), dropper.active);
            return;
        }
        WEIR_REQUIRE(!store.holdsReservoir(),
                     "emitters and sinks need the dense cell table (--neighbours dense)");
        if (auto* grid = std::get_if<NeighbourGrid<Exec>>(&structure_)) {
            exec.stageBegin("grid");
            grid->build(exec, store.pos(), n);
            const Index* order = grid->permutation();
            exec.forEach(n, [=] WEIR_HD(Index k) { place(order[k], k); });
            store.commitReorder(false);
            exec.stageEnd("grid");
        } else if constexpr (!std::is_same_v<Also, NothingElse>) {
            exec.forEach(n, [=] WEIR_HD(Index i) { also(i, i); });
        }
        exec.forEach(1, [=] WEIR_HD(Index) { once(); });
    }

    // Calls f(view) with the neighbour view of this mode over positions `pos` in cell order:
    // GridNeighbours, DenseGridNeighbours or BruteNeighbours (grid/).
    template <class F>
    void visit(const Real4* pos, Index n, F&& f) const {
        if (const auto* dense = std::get_if<DenseGrid<Exec>>(&structure_)) {
            f(dense->view(pos, h_));
        } else if (const auto* grid = std::get_if<NeighbourGrid<Exec>>(&structure_)) {
            f(grid->view());
        } else {
            f(BruteNeighbours{n});
        }
    }

    // The dense table over the cells of `share` widened by `margin` only (particles outside are
    // clamped into its end cells, still found), so a rank's table grows with its share, not with
    // the whole domain. The paper's grid keeps the whole domain.
    void restrictTo(const Slab& share, double margin) {
        if (auto* dense = std::get_if<DenseGrid<Exec>>(&structure_)) {
            dense->setSpec(sliceOf(denseFull_, share.axis, share.lo - margin, share.hi + margin));
        }
    }

    std::size_t bytesHeld() const {
        return std::visit(
            [](const auto& s) -> std::size_t {
                if constexpr (std::is_same_v<std::decay_t<decltype(s)>, std::monostate>) {
                    return 0;
                } else {
                    return s.bytesHeld();
                }
            },
            structure_);
    }
    // Occupied cells after the last build of the paper's grid (0 for the other modes).
    Index occupiedCells() const {
        const auto* grid = std::get_if<NeighbourGrid<Exec>>(&structure_);
        return grid != nullptr ? grid->numCells() : 0;
    }

   private:
    // A distributed run's dense build must keep exactly the particles the host expects; checked
    // where reading the count back costs nothing (CPU) or in debug builds.
    static void checkKept(Exec& exec, const DenseGrid<Exec>& dense, Index expected, bool dropped) {
#ifdef NDEBUG
        constexpr bool check = !Exec::isDevice;
#else
        constexpr bool check = true;
#endif
        if constexpr (check) {
            if (dropped) {
                const Index kept = dense.keptCount(exec);
                WEIR_REQUIRE(expected == kept,
                             "the grid build kept " << kept << " particles, not " << expected);
            }
        }
    }

    NeighbourMode mode_;
    Real h_;
    GridSpec denseFull_;  // the dense table's cells over the whole container
    std::variant<std::monostate, NeighbourGrid<Exec>, DenseGrid<Exec>> structure_;
};

}  // namespace weir
