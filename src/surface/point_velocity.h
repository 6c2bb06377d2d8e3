// The particles' velocity at given points near the fluid (a surface mesh's vertices), so that a
// mesh can be motion-blurred: the kernel-weighted mean of the particles around each point.
#pragma once

#include <vector>

#include "core/vec3.h"
#include "solver/particles.h"

namespace weir {

// For each point, the mean velocity of the particles within `radius` of it, weighted by
// (1 - r^2 / radius^2)^3 (the surface field's kernel, surface_field.h); zero where no particle is
// within reach. On the CPU (OpenMP), over the particles sorted into bins as for the surface.
// radius must be > 0 and finite (std::invalid_argument otherwise).
std::vector<Vec3f> particleVelocityAt(const HostParticles& particles,
                                      const std::vector<Vec3f>& points, double radius);

}  // namespace weir
