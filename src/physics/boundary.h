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
// of its 27 cells; a per-cell flag says whether any boundary particle lies in them, so particles
// away from the walls pay one byte load and no loop.
#pragma once

#include <cmath>
#include <vector>

#include "core/config.h"
#include "core/vec3.h"
#include "physics/kernels.h"

namespace weir {

struct BoundaryView {
    const Real4* pos = nullptr;           // x, y, z, psi; in cell order
    const Index* cellStart = nullptr;     // cells + 1 entries: cell c holds [start[c], start[c+1])
    const unsigned char* near = nullptr;  // per cell: a boundary particle in its 27 cells
    Vec3 origin;
    Real invCellSize = 0;
    int nx = 0, ny = 0, nz = 0;
    Index count = 0;

    // Calls f(b) for every boundary particle b in the 27 cells around position x.
    template <class F>
    WEIR_HD void forEachNear(const Vec3& x, F&& f) const {
        if (count == 0) {
            return;
        }
        const int cx = clampCell((x.x - origin.x) * invCellSize, nx);
        const int cy = clampCell((x.y - origin.y) * invCellSize, ny);
        const int cz = clampCell((x.z - origin.z) * invCellSize, nz);
        if (!near[cellOf(cx, cy, cz)]) {
            return;
        }
        const int xLo = cx > 0 ? cx - 1 : 0, xHi = cx + 1 < nx ? cx + 1 : nx - 1;
        for (int y = cy > 0 ? cy - 1 : 0; y <= cy + 1 && y < ny; ++y) {
            for (int z = cz > 0 ? cz - 1 : 0; z <= cz + 1 && z < nz; ++z) {
                const Index end = cellStart[cellOf(xHi, y, z) + 1];
                for (Index b = cellStart[cellOf(xLo, y, z)]; b < end; ++b) {
                    f(b);
                }
            }
        }
    }

    WEIR_HD Index cellOf(int x, int y, int z) const { return (Index(y) * nz + z) * nx + x; }
    WEIR_HD static int clampCell(Real v, int n) {
        const int c = int(std::floor(v));
        return c < 0 ? 0 : (c >= n ? n - 1 : c);
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
    std::vector<Real4> pos;  // x, y, z, psi; in cell order
    std::vector<Index> cellStart;
    std::vector<unsigned char> near;
    Vec3 origin;
    Real cellSize = 0;
    int dims[3] = {0, 0, 0};
    std::size_t size() const { return pos.size(); }
};

}  // namespace weir
