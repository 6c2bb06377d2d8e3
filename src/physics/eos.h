// Equation of state, paper eq. 3: P = k (rho - rho0), optionally clamped at zero.
#pragma once

#include "physics/sph_params.h"

namespace weir {

WEIR_HD inline Real pressureFromDensity(const SphParams& params, Real rho) {
    Real p = params.stiffness * (rho - params.restDensity);
    return (params.clampNegativePressure && p < Real(0)) ? Real(0) : p;
}

}  // namespace weir
