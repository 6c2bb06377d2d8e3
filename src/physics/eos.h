// Equations of state: the paper's eq. 3, P = k (rho - rho0), and Tait's for weakly compressible
// water, P = B ((rho / rho0)^gamma - 1) with gamma = 7 and B = rho0 c^2 / gamma (Monaghan 1994,
// Becker & Teschner 2007), so that both have the same speed of sound c = sqrt(dP / drho) at rho0.
// Negative pressure (tension, where the free surface lacks neighbours) is scaled by
// negativePressureScale: 0 clamps it (the default), 1 keeps it as the equation gives it.
#pragma once

#include <cmath>

#include "physics/sph_params.h"

namespace weir {

WEIR_HD inline Real pressureFromDensity(const SphParams& params, Real rho) {
    Real p;
    if (params.eos == EosKind::Tait) {
        const Real x = rho * params.invRestDensity;
        const Real x2 = x * x, x4 = x2 * x2;
        p = params.taitB * (x4 * x2 * x - Real(1));  // gamma = 7 by multiplications
    } else {
        p = params.stiffness * (rho - params.restDensity);
    }
    return p < Real(0) ? p * params.negativePressureScale : p;
}

// The density at which the equation of state gives pressure p (p >= 0; inverse of the above).
WEIR_HD inline Real densityFromPressure(const SphParams& params, Real p) {
    if (params.eos == EosKind::Tait) {
        return params.restDensity * std::pow(Real(1) + p / params.taitB, Real(1) / Real(7));
    }
    return params.restDensity + p / params.stiffness;
}

}  // namespace weir
