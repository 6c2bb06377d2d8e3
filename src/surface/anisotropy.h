// Anisotropic particle kernels (Yu & Turk 2013): per particle, a smoothed centre and a matrix that
// stretches its kernel along the spread of its neighbours, for a surface field whose sheets stay
// thin and whose flat parts stay flat. Per-particle functions for the CPU and the CUDA backends.
#pragma once

#include <cmath>

#include "core/config.h"
#include "core/symmetric_eigen.h"
#include "core/vec3.h"
#include "surface/surface_field.h"

namespace weir {

// A symmetric 3x3 matrix: its six distinct entries.
struct SymmetricMatrix3 {
    Real xx = 0, yy = 0, zz = 0, xy = 0, xz = 0, yz = 0;

    WEIR_HD Vec3 times(const Vec3& v) const {
        return {xx * v.x + xy * v.y + xz * v.z, xy * v.x + yy * v.y + yz * v.z,
                xz * v.x + yz * v.y + zz * v.z};
    }
    WEIR_HD Real entry(int r, int c) const {
        if (r == c) {
            return r == 0 ? xx : (r == 1 ? yy : zz);
        }
        const int sum = r + c;  // 1: xy, 2: xz, 3: yz
        return sum == 1 ? xy : (sum == 2 ? xz : yz);
    }
};

// Eigenvalues and unit eigenvectors of a symmetric 3x3 matrix by cyclic Jacobi rotations: values
// in `values`, vector k in column k of `vectors` (vectors[row][k]). Converges quadratically; six
// sweeps take a covariance matrix to float rounding.
WEIR_HD inline void symmetricEigen(const SymmetricMatrix3& m, Real values[3], Real vectors[3][3]) {
    Real a[3][3];
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) {
            a[r][c] = m.entry(r, c);
        }
    }
    jacobiEigen(a, vectors, 6, Real(1e-14));
    for (int k = 0; k < 3; ++k) {
        values[k] = a[k][k];
    }
}

// Yu & Turk's constants: lambda (centre smoothing), k_r (longest to shortest axis), N_eps (the
// fewest neighbours for an anisotropic kernel, self included). Yu & Turk count neighbours within
// twice the kernel radius and take N_eps = 25; within R = 2 d a particle inside a lattice has 33,
// one on a flat surface 23, one in a sheet a single particle thick 13.
constexpr double kAnisotropySmoothing = 0.9;
constexpr double kAnisotropyMaxStretch = 4;
constexpr int kAnisotropyMinNeighbours = 10;
// The neighbourhood's radius r_n over the kernel radius R. Yu & Turk take 2; measured here (a flat
// lattice face, a jittered sheet one particle thick, anisotropy_test.cpp), 1.5 and 2 pull a flat
// face in by 0.64 d and 1.0 d instead of 0.30 d and leave the sheet rougher (0.076 d and 0.056 d
// RMS against 0.038 d), at 3.4 and 8 times the neighbours.
constexpr double kAnisotropyNeighbourhood = 1.0;

// The constants of the anisotropy pass (Yu & Turk 2013, section 4), for kernel radius R.
struct AnisotropyParams {
    Real radius2;               // r_n^2: neighbours within r_n weigh w = 1 - (r / r_n)^3
    Real inverseRadius;         // 1 / r_n
    Real inverseKernelRadius;   // 1 / R
    Real smoothing;             // lambda: the centre moves this far to its neighbours' mean
    Real maxStretch;            // k_r: no axis shorter than 1 / k_r of the longest
    int minNeighbours;          // fewer (self included): an isotropic kernel
    Real isotropicDeterminant;  // 1 / R^3
};

// Particle i's smoothed centre x_i + lambda (xw_i - x_i), where xw_i is the w-weighted mean of
// its neighbours, and its kernel matrix G: the covariance C_i of those neighbours about xw_i,
// decomposed as C = Q diag(s) Q^T, gives G = Q diag(1 / (R s'_k)) Q^T with
// s'_k = max(s_k, s_max / k_r) / s_max. So the longest axis of the kernel's support, an ellipsoid,
// is R (the isotropic kernel's, so that the bins' search radius still holds) and the others are
// shortened across a sheet or a flat surface, down to R / k_r. A particle with fewer than
// minNeighbours neighbours (spray) keeps the isotropic kernel G = I / R. `centre` gets the
// smoothed centre and det(G) in w.
template <class Bins>
WEIR_HD void anisotropicKernelOf(Index i, const Bins& bins, const AnisotropyParams& params,
                                 Real4& centre, SymmetricMatrix3& g) {
    const Vec3 xi = bins.pos[i].xyz();
    Real weightSum = 0;
    Vec3 weighted;       // sum of w (x_j - x_i): offsets from x_i keep float precision
    SymmetricMatrix3 s;  // sum of w (x_j - x_i)(x_j - x_i)^T, in units of R^2
    int count = 0;
    bins.forEachNear(xi, params.radius2, [&](Index j) {
        const Vec3 offset = bins.pos[j].xyz() - xi;
        const Real r2 = lengthSquared(offset);
        if (r2 < params.radius2) {
            const Real q = std::sqrt(r2) * params.inverseRadius;
            const Real w = Real(1) - q * q * q;
            const Vec3 u = offset * params.inverseRadius;
            ++count;
            weightSum += w;
            weighted += offset * w;
            s.xx += w * u.x * u.x;
            s.yy += w * u.y * u.y;
            s.zz += w * u.z * u.z;
            s.xy += w * u.x * u.y;
            s.xz += w * u.x * u.z;
            s.yz += w * u.y * u.z;
        }
    });
    const Vec3 mean = weighted / weightSum;  // particle i itself weighs 1: weightSum >= 1
    centre = Real4::from(xi + mean * params.smoothing, params.isotropicDeterminant);
    g = SymmetricMatrix3{};
    g.xx = g.yy = g.zz = params.inverseKernelRadius;
    if (count < params.minNeighbours) {
        return;
    }
    const Vec3 m = mean * params.inverseRadius;
    SymmetricMatrix3 c;
    c.xx = s.xx / weightSum - m.x * m.x;
    c.yy = s.yy / weightSum - m.y * m.y;
    c.zz = s.zz / weightSum - m.z * m.z;
    c.xy = s.xy / weightSum - m.x * m.y;
    c.xz = s.xz / weightSum - m.x * m.z;
    c.yz = s.yz / weightSum - m.y * m.z;
    Real values[3], vectors[3][3];
    symmetricEigen(c, values, vectors);
    const Real largest = std::fmax(values[0], std::fmax(values[1], values[2]));
    if (!(largest > Real(0))) {
        return;
    }
    Real inverseAxis[3];
    Real determinant = 1;
    for (int k = 0; k < 3; ++k) {
        const Real stretch = std::fmax(values[k], largest / params.maxStretch) / largest;  // (0, 1]
        inverseAxis[k] = params.inverseKernelRadius / stretch;
        determinant *= inverseAxis[k];
    }
    SymmetricMatrix3 out;
    for (int k = 0; k < 3; ++k) {
        const Real v0 = vectors[0][k], v1 = vectors[1][k], v2 = vectors[2][k];
        const Real a = inverseAxis[k];
        out.xx += a * v0 * v0;
        out.yy += a * v1 * v1;
        out.zz += a * v2 * v2;
        out.xy += a * v0 * v1;
        out.xz += a * v0 * v2;
        out.yz += a * v1 * v2;
    }
    g = out;
    centre.w = determinant;
}

// The volume fraction at which the anisotropic surface is drawn. Half: where a flat fluid of
// isotropic kernels ends, half a spacing beyond its outer layer, half of each kernel is inside.
// The smoothed centres pull a flat face in by 0.30 d (anisotropy_test.cpp); a lower threshold
// would push it back out but thicken thin sheets (0.4: a face 0.05 d in, a sheet one particle
// thick 1.23 d thick instead of 0.82 d, thicker than the isotropic field's 1.12 d).
constexpr double kAnisotropicThreshold = 0.5;

// The volume fraction's fall per particle spacing d across a flat surface of isotropic kernels of
// radius R = ratio d: the kernel integrated over a plane through its centre, 315 / (256 R), times
// d.
inline double anisotropicFractionSlope(double ratio) { return 315.0 / (256.0 * ratio); }

// f(x) = sum_j V W(G_j (x - c_j)) det(G_j), W the normalised kernel 315 / (64 pi) (1 - q^2)^3 on
// the unit ball and V = d^3 the volume of a particle: the fluid's volume fraction, about 1 inside
// and falling through `threshold` at its surface. The value sampled is
// (threshold - f) / slope, with slope the fraction's fall per particle spacing across a flat
// surface of isotropic kernels: negative in the fluid, zero on the surface, in particle spacings
// near it, like ZhuBridsonField's.
struct AnisotropicField {
    ParticleBinsView centres;        // smoothed centres, det(G) in w
    const SymmetricMatrix3* matrix;  // G, in the centres' order
    Real kernelRadius2;              // every kernel's support lies within R of its centre
    Real weightScale;                // V 315 / (64 pi)
    Real threshold;
    Real inverseSlope;  // spacings per unit of volume fraction

    // The value beyond every kernel's reach (fraction 0), as valueAt computes it there.
    WEIR_HD float valueFarAway() const { return float(threshold * inverseSlope); }

    WEIR_HD float valueAt(const Vec3& x) const {
        Real fraction = 0;
        centres.forEachNear(x, kernelRadius2, [&](Index j) {
            const Real4 c = centres.pos[j];
            const Vec3 offset = x - c.xyz();
            if (lengthSquared(offset) < kernelRadius2) {
                const Real q2 = lengthSquared(matrix[j].times(offset));
                if (q2 < Real(1)) {
                    const Real s = Real(1) - q2;
                    fraction += c.w * s * s * s;
                }
            }
        });
        return float((threshold - fraction * weightScale) * inverseSlope);
    }
};

}  // namespace weir
