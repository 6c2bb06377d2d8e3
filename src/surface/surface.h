// Surface reconstruction: particles in, a closed triangle mesh of the fluid's surface out, on the
// CPU (OpenMP) or the GPU (CUDA).
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

#include "core/backend.h"
#include "core/vec3.h"
#include "solver/particles.h"
#include "surface/triangle_mesh.h"

namespace weir {

// Input the surface cannot be built from (no particles, a non-finite position, a grid too large
// for the memory limit); the message names the value and what is allowed.
class SurfaceError : public std::runtime_error {
   public:
    using std::runtime_error::runtime_error;
};

// The scalar field the surface is the iso-surface of (surface_field.h, anisotropy.h).
enum class SurfaceField {
    Isotropic,    // Zhu & Bridson: distance to the kernel-weighted mean of the particles
    Anisotropic,  // Yu & Turk: kernels stretched along each particle's neighbours, smoothed centres
};

// "isotropic" or "anisotropic"; std::invalid_argument naming the value and the allowed names.
SurfaceField parseSurfaceField(const std::string& name);
const char* surfaceFieldName(SurfaceField field);
std::string surfaceFieldList();  // "isotropic, anisotropic"

struct SurfaceOptions {
    SurfaceField field = SurfaceField::Isotropic;
    // sliver_cleanup.h: no edge under 1% of a cell, no angle under 1 degree
    bool removeSlivers = true;
    double spacing = 0;   // particle spacing d [m]; 0: the median nearest-neighbour distance
    double cellSize = 0;  // marching-cubes cell edge [m]; 0: d / 2
    double iso = 0;       // iso-value in particle spacings: 0 is the fluid's surface, > 0 inflates
    double kernelRadiusRatio = 2;                     // kernel radius R / d
    std::int64_t maxSamples = std::int64_t(1) << 26;  // field samples allowed (12 bytes each)
};

// Everything derived from the options and the particles, in metres.
struct SurfacePlan {
    SurfaceField field = SurfaceField::Isotropic;
    bool removeSlivers = true;
    double spacing = 0;
    bool spacingEstimated = false;
    double kernelRadius = 0;    // R
    double particleRadius = 0;  // r (surface_field.h)
    double cellSize = 0;
    double iso = 0;  // in particle spacings
    // Anisotropic field: the volume fraction at the surface and its fall per spacing
    // (anisotropy.h).
    double fractionThreshold = 0, fractionSlope = 0;
    Vec3d origin;  // the first field sample; the lattice covers the particles plus R + 2 cells
    int dims[3] = {0, 0, 0};  // samples per axis
    Vec3d particleMin, particleMax;
    double binSize = 0;  // edge of the particle bins, >= R / 2
    std::int64_t sampleCount() const {
        return std::int64_t(dims[0]) * std::int64_t(dims[1]) * std::int64_t(dims[2]);
    }
};

// Validates the options (std::invalid_argument naming the option, its value and what is allowed)
// and the particles (SurfaceError), and sizes the field lattice.
SurfacePlan planSurface(const HostParticles& particles, const SurfaceOptions& options);

// The median distance of (up to a few thousand sampled) particles to their nearest neighbour:
// the lattice spacing for a seeded frame, a little less for a compressed fluid. 0 if no particle
// has a neighbour at a positive distance.
double estimateParticleSpacing(const HostParticles& particles);

// The iso-surface of the plan's field (surface_field.h, anisotropy.h), by marching cubes, then
// (plan.removeSlivers) cleaned of slivers on the host (sliver_cleanup.h); vertices are shared
// between triangles (closed where the fluid is), normals point out of the fluid.
TriangleMesh reconstructSurface(Backend backend, const HostParticles& particles,
                                const SurfacePlan& plan);
TriangleMesh reconstructSurface(Backend backend, const HostParticles& particles,
                                const SurfaceOptions& options, SurfacePlan* planOut = nullptr);

}  // namespace weir
