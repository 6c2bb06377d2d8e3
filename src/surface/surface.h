// Surface reconstruction: particles in, a closed triangle mesh of the fluid's surface out, on the
// CPU (OpenMP) or the GPU (CUDA).
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

#include "core/backend.h"
#include "core/stage_timer.h"
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

// How far (in cells, where the field changes by a cell per cell) marching cubes' vertices are
// kept from the lattice's samples. A vertex moves along its edge, on average by about a third of
// this (sliver_cleanup_test.cpp), at most by half a cell where both ends of its edge lie within
// the margin of iso (there the field barely crosses iso, and any noise moves the vertex as far).
// Measured on a jittered ball: 0.02 leaves 4 bad triangles of 265k in a synthetic frame, 0.03
// none, 0.05 none with a vertex moving 0.021 cells on average instead of 0.009.
constexpr double kSurfaceSnapFraction = 0.03;

struct SurfaceOptions {
    SurfaceField field = SurfaceField::Isotropic;
    // sliver_cleanup.h: no edge under 1% of a cell, no angle under 1 degree
    bool removeSlivers = true;
    double spacing = 0;   // particle spacing d [m]; 0: the median nearest-neighbour distance
    double cellSize = 0;  // marching-cubes cell edge [m]; 0: d / 2
    double iso = 0;       // iso-value in particle spacings: 0 is the fluid's surface, > 0 inflates
    double kernelRadiusRatio = 2;  // kernel radius R / d
    // Field samples allowed near the fluid (kBytesPerSurfaceSample each); 0: as many as half the
    // backend's free memory holds, up to kMaxSurfaceSamples.
    std::int64_t maxSamples = 0;
    // Marching cubes' vertices kept this fraction of a cell from the lattice's samples (plan's
    // snapMargin); 0 leaves the field as it is.
    double snapFraction = kSurfaceSnapFraction;
};

// The sparse lattice (sparse_lattice.h) stores the samples of the blocks of 8^3 samples near
// some particle: a sample costs its value (4 bytes) and two 64-bit prefix sums (vertices,
// triangles). Kernels index samples with 32-bit integers; the lattice's block table holds one
// entry (12 bytes) per block of the particles' bounding box; the particle bins (grid/dense_grid.h)
// one per bin, widened past R / 2 where a sparse frame's box would need more.
constexpr std::int64_t kBytesPerSurfaceSample = 20;
constexpr std::int64_t kMaxSurfaceSamples = (std::int64_t(1) << 31) - 512;
constexpr std::int64_t kMaxSurfaceBlocks = std::int64_t(1) << 28;
constexpr std::int64_t kMaxSurfaceBins = std::int64_t(1) << 27;
constexpr std::int64_t kMaxSurfaceVertices = std::int64_t(1) << 32;  // 32-bit triangle indices

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
    double binSize = 0;           // edge of the particle bins, >= R / 2
    std::int64_t maxSamples = 0;  // SurfaceOptions::maxSamples
    // Field samples within this of iso move out to it (snappedOffIso, marching_cubes.h), in the
    // field's units (particle spacings): kSurfaceSnapFraction of a cell.
    double snapMargin = 0;
    std::int64_t sampleCount() const {
        return std::int64_t(dims[0]) * std::int64_t(dims[1]) * std::int64_t(dims[2]);
    }
};

// Validates the options (std::invalid_argument naming the option, its value and what is allowed)
// and the particles (SurfaceError), and sizes the field lattice.
SurfacePlan planSurface(const HostParticles& particles, const SurfaceOptions& options);
// The same plan from the particles' bounds alone (particles that stay on the GPU: their bounds
// reduced there); options.spacing must be given.
SurfacePlan planSurfaceForBounds(const Vec3d& low, const Vec3d& high,
                                 const SurfaceOptions& options);

// The median distance of (up to a few thousand sampled) particles to their nearest neighbour:
// the lattice spacing for a seeded frame, a little less for a compressed fluid. 0 if no particle
// has a neighbour at a positive distance.
double estimateParticleSpacing(const HostParticles& particles);

// The message of a sparse lattice that needs `samples` samples near the fluid, more than `limit`
// (given by the user, or from the free memory of `memoryName`): the numbers and a cell size that
// fits.
std::string surfaceTooLargeMessage(const SurfacePlan& plan, std::int64_t samples,
                                   std::int64_t limit, bool limitGiven, const char* memoryName);

// The iso-surface of the plan's field (surface_field.h, anisotropy.h), by marching cubes over a
// sparse lattice (sparse_lattice.h), then (plan.removeSlivers) cleaned of slivers on the host
// (sliver_cleanup.h); vertices are shared between triangles (closed where the fluid is), normals
// point out of the fluid. `stages` gets each stage's wall time in ms where given ("surface
// upload", "surface bins", "surface anisotropy", "surface blocks", "surface field", "surface
// vertices", "surface triangles", "surface download", "surface slivers").
TriangleMesh reconstructSurface(Backend backend, const HostParticles& particles,
                                const SurfacePlan& plan, StageTimes* stages = nullptr);
TriangleMesh reconstructSurface(Backend backend, const HostParticles& particles,
                                const SurfaceOptions& options, SurfacePlan* planOut = nullptr);

}  // namespace weir
