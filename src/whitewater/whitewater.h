// Spray, foam and bubbles after Ihmsen, Akinci, Becker & Teschner 2012, "Unified spray, foam and
// bubbles for particle-based fluids" (The Visual Computer 28): diffuse particles generated where
// the fluid traps air, breaks into wave crests and moves fast, classified by the fluid around
// them and advected from one saved fluid frame to the next, as a post-process (Houdini's
// whitewater solver works the same way). CPU (OpenMP) only.
#pragma once

#include <cstdint>
#include <vector>

#include "core/vec3.h"
#include "scene/scene.h"
#include "solver/particles.h"
#include "whitewater/diffuse_particles.h"

namespace weir {

// The scale of the fluid: what the thresholds and rates are measured against.
struct WhitewaterScale {
    double spacing = 0;         // d, the fluid's particle spacing [m]
    double smoothingRatio = 2;  // h / d: the neighbourhood of the potentials and classification
    Vec3d gravity{0, -9.81, 0};
    Box container;           // diffuse particles that leave it are removed
    double flowSpeed = 1.0;  // U [m/s]: sqrt(2 g H) + the fastest initial speed (flowSpeedOf)

    double neighbourRadius() const { return smoothingRatio * spacing; }
};

// U = sqrt(2 |g| H) + max |v| of a run's first frame, H the fluid's extent along gravity there (at
// least one spacing): the speed a falling or thrown fluid reaches, as scene/setup.cpp estimates
// it, measured on the frame so that a run and its post-process agree.
double flowSpeedOf(const HostParticles& firstFrame, const Vec3d& gravity, double spacing);

// The paper's settings, with every threshold in physical units as a multiple of the scene's
// scale, so that one set works for every scene. Ranges are [min, max] of the paper's clamp
// Phi(I, min, max) = (min(I, max) - min(I, min)) / (max - min).
struct WhitewaterSettings {
    // Trapped air: v_diff = sum_j |v_ij| (1 - v^_ij . x^_ij) W(x_ij) / sum_lattice W, in m/s (a
    // weighted mean relative speed: the paper's sum over the sum of W over a full lattice
    // neighbourhood, (pi / 3) (h / d)^3, so that it does not grow with the smoothing ratio);
    // the range in U.
    double trappedAirMin = 0.1, trappedAirMax = 0.5;
    // Wave crest: kappa = sum_j (1 - n^_i . n^_j) W(x_ij) / sum_lattice W over the neighbours
    // behind the surface (x^_ji . n^_i < 0) that are at the surface themselves, dimensionless;
    // counted only at the surface (asymmetry >= below) and where the particle moves along its
    // normal (v^_i . n^_i >= waveCrestAlignment).
    double waveCrestMin = 0.05, waveCrestMax = 0.25;
    double waveCrestAlignment = 0.6;
    // The surface: the weighted mean direction away from the neighbours, |a| = |sum_j x^_ij W| /
    // sum_j W, is 0 inside the fluid and 0.30-0.35 in the top layer of a flat surface (h = 2d-3d).
    double surfaceAsymmetry = 0.2;
    // Kinetic energy per unit mass, e = |v|^2 / 2, in J/kg; the range as speeds, in U.
    double kineticSpeedMin = 0.3, kineticSpeedMax = 0.9;
    // Diffuse particles per fluid particle per second at full potential (k_ta, k_wc).
    double trappedAirRate = 100, waveCrestRate = 100;
    // Classification by the fluid neighbours within h, as a share of a full neighbourhood
    // (4/3 pi (h/d)^3 particles; 33.5 at h = 2d): spray below sprayBelow (6.0 at 2d, the
    // paper's 6), bubbles above bubbleAbove (20.1 at 2d, the paper's 20), foam between.
    double sprayBelow = 0.18, bubbleAbove = 0.6;
    // Foam lives lifetime x uniform(0.5, 1.5) seconds, then dissolves.
    double foamLifetime = 2.0;
    // Bubbles: dv/dt = -buoyancy g + (v_fluid - v) / tau, tau = dragTime sqrt(h / |g|); they rise
    // through the fluid at buoyancy |g| tau (0.5 sqrt(|g| h): 0.3 m/s at h = 4 cm).
    double buoyancy = 2.0, dragTime = 0.25;
    // The new particles' sideways speed: up to this share of the fluid particle's speed, outwards
    // from its path.
    double spread = 0.1;
    // At most this many diffuse particles: generation stops at the cap (a run never explodes).
    std::size_t maxParticles = 2'000'000;
    // Sub-steps per frame interval; 0: enough that no diffuse particle moves further than h / 2
    // at speed 2U in one.
    int substeps = 0;

    // Throws std::invalid_argument naming the setting and the allowed range.
    void check() const;
};

// The paper's potentials of one fluid frame, per particle, each clamped to [0, 1].
struct WhitewaterPotentials {
    std::vector<float> trappedAir, waveCrest, kinetic;
    // Unclamped, for --explain and the docs: v_diff [m/s], kappa, e [J/kg].
    std::vector<float> rawTrappedAir, rawWaveCrest, rawKinetic;
};
WhitewaterPotentials computePotentials(const HostParticles& fluid, const WhitewaterScale& scale,
                                       const WhitewaterSettings& settings);

// What one frame interval did.
struct WhitewaterStep {
    std::size_t born = 0;       // generated
    std::size_t capped = 0;     // not generated: the cap was reached
    std::size_t left = 0;       // removed: outside the container
    std::size_t dissolved = 0;  // removed: foam past its lifetime
    int substeps = 0;
};

class Whitewater {
   public:
    // Throws std::invalid_argument for bad settings or scale.
    Whitewater(const WhitewaterScale& scale, const WhitewaterSettings& settings);

    // Advances the diffuse particles over one frame interval of dt seconds: new ones from the
    // fluid at the interval's start (`from`, frame number fromIndex, which keys the random
    // numbers), all moved in sub-steps through that fluid, then classified by `to`, the fluid at
    // the interval's end.
    WhitewaterStep advance(const HostParticles& from, std::int64_t fromIndex,
                           const HostParticles& to, double dt);

    // Classifies every diffuse particle by the fluid around it (advance does so at its end).
    void classify(const HostParticles& fluid);

    const DiffuseParticles& particles() const { return particles_; }
    DiffuseParticles& particles() { return particles_; }
    const WhitewaterScale& scale() const { return scale_; }
    const WhitewaterSettings& settings() const { return settings_; }

   private:
    WhitewaterScale scale_;
    WhitewaterSettings settings_;
    DiffuseParticles particles_;
};

}  // namespace weir
