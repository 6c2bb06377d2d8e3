// Surface planning (spacing, lattice, limits), the CPU instantiation and the backend dispatch.
#include "surface/surface.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>
#include <vector>

#include "core/exec_cpu.h"
#include "surface/sliver_cleanup.h"
#include "surface/sparse_lattice.h"
#include "surface/surface_field.h"
#include "surface/surface_pipeline.h"

namespace weir {

#if defined(WEIR_HAS_CUDA)
TriangleMesh reconstructSurfaceCuda(const HostParticles& particles, const SurfacePlan& plan,
                                    StageTimes* stages);
#endif

namespace {

std::string text(double value) {
    std::ostringstream out;
    out << value;
    return out.str();
}

void requireNonNegative(double value, const char* name, const char* zeroMeans) {
    if (!(value >= 0) || !std::isfinite(value)) {
        throw std::invalid_argument(std::string(name) + " is " + text(value) +
                                    ", must be a number > 0 (or 0 for " + zeroMeans + ")");
    }
}

}  // namespace

SurfaceField parseSurfaceField(const std::string& name) {
    for (SurfaceField field : {SurfaceField::Isotropic, SurfaceField::Anisotropic}) {
        if (name == surfaceFieldName(field)) {
            return field;
        }
    }
    throw std::invalid_argument("surface field '" + name +
                                "' is not known; allowed: " + surfaceFieldList());
}

const char* surfaceFieldName(SurfaceField field) {
    return field == SurfaceField::Anisotropic ? "anisotropic" : "isotropic";
}

std::string surfaceFieldList() { return "isotropic, anisotropic"; }

double estimateParticleSpacing(const HostParticles& particles) {
    const std::size_t n = particles.size();
    std::vector<std::uint32_t> byX(n);
    std::iota(byX.begin(), byX.end(), 0u);
    std::sort(byX.begin(), byX.end(),
              [&](std::uint32_t a, std::uint32_t b) { return particles.x[a] < particles.x[b]; });
    const auto distance2 = [&](std::uint32_t a, std::uint32_t b) {
        const double dx = double(particles.x[a]) - particles.x[b];
        const double dy = double(particles.y[a]) - particles.y[b];
        const double dz = double(particles.z[a]) - particles.z[b];
        return dx * dx + dy * dy + dz * dz;
    };
    // Nearest neighbours by a sweep along x from each sampled particle, stopped once the x gap
    // alone exceeds the best distance found.
    const std::size_t samples = std::min<std::size_t>(n, 4096);
    std::vector<double> nearest;
    nearest.reserve(samples);
    for (std::size_t s = 0; s < samples; ++s) {
        const std::size_t k = s * n / samples;
        const std::uint32_t i = byX[k];
        double best2 = std::numeric_limits<double>::infinity();
        for (int direction : {-1, 1}) {
            for (std::size_t m = k;;) {
                if ((direction < 0 && m == 0) || (direction > 0 && m + 1 == n)) {
                    break;
                }
                m = direction < 0 ? m - 1 : m + 1;
                const double gap = double(particles.x[byX[m]]) - particles.x[i];
                if (gap * gap >= best2) {
                    break;
                }
                const double d2 = distance2(i, byX[m]);
                if (d2 > 0 && d2 < best2) {
                    best2 = d2;
                }
            }
        }
        if (std::isfinite(best2)) {
            nearest.push_back(std::sqrt(best2));
        }
    }
    if (nearest.empty()) {
        return 0;
    }
    std::nth_element(nearest.begin(), nearest.begin() + nearest.size() / 2, nearest.end());
    return nearest[nearest.size() / 2];
}

namespace {

// The options' checks, shared by both ways of planning.
void validateSurfaceOptions(const SurfaceOptions& options) {
    requireNonNegative(options.spacing, "spacing", "an estimate from the particles");
    requireNonNegative(options.cellSize, "cell size", "half the particle spacing");
    if (!(options.snapFraction >= 0 && options.snapFraction <= 0.25)) {
        throw std::invalid_argument("snap fraction is " + text(options.snapFraction) +
                                    ", must be in [0, 0.25] cells");
    }
    if (!(options.kernelRadiusRatio >= 1 && options.kernelRadiusRatio <= 5)) {
        throw std::invalid_argument("kernel radius ratio is " + text(options.kernelRadiusRatio) +
                                    ", must be in [1, 5] particle spacings");
    }
    if (options.maxSamples < 0 || (options.maxSamples > 0 && options.maxSamples < 8)) {
        throw std::invalid_argument("sample limit is " + text(double(options.maxSamples)) +
                                    ", must be at least 8 (or 0 for half the free memory)");
    }
}

SurfacePlan planForBounds(const Vec3d& low, const Vec3d& high, double spacing,
                          bool spacingEstimated, const SurfaceOptions& options);

}  // namespace

SurfacePlan planSurface(const HostParticles& particles, const SurfaceOptions& options) {
    validateSurfaceOptions(options);
    const std::size_t n = particles.size();
    if (n == 0) {
        throw SurfaceError("there are no particles to build a surface from");
    }
    // Bounds and the first non-finite position, on all cores.
    double low[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, high[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    std::int64_t firstBad = std::int64_t(n);
    const Real* coords[3] = {particles.x.data(), particles.y.data(), particles.z.data()};
#pragma omp parallel for schedule(static) reduction(min                                \
                                                    : low[:3], firstBad) reduction(max \
                                                                                   : high[:3])
    for (std::int64_t i = 0; i < std::int64_t(n); ++i) {
        for (int a = 0; a < 3; ++a) {
            const double value = coords[a][i];
            if (!std::isfinite(value)) {
                firstBad = std::min(firstBad, i);
            }
            low[a] = std::min(low[a], value);
            high[a] = std::max(high[a], value);
        }
    }
    if (firstBad < std::int64_t(n)) {
        const std::size_t i = std::size_t(firstBad);
        throw SurfaceError("particle " + std::to_string(i) + " has position " +
                           text(particles.x[i]) + " " + text(particles.y[i]) + " " +
                           text(particles.z[i]) + ", every coordinate must be finite");
    }
    double spacing = options.spacing;
    if (spacing == 0) {
        spacing = estimateParticleSpacing(particles);
        if (!(spacing > 0)) {
            throw SurfaceError("cannot estimate the particle spacing from " + std::to_string(n) +
                               " particle(s) at one point; give the spacing");
        }
    }
    return planForBounds(Vec3d(low[0], low[1], low[2]), Vec3d(high[0], high[1], high[2]), spacing,
                         options.spacing == 0, options);
}

SurfacePlan planSurfaceForBounds(const Vec3d& low, const Vec3d& high,
                                 const SurfaceOptions& options) {
    validateSurfaceOptions(options);
    if (!(options.spacing > 0)) {
        throw std::invalid_argument("spacing is " + text(options.spacing) +
                                    ", must be given (> 0) to plan a surface from bounds alone");
    }
    for (int a = 0; a < 3; ++a) {
        if (!std::isfinite(low[a]) || !std::isfinite(high[a]) || !(low[a] <= high[a])) {
            throw SurfaceError("the particles' bounds are " + text(low.x) + " " + text(low.y) +
                               " " + text(low.z) + " to " + text(high.x) + " " + text(high.y) +
                               " " + text(high.z) + ": every coordinate must be finite");
        }
    }
    return planForBounds(low, high, options.spacing, false, options);
}

namespace {

SurfacePlan planForBounds(const Vec3d& low, const Vec3d& high, double spacing,
                          bool spacingEstimated, const SurfaceOptions& options) {
    SurfacePlan plan;
    plan.particleMin = low;
    plan.particleMax = high;
    plan.spacing = spacing;
    plan.spacingEstimated = spacingEstimated;
    const double ratio = options.kernelRadiusRatio;
    plan.kernelRadius = ratio * plan.spacing;
    plan.particleRadius = zhuBridsonParticleRadius(ratio) * plan.spacing;
    plan.cellSize = options.cellSize > 0 ? options.cellSize : 0.5 * plan.spacing;
    plan.iso = options.iso;
    plan.field = options.field;
    plan.removeSlivers = options.removeSlivers;
    // Deep in the fluid the field is -r / d, beyond the kernel's reach (R - r) / d.
    double isoLow = -plan.particleRadius / plan.spacing;
    double isoHigh = (plan.kernelRadius - plan.particleRadius) / plan.spacing;
    if (plan.field == SurfaceField::Anisotropic) {
        // The volume fraction is about 1 deep in the fluid and 0 beyond every kernel.
        plan.fractionThreshold = kAnisotropicThreshold;
        plan.fractionSlope = anisotropicFractionSlope(ratio);
        isoLow = (plan.fractionThreshold - 1) / plan.fractionSlope;
        isoHigh = plan.fractionThreshold / plan.fractionSlope;
    }
    if (!(plan.iso > isoLow && plan.iso < isoHigh)) {
        throw std::invalid_argument("iso-value is " + text(plan.iso) + ", must be in (" +
                                    text(isoLow) + ", " + text(isoHigh) +
                                    ") particle spacings (0 is the fluid surface)");
    }

    // Lattice over the particles plus the kernel radius and two cells, so that the surface never
    // touches its faces and comes out closed. Only its blocks near the fluid are stored
    // (sparse_lattice.h), but its block table covers the whole box.
    const double margin = plan.kernelRadius + 2 * plan.cellSize;
    plan.origin = plan.particleMin - Vec3d(margin, margin, margin);
    plan.maxSamples = options.maxSamples;
    plan.snapMargin = options.snapFraction * plan.cellSize / plan.spacing;
    double samples = 1, blocks = 1;
    for (int a = 0; a < 3; ++a) {
        const double extent = plan.particleMax[a] - plan.particleMin[a] + 2 * margin;
        const double count = std::ceil(extent / plan.cellSize) + 1;
        samples *= count;
        blocks *= std::ceil(count / kSurfaceBlockEdge);
        plan.dims[a] = int(std::min(count, 2e9));
    }
    if (blocks > double(kMaxSurfaceBlocks)) {
        const double limit = double(kMaxSurfaceBlocks) * kSurfaceBlockSamples;
        std::ostringstream message;
        message << "the surface lattice's box would span " << plan.dims[0] << " x " << plan.dims[1]
                << " x " << plan.dims[2] << " = " << samples << " samples at cell size "
                << plan.cellSize << " m (particles spanning "
                << text(plan.particleMax.x - plan.particleMin.x) << " x "
                << text(plan.particleMax.y - plan.particleMin.y) << " x "
                << text(plan.particleMax.z - plan.particleMin.z) << " m), more than the limit of "
                << limit << " for its block table; use a cell size of at least "
                << plan.cellSize * std::cbrt(samples / limit) * 1.05 << " m";
        throw SurfaceError(message.str());
    }
    // Bins of R / 2, wider where the box would need more than kMaxSurfaceBins (a frame of a few
    // drops far apart): the field then looks at more particles per sample, but nothing grows
    // with the box but the bin table.
    plan.binSize = std::max(plan.kernelRadius / 2, plan.cellSize);
    double bins = 1;
    for (int a = 0; a < 3; ++a) {
        bins *= std::ceil((plan.particleMax[a] - plan.particleMin[a]) / plan.binSize + 1e-6) + 1;
    }
    if (bins > double(kMaxSurfaceBins)) {
        plan.binSize *= std::cbrt(bins / double(kMaxSurfaceBins)) * 1.01;
    }
    return plan;
}

}  // namespace

std::string surfaceTooLargeMessage(const SurfacePlan& plan, std::int64_t samples,
                                   std::int64_t limit, bool limitGiven, const char* memoryName) {
    std::ostringstream message;
    message << "the surface lattice near the fluid needs " << samples << " samples ("
            << samples / kSurfaceBlockSamples << " blocks of " << kSurfaceBlockSamples
            << ") at cell size " << plan.cellSize << " m, more than the limit of " << limit;
    if (limitGiven) {
        message << " given";
    } else {
        message << " (" << kBytesPerSurfaceSample << " bytes each in half the free memory of "
                << memoryName << ", at most " << kMaxSurfaceSamples << ")";
    }
    message << "; use a cell size of at least "
            << plan.cellSize * std::cbrt(double(samples) / double(limit)) * 1.05 << " m";
    return message.str();
}

TriangleMesh reconstructSurface(Backend backend, const HostParticles& particles,
                                const SurfacePlan& plan, StageTimes* stages) {
    TriangleMesh mesh;
    if (backend == Backend::Cuda) {
#if defined(WEIR_HAS_CUDA)
        mesh = reconstructSurfaceCuda(particles, plan, stages);
#else
        throw SurfaceError("this weir was built without CUDA; use the cpu backend");
#endif
    } else {
        CpuExec exec;
        mesh = extractSurface(exec, particles, plan, "host memory", stages);
    }
    if (plan.removeSlivers) {
        const auto start = std::chrono::steady_clock::now();
        removeSlivers(mesh, plan.cellSize);
        if (stages != nullptr) {
            stages->add("surface slivers", std::chrono::duration<double, std::milli>(
                                               std::chrono::steady_clock::now() - start)
                                               .count());
        }
    }
    return mesh;
}

TriangleMesh reconstructSurface(Backend backend, const HostParticles& particles,
                                const SurfaceOptions& options, SurfacePlan* planOut) {
    const SurfacePlan plan = planSurface(particles, options);
    if (planOut != nullptr) {
        *planOut = plan;
    }
    return reconstructSurface(backend, particles, plan);
}

}  // namespace weir
