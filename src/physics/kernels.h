// Müller et al. 2003 smoothing kernels (paper eqs. 2, 4, 5), written in q = r / h so that
// they stay in float range for any h.
#pragma once

#include <cmath>

#include "core/config.h"

namespace weir {

constexpr double kPi = 3.14159265358979323846;

// Constant factors of the kernels for one smoothing radius h.
struct KernelCoefficients {
    Real h = 1, h2 = 1, invH = 1, invH2 = 1;
    Real poly6 = 0;        // 315 / (64 pi h^3):      W(r)      = poly6 * (1 - q^2)^3
    Real spikyGrad = 0;    // -45 / (pi h^4):         grad W(r) = spikyGrad * (1 - q)^2 * r / |r|
    Real viscLaplace = 0;  // 45 / (pi h^5):          lap W(r)  = viscLaplace * (1 - q)

    static KernelCoefficients forRadius(double h) {
        KernelCoefficients k;
        k.h = Real(h);
        k.h2 = Real(h * h);
        k.invH = Real(1.0 / h);
        k.invH2 = Real(1.0 / (h * h));
        k.poly6 = Real(315.0 / (64.0 * kPi * h * h * h));
        k.spikyGrad = Real(-45.0 / (kPi * h * h * h * h));
        k.viscLaplace = Real(45.0 / (kPi * h * h * h * h * h));
        return k;
    }
};

// Wendland's C2 kernel (Wendland 1995; Dehnen & Aly 2012) with support radius h, q = r / h:
// W = 21 / (2 pi h^3) (1 - q)^4 (1 + 4 q), grad W = -210 / (pi h^5) (1 - q)^3 r_vec. Positive
// definite Fourier transform, so no pairing instability at any neighbour count, and a smooth
// gradient to the origin (the spiky kernel's does not vanish there). `gradientScale` divides
// the gradient by its lattice moment (wendlandLatticeMoment), so that on the seeded lattice the
// discrete gradient of a linear field, the divergence of a linear flow and Morris's Laplacian of a
// quadratic one are exact: at h = 2 d the raw moment is 0.950 (the spiky kernel's 0.947), and a
// tank at rest would hold a pressure gradient 5% steeper than rho0 g.
struct WendlandKernel {
    Real h = 1, invH = 1, h2 = 1;
    Real w = 0;     // 21 / (2 pi h^3)
    Real grad = 0;  // -210 / (pi h^5) / lattice moment

    static WendlandKernel forRadius(double h, double latticeMoment = 1.0) {
        WendlandKernel k;
        k.h = Real(h);
        k.invH = Real(1.0 / h);
        k.h2 = Real(h * h);
        k.w = Real(21.0 / (2.0 * kPi * h * h * h));
        k.grad = Real(-210.0 / (kPi * h * h * h * h * h) / latticeMoment);
        return k;
    }

    // The same kernel with its gradient divided by `latticeMoment` as well.
    WendlandKernel withGradientDividedBy(Real latticeMoment) const {
        WendlandKernel k = *this;
        k.grad = grad / latticeMoment;
        return k;
    }

    // W at distance r (0 <= r; zero outside the support).
    WEIR_HD Real value(Real r) const {
        const Real q = r * invH;
        if (q >= Real(1)) {
            return Real(0);
        }
        const Real t = Real(1) - q, t2 = t * t;
        return w * t2 * t2 * (Real(1) + Real(4) * q);
    }
    // g with grad W = g * r_vec (r_vec = x_i - x_j, 0 <= r < h); negative.
    WEIR_HD Real gradientFactor(Real r) const {
        const Real t = Real(1) - r * invH;
        return grad * t * t * t;
    }
    // dg/dr of gradientFactor (0 <= r < h): the Hessian of W is g I + (dg/dr) r_vec r_vec^T / r.
    WEIR_HD Real gradientFactorSlope(Real r) const {
        const Real t = Real(1) - r * invH;
        return Real(-3) * grad * t * t * invH;
    }
};

// Over a cubic lattice of spacing 1 around a site, for Wendland C2 with radius `ratio`:
// -(V / 3) sum_j r_j . grad W_j with V = 1 / (the lattice sum of W), the volume the mass
// calibration gives each particle (scene/setup.cpp). 1 for the continuum kernel.
inline double wendlandLatticeMoment(double ratio) {
    const WendlandKernel k = WendlandKernel::forRadius(ratio);
    const int reach = int(std::ceil(ratio));
    double sumW = 0, moment = 0;
    for (int i = -reach; i <= reach; ++i) {
        for (int j = -reach; j <= reach; ++j) {
            for (int l = -reach; l <= reach; ++l) {
                const double r2 = double(i * i + j * j + l * l), r = std::sqrt(r2);
                if (r < ratio) {
                    sumW += double(k.value(Real(r)));
                    moment += double(k.gradientFactor(Real(r))) * r2;
                }
            }
        }
    }
    return -moment / (3.0 * sumW);
}

// The lattice sum of Wendland C2 with radius `ratio` (W d^3): the mass calibration's divisor.
inline double wendlandLatticeSum(double ratio) {
    const WendlandKernel k = WendlandKernel::forRadius(ratio);
    const int reach = int(std::ceil(ratio));
    double sum = 0;
    for (int i = -reach; i <= reach; ++i) {
        for (int j = -reach; j <= reach; ++j) {
            for (int l = -reach; l <= reach; ++l) {
                const double r = std::sqrt(double(i * i + j * j + l * l));
                sum += double(k.value(Real(r)));
            }
        }
    }
    return sum;
}

// poly6 W at squared distance r2 (zero outside the support).
WEIR_HD inline Real poly6(const KernelCoefficients& k, Real r2) {
    if (r2 >= k.h2) {
        return Real(0);
    }
    Real t = Real(1) - r2 * k.invH2;
    return k.poly6 * t * t * t;
}

// 1 / sqrt(x), one instruction on the GPU.
WEIR_HD inline Real reciprocalSqrt(Real x) {
#if defined(__CUDA_ARCH__)
    return rsqrt(x);
#else
    return Real(1) / std::sqrt(x);
#endif
}

// 1 / x: on the GPU the hardware's approximate reciprocal (about 1 ulp) instead of an IEEE
// division, which costs the force loop some ten instructions per neighbour.
WEIR_HD inline Real reciprocal(Real x) {
#if defined(__CUDA_ARCH__) && !defined(WEIR_DOUBLE)
    return __fdividef(1.0f, x);
#else
    return Real(1) / x;
#endif
}

// Magnitude factor g of the spiky gradient, grad W = g * r_vec (r_vec = x_i - x_j, 0 < r < h),
// given r and 1 / r.
WEIR_HD inline Real spikyGradientFactor(const KernelCoefficients& k, Real r, Real invR) {
    Real t = Real(1) - r * k.invH;
    return k.spikyGrad * t * t * invR;
}
WEIR_HD inline Real spikyGradientFactor(const KernelCoefficients& k, Real r) {
    return spikyGradientFactor(k, r, Real(1) / r);
}

// Laplacian of the viscosity kernel at distance r (0 <= r < h).
WEIR_HD inline Real viscosityLaplacian(const KernelCoefficients& k, Real r) {
    return k.viscLaplace * (Real(1) - r * k.invH);
}

// Sum over a cubic lattice of spacing 1 of poly6 with radius `ratio` (W d^3, in double): 1 for an
// exact kernel; the particle mass is corrected by it so that the seeded lattice sits at the rest
// density (scene/setup.cpp).
inline double latticeKernelSum(double ratio) {
    const int reach = int(std::ceil(ratio));
    const double poly6 = double(KernelCoefficients::forRadius(ratio).poly6);  // as the step has it
    double sum = 0;
    for (int i = -reach; i <= reach; ++i) {
        for (int j = -reach; j <= reach; ++j) {
            for (int l = -reach; l <= reach; ++l) {
                const double r2 = double(i * i + j * j + l * l);
                if (r2 < ratio * ratio) {
                    const double t = 1.0 - r2 / (ratio * ratio);
                    sum += poly6 * t * t * t;
                }
            }
        }
    }
    return sum;
}

}  // namespace weir
