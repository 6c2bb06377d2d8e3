// CUDA-OpenGL interop for `weir view`: when the simulation runs on the GPU that also draws, each
// frame's positions and colour values go straight from the solver's device arrays into the
// renderer's vertex buffers, with no copy through the host.
#pragma once

#include <memory>
#include <string>

#include "render/colour_map.h"
#include "render/renderer.h"
#include "solver/simulation.h"

namespace weir {

class ParticleInterop {
   public:
    virtual ~ParticleInterop() = default;
    // Writes the simulation's current particles into the renderer's buffers (a current OpenGL
    // context is needed) and tells the renderer to draw them.
    virtual void update(Renderer& renderer, ColourField field, double radius) = 0;
    virtual std::string description() const = 0;
};

// An interop path for this simulation and the current OpenGL context, or null (and the reason in
// *why) when there is none: a CPU simulation, a build without CUDA, or an OpenGL context on
// another device than the simulation's (e.g. Mesa's software renderer).
std::unique_ptr<ParticleInterop> makeParticleInterop(Simulation& simulation, std::string* why);

}  // namespace weir
