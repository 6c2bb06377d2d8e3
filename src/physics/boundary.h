// Walls that hold pressure: static boundary particles sampled on the container and obstacles, in
// the manner of Akinci et al. 2012 ("Versatile rigid-fluid coupling for incompressible SPH").
// Each boundary particle b carries psi_b = rho0 / sum_k W_bk over its boundary neighbours k: the
// fluid mass it stands for, so that a sparse or uneven sampling weighs the same as a dense one.
// It adds psi_b W_ib to a fluid particle's density and the pressure force
// a_i = -psi_b p_i / rho_i^2 grad W_ib (pressure mirrored from the fluid particle), plus an
// optional friction against the wall (walls.friction).
//
// Boundary particles never move, so they live apart from the fluid: their own arrays, sorted
// once into a static uniform grid of h-wide cells built on the host at set-up (no per-step sort,
// and the fluid's sorted arrays and grid stay as they were). A fluid particle visits the 9 X runs
// of its 27 cells by the shared cell walk (grid/cell_walk.h); a per-cell flag says whether any
// boundary particle lies in them, so particles away from the walls pay one byte load and no loop.
#pragma once

#include <cmath>
#include <vector>

#include "core/config.h"
#include "core/vec3.h"
#include "grid/cell_walk.h"
#include "physics/kernels.h"

namespace weir {

struct BoundaryView {
    const Real4* pos = nullptr;       // x, y, z, psi; in cell order
    const Real4* velocity = nullptr;  // the wall's velocity at each (null: walls at rest)
    // delta-SPH: each one's velocity and p / rho^2 as the fluid near it extrapolates them this
    // step (Adami et al. 2012; physics/delta_sph.h), by the method; null otherwise.
    const Real4* state = nullptr;
    const unsigned char* near = nullptr;  // per cell: a boundary particle in its 27 cells
    CellTableView cells{};                // h-wide cells (grid/cell_walk.h)
    Index count = 0;

    // Calls f(b) for every boundary particle b that can lie within h (the cell size) of x.
    template <class F>
    WEIR_HD void forEachNear(const Vec3& x, F&& f) const {
        if (count == 0) {
            return;
        }
        const CellCoord c = cells.spec.cellOf(x.x, x.y, x.z);
        if (!near[denseCellIndex(c.x, c.y, c.z, cells.spec.dims[0], cells.spec.dims[2])]) {
            return;
        }
        const Real h = cells.spec.cellSize;
        cells.forEachRun(x, 1, h * h, [&](Index first, Index end) {
            for (Index b = first; b < end; ++b) {
                f(b);
            }
        });
    }
};

// Density of particle i's boundary neighbours: sum_b psi_b W_ib.
WEIR_HD inline Real boundaryDensity(const BoundaryView& bv, const KernelCoefficients& k,
                                    const Vec3& xi) {
    Real sum = 0;
    bv.forEachNear(xi, [&](Index b) {
        const Real4 pb = bv.pos[b];
        sum += pb.w * poly6(k, lengthSquared(xi - pb.xyz()));
    });
    return sum;
}

// Acceleration of fluid particle i from the walls: Akinci's pressure term with the pressure
// mirrored (p_b = p_i), and viscous friction wallViscosity * V_b lap W (0 - v_i) / rho_i.
WEIR_HD inline Vec3 boundaryAcceleration(const BoundaryView& bv, const KernelCoefficients& k,
                                         const Vec3& xi, const Vec3& vi, Real rhoi, Real pi,
                                         Real wallViscosity, Real invRestDensity) {
    Vec3 acc;
    const Real pressureOverRho2 = pi / (rhoi * rhoi);
    const Real friction = wallViscosity * invRestDensity / rhoi;
    bv.forEachNear(xi, [&](Index b) {
        const Real4 pb = bv.pos[b];
        const Vec3 rVec = xi - pb.xyz();
        const Real r2 = lengthSquared(rVec);
        if (r2 < k.h2 && r2 > Real(0)) {
            const Real invR = reciprocalSqrt(r2);
            const Real r = r2 * invR;
            acc += rVec * (-pb.w * pressureOverRho2 * spikyGradientFactor(k, r, invR));
            acc -= vi * (friction * pb.w * viscosityLaplacian(k, r));
        }
    });
    return acc;
}

// The boundary particles and their static grid, as built on the host (scene/boundary.cpp).
struct BoundaryParticles {
    std::vector<Real4> pos;       // x, y, z, psi; in cell order
    std::vector<Real4> velocity;  // the wall's velocity at each; empty: every wall at rest
    std::vector<Index> cellStart;
    std::vector<unsigned char> near;
    Vec3 origin;
    Real cellSize = 0;
    int dims[3] = {0, 0, 0};
    std::size_t size() const { return pos.size(); }

    // The cells of the static grid, as the view walks them.
    GridSpec cellSpec() const {
        GridSpec spec;
        spec.origin = origin;
        spec.cellSize = cellSize;
        spec.inverseCellSize = cellSize > Real(0) ? Real(1) / cellSize : Real(0);
        for (int a = 0; a < 3; ++a) {
            spec.dims[a] = dims[a] > 0 ? dims[a] : 1;
        }
        return spec;
    }
};

}  // namespace weir
