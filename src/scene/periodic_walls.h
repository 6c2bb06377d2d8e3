// Boundary particles of a container with periodic axes (container.periodic): walls only on the
// faces of the other axes, and their periodic images past the periodic faces.
#pragma once

#include "scene/boundary.h"
#include "scene/scene.h"

namespace weir {

// sampleBoundary (scene/boundary.h) for a container with periodic axes: the faces of the axes
// with walls only, sampled so that each periodic axis holds a whole number of spacings starting
// d/2 from its lower face (the sheets continue seamlessly across the periodic faces, as a fluid
// lattice of a whole number of spacings does), extended past the periodic faces as far as the
// fluid's ghost copies reach (solver/periodic_ghosts.h): the fluid near a periodic face finds the
// walls beyond it, and the images' volumes psi sum the walls they would see. Obstacles are
// sampled as sampleBoundary does, without images (keep them a few h from periodic faces).
// Without periodic axes: sampleBoundary itself.
BoundarySamples samplePeriodicBoundary(const Scene& scene, double d, double h, int layers);

}  // namespace weir
