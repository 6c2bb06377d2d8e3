// Every number the step needs, derived once from the scene (scene/derive.cpp) and passed by
// value to the stages.
#pragma once

#include "core/config.h"
#include "core/vec3.h"
#include "physics/kernels.h"
#include "physics/wall_weight.h"

namespace weir {

enum class IntegratorKind : int { SemiImplicitEuler = 0, ExplicitEuler = 1 };
// Linear: the paper's eq. 3. Tait: gamma = 7 (physics/eos.h).
enum class EosKind : int { Linear = 0, Tait = 1 };
// Simple: the paper's collision response at the walls. Particles: Akinci et al. 2012 boundary
// particles that add to density and pressure force (the simple response stays as a safety net).
// Pressure force: Symmetric, m_j (p_i / rho_i^2 + p_j / rho_j^2) (consistent: tends to grad p),
// or the paper's eq. 4, m_j (p_i + p_j) / (2 rho_j) (tends to grad p / 2). physics/stages.h.
enum class PressureForm : int { Symmetric = 0, Paper = 1 };
enum class WallKind : int { Simple = 0, Particles = 1 };
// The fluid model. Paper: Müller et al. 2003 as the paper has it (summation density with poly6,
// pressure by the spiky gradient, viscosity by the viscosity kernel's Laplacian), two passes
// over the neighbours. DeltaSph: weakly compressible SPH as modern codes run it (Antuono et al.
// 2010; Fourtakas et al. 2019; DualSPHysics): Wendland C2, density by the continuity equation
// with density diffusion, the fluid's own viscosity by Morris et al. 1997's operator, a small
// artificial viscosity only between approaching particles, walls that extrapolate pressure and
// velocity; one pass over the neighbours per step. physics/delta_sph.h.
enum class FluidModel : int { Paper = 0, DeltaSph = 1 };

struct SphParams {
    KernelCoefficients kernel;
    Real mass = 0;            // per particle, kg
    Real restDensity = 0;     // rho0, kg/m^3
    Real invRestDensity = 0;  // 1 / rho0
    EosKind eos = EosKind::Linear;
    PressureForm pressureForce = PressureForm::Symmetric;
    Real stiffness = 0;              // k of eq. 3, m^2/s^2 (= c^2)
    Real taitB = 0;                  // B of Tait's equation, Pa (= rho0 c^2 / 7)
    Real negativePressureScale = 0;  // share of negative pressure kept: 0 clamps, 1 keeps
    Real viscosity = 0;              // mu of eq. 5, Pa s
    Vec3 gravity;                    // m/s^2
    Real timeStep = 0;               // s: the fixed step, or the first adaptive one
    // Adaptive step (physics/time_step.h), recomputed every step on the device.
    bool adaptiveTimeStep = false;
    Real speedOfSound = 0;     // c, m/s
    Real cflNumber = 0.4;      // dt <= cflNumber h / (c + max |v|)
    Real forceNumber = 0.25;   // dt <= forceNumber sqrt(h / max |a|)
    Real viscousLimit = 1e30;  // dt <= 0.125 h^2 / nu, s (constant)
    Real maxTimeStep = 1e30;   // s
    Real minCflSpeed = 0;      // the CFL condition's least max |v|, m/s (DFSPH: the flow's scale)
    IntegratorKind integrator = IntegratorKind::SemiImplicitEuler;

    Vec3 boxMin, boxMax;  // container walls
    // Bit a set: axis a is periodic (container.periodic): no walls on its two faces, a particle
    // that leaves through one comes back through the other, and neighbours are found across
    // them (solver/periodic_ghosts.h). 0: walls all round, and no extra work.
    int periodicAxes = 0;
    Real restitution = 0;  // normal speed kept after a wall contact
    Real friction = 0;     // share of tangential speed removed on contact
    WallKind walls = WallKind::Simple;
    WallWeightTable wallWeight;  // the simple walls' planes (physics/wall_weight.h); empty: bare
    Real wallViscosity = 0;      // mu against boundary particles, Pa s (0: free slip)
    Real maxSpeed = 0;           // blow-up bound, m/s

    // The delta-SPH model (FluidModel::DeltaSph; physics/delta_sph.h).
    FluidModel model = FluidModel::Paper;
    WendlandKernel wendland;  // with the lattice-moment correction of its gradient
    // 1, or where `wendland` keeps the raw gradient (DFSPH's solves, whose prediction must be
    // that of the summed density), the raw gradient's lattice moment: the viscous forces and the
    // reported pressure then apply the correction themselves.
    Real rawGradientMoment = 1;
    Real dynamicViscosity = 0;     // mu, the fluid's own, Pa s (Morris et al. 1997)
    Real viscositySoftening = 0;   // eta^2 = 0.01 (h/2)^2 of Morris's operator, m^2
    Real artificialViscosity = 0;  // alpha c (h/2), m^2/s (Monaghan 1992; approaching pairs)
    Real densityDiffusion = 0;     // delta c h, m^2/s (Molteni & Colagrossi 2009)
    Vec3 hydrostaticGradient;      // rho0 g / c^2, kg/m^4: the hydrostatic part that density
                                   // diffusion leaves alone (Fourtakas et al. 2019)
    bool noSlip = false;           // walls: no-slip (true) or free slip
    // Particle shifting (physics/delta_sph.h): A of delta x = -A dt sum V_j (1 + R ..) grad W,
    // m^2/s (0: off); 1 / W(d) of its tensile term; the most it moves a particle in a step, m;
    // the relative speed across the kernel from which it acts in full, m/s; the kernel sums
    // under which a particle, or a neighbour, is at a free surface (it shifts along it only).
    Real shifting = 0;
    Real shiftingInvW = 0;
    // Monaghan's (2000) artificial pressure against the tensile instability: in a pair where a
    // particle is in tension, its p / rho^2 adds R |p / rho^2| (W_ij / W(h / 3))^4 of repulsion
    // (R = tensileCorrection, 0: off; 1 / W(h / 3) = invKernelAtReference).
    Real tensileCorrection = 0;
    Real invKernelAtReference = 0;
    Real shiftingLimit = 0;
    Real shiftingGateSpeed = 0;
    Real surfaceKernelSum = 0;
    Real surfaceNeighbourKernelSum = 0;
    Real splashKernelSum = 0;  // under it (a drop, a thin sheet) a particle is not shifted
    Real maxDensityRatio = 0;  // blow-up bound on rho / rho0 (0: none)

    // Divergence-free SPH (solver "dfsph", solver/dfsph/): the mean density error at which the
    // constant-density solve stops, and the mean error dt (drho/dt) / rho0 at which the
    // divergence-free one does (0: that solve off); sweeps a solve may take at most.
    Real densityTolerance = 0;
    Real divergenceTolerance = 0;
    Real worstDensityTolerance = 0;  // ... and the largest one particle's may keep (0: any)
    bool dfsphSecondOrder = false;   // the density solve predicts the move to second order
    int maxSolverIterations = 0;
    Real minFactorDenominator = 0;  // the least denominator of the factor alpha, kg^2/m^8
};

// Whether axis a (0, 1, 2 for x, y, z) is periodic.
WEIR_HD inline bool isPeriodic(const SphParams& params, int a) {
    return ((params.periodicAxes >> a) & 1) != 0;
}

}  // namespace weir
