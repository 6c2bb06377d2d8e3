// Parameter derivation and particle seeding for a scene.
#include "scene/setup.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <initializer_list>
#include <sstream>
#include <string>
#include <utility>

#include "core/exec_cpu.h"
#include "grid/cell_id.h"
#include "physics/kernels.h"
#include "scene/boundary.h"
#include "scene/lattice_seeder.h"
#include "scene/periodic_walls.h"
#include "scene/seeding.h"
#include "solver/simulation.h"

namespace weir {

namespace {

constexpr std::int64_t kDefaultParticleCount = 20000;
// delta-SPH's defaults: alpha of the artificial viscosity, delta of the density diffusion (the
// value of Molteni & Colagrossi 2009 and DualSPHysics), the CFL number on h.
constexpr double kDefaultArtificialViscosity = 0.01;
constexpr double kDefaultDensityDiffusion = 0.1;
// Monaghan's (2000) R for his artificial pressure (his value for n = 4): delta-SPH keeps negative
// pressure, and without it two particles in tension closed onto one point (Lobovsky's dam break
// at 240 over H, on the ceiling where its run-up jet hits, H200 2026-12-04).
constexpr double kDefaultTensileCorrection = 0.2;
// Below h = 2 d it is off unless the scene asks for it: its reach h / 3 is then under 0.7 d, so it
// never acts on the lattice's neighbours, only on a pair already run into each other, all at once
// ((W(0) / W(h / 3))^4 = 22) and stiffer than the time step allows. At h = 1.5 d it blew up
// dam_break_obstacle and tsunami_on_step at 100k particles (density 1.6 rho0 where a splash
// lands), which run to the end without it (H200, 2026-12-04).
constexpr double kTensileCorrectionLeastRatio = 2.0;

// The tensile correction's R: the scene's, else the default where h >= 2 d.
double tensileCorrectionOf(const Scene& scene) {
    if (scene.tensileCorrection) {
        return *scene.tensileCorrection;
    }
    return scene.smoothingRatio >= kTensileCorrectionLeastRatio ? kDefaultTensileCorrection : 0.0;
}
constexpr double kDeltaSphCfl = 0.25;
// Divergence-free SPH (solver "dfsph"): its CFL number, tolerances and sweep limit are the
// scene's "dfsph" settings (scene/scene.h); its force condition dt <= kDfsphForceNumber
// sqrt(h / max |a|) (a: the forces but
// pressure): measured on a tank at rest (0.2 m deep, d = 0.01 m), 0.25 (WCSPH's) let the solves'
// linear prediction fail (compression past 50% in 0.03 s); 0.1 holds it (RMS speed 0.04 m/s).
constexpr double kDfsphForceNumber = 0.1;
// Particle shifting (physics/delta_sph.h): the largest shift a step, in spacings (a guard, not
// a paper's value: the shift of a healthy flow is a few thousandths of d a step); the relative
// speed across the kernel from which it acts in full, as a share of the flow's speed scale
// c / 10; and the kernel sums under which a particle (own) or a neighbour is at a free surface
// (the seeded lattice reads 1; at h = 2d its surface layer reads 0.89, and disorder and
// compression move the interior by about 2%).
constexpr double kShiftingLimit = 0.1;
constexpr double kShiftingGate = 0.1;
constexpr double kSurfaceKernelSum = 0.95;
constexpr double kSurfaceNeighbourKernelSum = 0.9;
constexpr double kSplashKernelSum =
    0.75;  // under it: a drop or a sheet, with no surface to slide along

// Steps per output frame at most: beyond, a time step is too small to run (and an int).
constexpr double kMaxStepsPerFrame = 1e9;

// An emitter's sites: a square lattice of spacing d over its disc (centred on a site) or its
// rectangle (sites d/2 in from its edges), at least one.
std::vector<Vec3d> emitterSites(const EmitterSpec& e, double d) {
    Vec3d u, v;
    e.planeAxes(u, v);
    std::vector<Vec3d> sites;
    if (e.isDisc) {
        const int reach = int(std::min(1e4, std::floor(e.radius / d)));
        for (int i = -reach; i <= reach; ++i) {
            for (int j = -reach; j <= reach; ++j) {
                if (double(i * i + j * j) * d * d <= e.radius * e.radius * (1 + 1e-9)) {
                    sites.push_back(e.center + u * (i * d) + v * (j * d));
                }
            }
        }
    } else {
        const int na = int(std::clamp(std::round(e.width / d), 1.0, 1e4));
        const int nb = int(std::clamp(std::round(e.height / d), 1.0, 1e4));
        for (int i = 0; i < na; ++i) {
            for (int j = 0; j < nb; ++j) {
                sites.push_back(e.center + u * ((i + 0.5 - 0.5 * na) * d) +
                                v * ((j + 0.5 - 0.5 * nb) * d));
            }
        }
    }
    return sites;
}

// Seconds an emitter lets fluid in over a run of `duration` seconds.
double emittingTime(const EmitterSpec& e, double duration) {
    return std::max(0.0, std::min(e.stop, duration) - e.start);
}

// Layers an emitter lets in over a run (physics/emitter.h: one at its start, then one every
// d / speed seconds).
std::int64_t emitterLayers(const EmitterSpec& e, double d, double duration) {
    if (e.start > duration) {
        return 0;
    }
    return std::int64_t(std::min(1e15, std::floor(emittingTime(e, duration) * e.speed / d))) + 1;
}

// Particles the emitters let in over the scene's duration at spacing d.
std::int64_t emittedCount(const Scene& scene, double d) {
    double count = 0;
    for (const EmitterSpec& e : scene.emitters) {
        count += double(emitterSites(e, d).size()) * double(emitterLayers(e, d, scene.duration));
    }
    return std::int64_t(std::min(count, 1e15));
}

std::int64_t countSeeds(const Scene& scene, double d, std::int64_t limit) {
    return sceneSeeds(scene, d, limit).count + emittedCount(scene, d);
}

double fluidVolume(const Scene& scene) {
    double v = 0;
    for (const FluidBlock& b : scene.blocks) {
        Vec3d e = b.box.max - b.box.min;
        v += e.x * e.y * e.z;
    }
    for (const FluidSphere& s : scene.spheres) {
        v += 4.0 / 3.0 * kPi * std::pow(s.sphere.radius, 3);
    }
    for (const EmitterSpec& e : scene.emitters) {  // what they let in over the run
        v += e.area() * e.speed * emittingTime(e, scene.duration);
    }
    return v;
}

// The spacing whose lattice holds closest to `wanted` particles (bisection on the count; counts
// past twice the wanted one are cut short, they only need to read as too many).
double spacingForCount(const Scene& scene, std::int64_t wanted) {
    const std::int64_t limit = 2 * wanted + 1;
    double guess = std::cbrt(fluidVolume(scene) / double(wanted));
    double lo = guess * 0.7, hi = guess * 1.4;  // count(lo) >= wanted >= count(hi)
    double best = guess;
    std::int64_t bestError = std::llabs(countSeeds(scene, guess, limit) - wanted);
    for (int it = 0; it < 40 && bestError > 0; ++it) {
        double mid = 0.5 * (lo + hi);
        std::int64_t count = countSeeds(scene, mid, limit);
        if (std::llabs(count - wanted) < bestError) {
            bestError = std::llabs(count - wanted);
            best = mid;
        }
        (count > wanted ? lo : hi) = mid;
        if (hi - lo < guess * 1e-7) {
            break;
        }
    }
    return best;
}

std::string fmt(double v) {
    std::ostringstream s;
    s.precision(4);
    s << v;
    return s.str();
}

// What host memory holds, checked before anything is seeded or sampled: the seeded arrays (unless
// the backend seeds) and, for a CPU run, the simulation's (solver/simulation.h's estimate in the
// leanest neighbour mode; makeSimulation checks the chosen one); the same reserve as
// checkMemoryFits.
struct HostBudget {
    std::size_t freeBytes = 0, usable = 0, perParticle = 0;
    std::int64_t maxParticles = kMaxParticles;
    // A CUDA run with its device's free memory given: what the GPU holds, if less.
    std::size_t deviceFreeBytes = 0, devicePerParticle = 0;
    std::int64_t deviceMaxParticles = kMaxParticles;

    explicit HostBudget(const SetupOptions& options) {
        freeBytes = options.hostFreeBytes ? *options.hostFreeBytes : CpuExec().freeMemoryBytes();
        const std::size_t reserve = (std::size_t(256) << 20) + freeBytes / 10;
        usable = freeBytes > reserve ? freeBytes - reserve : 0;
        // Seeded by the backend (a distributed run: each rank holds its share only): no limit
        // but the ids' here; makeSimulation checks each rank's memory.
        perParticle = options.seedOnDevice ? 0 : 8 * sizeof(Real);  // HostParticles
        if (options.backend == Backend::Cpu && !options.seedOnDevice) {
            perParticle += std::min(bytesPerParticleEstimate(NeighbourMode::Grid),
                                    bytesPerParticleEstimate(NeighbourMode::Dense));
        }
        if (perParticle > 0) {
            maxParticles = std::int64_t(
                std::min<std::size_t>(std::size_t(kMaxParticles), usable / perParticle));
        }
        if (options.backend == Backend::Cuda && options.deviceFreeBytes && !options.seedOnDevice) {
            deviceFreeBytes = *options.deviceFreeBytes;
            const std::size_t deviceReserve = (std::size_t(256) << 20) + deviceFreeBytes / 10;
            const std::size_t deviceUsable =
                deviceFreeBytes > deviceReserve ? deviceFreeBytes - deviceReserve : 0;
            devicePerParticle = std::min(bytesPerParticleEstimate(NeighbourMode::Grid),
                                         bytesPerParticleEstimate(NeighbourMode::Dense));
            deviceMaxParticles = std::int64_t(std::min<std::size_t>(
                std::size_t(kMaxParticles), deviceUsable / devicePerParticle));
        }
    }
    // The most particles that fit both.
    std::int64_t limit() const { return std::min(maxParticles, deviceMaxParticles); }

    // The SceneError for `count` particles (about, when estimated) at spacing d.
    SceneError tooMany(const std::string& where, double count, double d, bool about) const {
        const std::string hint =
            "; use a larger particles.spacing, or a smaller particles.count or --particles";
        if (count > double(kMaxParticles) && limit() == kMaxParticles) {
            return SceneError(where + ": " + (about ? "about " : "") + fmt(count) +
                              " particles at spacing " + fmt(d) + " m exceed the limit of " +
                              std::to_string(kMaxParticles) + " (32-bit particle ids)" + hint);
        }
        if (deviceMaxParticles < maxParticles) {
            return SceneError(where + ": " + (about ? "about " : "") + fmt(count) +
                              " particles at spacing " + fmt(d) + " m need about " +
                              fmt(count * double(devicePerParticle) / double(1 << 20)) +
                              " MiB of GPU memory (" + std::to_string(devicePerParticle) +
                              " bytes each) but the GPU has " +
                              std::to_string(deviceFreeBytes >> 20) + " MiB free: at most " +
                              std::to_string(deviceMaxParticles) + " particles fit" + hint);
        }
        return SceneError(
            where + ": " + (about ? "about " : "") + fmt(count) + " particles at spacing " +
            fmt(d) + " m need about " + fmt(count * double(perParticle) / double(1 << 20)) +
            " MiB of host memory (" + std::to_string(perParticle) + " bytes each) but it has " +
            std::to_string(freeBytes >> 20) + " MiB free: at most " + std::to_string(maxParticles) +
            " particles fit" + hint);
    }
};

// Throws SceneError when a derived parameter does not fit the solver's Real (float by default).
void requireReal(const std::string& where, const std::string& what, double value) {
    const bool fits = std::isfinite(value) && std::isfinite(double(Real(value))) &&
                      (value == 0 || Real(value) != Real(0));
    if (!fits) {
        throw SceneError(where + ": the derived " + what + " = " + fmt(value) +
                         " does not fit the solver's numbers (" + std::to_string(sizeof(Real) * 8) +
                         "-bit floating point); bring particles.spacing, fluid.restDensity, "
                         "fluid.stiffness, fluid.viscosity and gravity nearer everyday values");
    }
}

}  // namespace

HostParticles seedParticles(const Scene& scene, double spacing) {
    HostParticles particles;
    forEachSeed(sceneSeeds(scene, spacing),
                [&](const Vec3d& p, const Vec3d& v) { particles.push(p, v); });
    return particles;
}

namespace {

// The unit quaternion of the rotation whose matrix has these columns (a right-handed frame).
Real4 quaternionOf(const std::array<Vec3d, 3>& columns) {
    const double m[3][3] = {{columns[0].x, columns[1].x, columns[2].x},
                            {columns[0].y, columns[1].y, columns[2].y},
                            {columns[0].z, columns[1].z, columns[2].z}};
    const double trace = m[0][0] + m[1][1] + m[2][2];
    double x, y, z, w;
    if (trace > 0) {
        const double s = 2 * std::sqrt(trace + 1);
        w = s / 4;
        x = (m[2][1] - m[1][2]) / s;
        y = (m[0][2] - m[2][0]) / s;
        z = (m[1][0] - m[0][1]) / s;
    } else if (m[0][0] > m[1][1] && m[0][0] > m[2][2]) {
        const double s = 2 * std::sqrt(1 + m[0][0] - m[1][1] - m[2][2]);
        w = (m[2][1] - m[1][2]) / s;
        x = s / 4;
        y = (m[0][1] + m[1][0]) / s;
        z = (m[0][2] + m[2][0]) / s;
    } else if (m[1][1] > m[2][2]) {
        const double s = 2 * std::sqrt(1 + m[1][1] - m[0][0] - m[2][2]);
        w = (m[0][2] - m[2][0]) / s;
        x = (m[0][1] + m[1][0]) / s;
        y = s / 4;
        z = (m[1][2] + m[2][1]) / s;
    } else {
        const double s = 2 * std::sqrt(1 + m[2][2] - m[0][0] - m[1][1]);
        w = (m[1][0] - m[0][1]) / s;
        x = (m[0][2] + m[2][0]) / s;
        y = (m[1][2] + m[2][1]) / s;
        z = s / 4;
    }
    const double norm = std::sqrt(x * x + y * y + z * z + w * w);
    return {Real(x / norm), Real(y / norm), Real(z / norm), Real(w / norm)};
}

// The rigid bodies' states and their boundary particles in each body's frame (centred on its
// centre of mass, axes the box's): sampled as obstacles are, with Akinci's psi from each body's
// own particles (capped at a full neighbourhood's volume, as the walls').
RigidBodySetup rigidBodySetup(const Scene& scene, double d, double h, double particleMass) {
    RigidBodySetup out;
    const int layers = boundaryLayers(h, d, true);
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
        const BodySpec& spec = scene.bodies[i];
        const Box bounds = spec.bounds();
        const BoundaryParticles built =
            buildBoundary(sampleBodySurface(spec, d, layers), bounds, h, scene.restDensity,
                          particleMass / scene.restDensity, BoundaryKernel::Wendland);
        if (built.pos.empty()) {  // far smaller than a spacing: nothing to stand for it
            const Vec3d size = bounds.max - bounds.min;
            throw SceneError("scene '" + scene.sourcePath + "': field 'bodies[" +
                             std::to_string(i) + "]' is a body " +
                             fmt(std::max({size.x, size.y, size.z})) +
                             " m across, too small for a boundary particle at spacing " + fmt(d) +
                             " m: make it larger or the particles finer");
        }
        const Vec3d centre = spec.centre();
        for (const Real4& p : built.pos) {
            out.particles.push_back(
                {Real(p.x - centre.x), Real(p.y - centre.y), Real(p.z - centre.z), p.w});
            out.owner.push_back(int(i));
        }
        RigidBody body;
        body.x = Vec3(centre);
        body.home = body.x;
        body.v = Vec3(spec.velocity);
        body.omega = Vec3(spec.angularVelocity);
        body.shape = spec.isMesh     ? BodyShape::Mesh
                     : spec.isSphere ? BodyShape::Sphere
                                     : BodyShape::Box;
        const Vec3d half = (bounds.max - bounds.min) * 0.5;
        body.halfSize = Vec3(half);
        body.boxCentre = Vec3((bounds.min + bounds.max) * 0.5 - centre);
        if (spec.drive == BodyDrive::Floating) {
            const double m = spec.mass;
            body.invMass = Real(1 / m);
            Vec3d inertia;
            if (spec.isMesh) {
                // About the principal axes of the uniform solid the mesh bounds, whatever its
                // density says of the mass (a body of given mass is uniform too).
                const PrincipalAxes principal = principalAxesOf(inertiaTensorOf(spec.solid, m));
                inertia = principal.values;
                body.axes = quaternionOf(principal.axes);
            } else if (spec.isSphere) {
                const double i = 0.4 * m * spec.sphere.radius * spec.sphere.radius;
                inertia = Vec3d(i, i, i);
            } else {
                const Vec3d size = half * 2.0;
                inertia =
                    Vec3d(size.y * size.y + size.z * size.z, size.x * size.x + size.z * size.z,
                          size.x * size.x + size.y * size.y) *
                    (m / 12);
            }
            body.invInertia = Vec3(Real(1 / inertia.x), Real(1 / inertia.y), Real(1 / inertia.z));
        } else {
            body.motion =
                spec.drive == BodyDrive::Oscillate ? BodyMotion::Oscillating : BodyMotion::Rotating;
            body.amplitude = Vec3(spec.amplitude);
            body.period = Real(spec.period);
            body.ramp = Real(spec.ramp);
            body.rate = Vec3(spec.rate);
        }
        out.bodies.push_back(body);
    }
    return out;
}

}  // namespace

SimulationSetup buildSetup(const Scene& scene, const SetupOptions& options, SetupReport* out) {
    SetupReport report;
    auto say = [&](const std::string& line) { report.lines.push_back(line); };
    const std::string where = "scene '" + scene.sourcePath + "'";
    const HostBudget budget(options);

    // Resolution: spacing given, or the spacing whose lattice holds the wanted count.
    report.fluidVolume = fluidVolume(scene);
    const std::optional<std::int64_t> wantedCount =
        options.particleCount
            ? options.particleCount
            : (scene.spacing ? std::nullopt
                             : std::optional<std::int64_t>(
                                   scene.particleCount.value_or(kDefaultParticleCount)));
    if (wantedCount && *wantedCount > budget.limit()) {
        throw budget.tooMany(where, double(*wantedCount),
                             std::cbrt(report.fluidVolume / double(*wantedCount)), true);
    }
    if (options.particleCount) {
        report.spacing = spacingForCount(scene, *options.particleCount);
        say("spacing d = " + fmt(report.spacing) + " m, for about " +
            std::to_string(*options.particleCount) + " particles (--particles)");
    } else if (scene.spacing) {
        report.spacing = *scene.spacing;
        say("spacing d = " + fmt(report.spacing) + " m (scene)");
    } else {
        std::int64_t wanted = scene.particleCount.value_or(kDefaultParticleCount);
        report.spacing = spacingForCount(scene, wanted);
        say("spacing d = " + fmt(report.spacing) + " m, for about " + std::to_string(wanted) +
            " particles" + (scene.particleCount ? " (scene)" : " (default count)"));
    }
    const double d = report.spacing;
    SimulationSetup setup;
    SceneSeeds seeds = sceneSeeds(scene, d, budget.limit());
    if (seeds.count == 0 && scene.emitters.empty()) {
        throw SceneError(where + ": the fluid holds no particle at spacing " + fmt(d) +
                         " m; make the blocks or spheres larger or the spacing smaller");
    }
    if (seeds.overLimit) {
        throw budget.tooMany(where, seeds.estimate, d, true);
    }
    // Smoothing radius and mass (§5.2: mass from density, volume and count). The lattice sum
    // corrects the mass so that the initial lattice sits exactly at the rest density; without
    // it poly6 at h = 2d reads 1% dense and the fluid starts with a jolt.
    const bool deltaModel = scene.model == FluidModelName::DeltaSph;
    if (deltaModel && scene.walls == WallModel::Simple) {
        report.warnings.push_back(
            "walls.model \"simple\" with the delta-SPH model is not yet proven stable at scale "
            "(measured: blow-ups at 100k particles with smoothingRatio 1.5 on a GPU, before the "
            "walls' push became the gradient of their density share; not re-measured since): use "
            "walls.model \"particles\" (delta-SPH's default) or fluid.model \"paper\"");
    }
    const bool dfsph = scene.solver == "dfsph";
    if (dfsph) {
        if (!deltaModel) {
            throw SceneError(where +
                             ": solver \"dfsph\" runs with the delta-sph model's kernel and "
                             "viscosity, but fluid.model is \"paper\"; remove fluid.model (or set "
                             "it to \"delta-sph\"), or use solver \"wcsph\"");
        }
        if (scene.walls == WallModel::Simple) {
            throw SceneError(where +
                             ": solver \"dfsph\" needs walls of boundary particles, but "
                             "walls.model is \"simple\"; set walls.model to \"particles\" (the "
                             "default with delta-sph), or use solver \"wcsph\"");
        }
    }
    setup.method = scene.solver;
    const double h = scene.smoothingRatio * d;
    report.smoothingRadius = h;
    report.latticeKernelSum = deltaModel ? wendlandLatticeSum(scene.smoothingRatio)
                                         : latticeKernelSum(scene.smoothingRatio);
    const double mass = scene.restDensity * d * d * d / report.latticeKernelSum;
    report.gradientMoment = deltaModel ? wendlandLatticeMoment(scene.smoothingRatio) : 1.0;
    say(deltaModel
            ? "fluid model delta-SPH: Wendland C2 kernel, density by the continuity equation "
              "with density diffusion, the fluid's own viscosity (Morris et al. 1997), walls "
              "that extrapolate pressure and velocity (fluid.model \"paper\": the paper's)"
            : "fluid model: the paper's (Müller et al. 2003: poly6 density, spiky pressure "
              "gradient, viscosity kernel; fluid.model \"delta-sph\" for the modern one)");
    say("smoothing radius h = " + fmt(h) + " m (" + fmt(scene.smoothingRatio) + " d)");
    say("particle mass m = " + fmt(mass) + " kg = rho0 d^3 / " + fmt(report.latticeKernelSum) +
        (deltaModel ? " (lattice sum of Wendland C2" : " (lattice sum of poly6") +
        ", so the initial fluid is at rest density)");

    // Expected speeds: free fall over the deepest column, plus any initial speed. Gravity along a
    // periodic axis is a body force that drives a flow (a channel's), not a weight that walls
    // hold: no column stands on it, so it neither sets the fall height nor makes the fluid
    // hydrostatic at rest.
    Vec3d weight = scene.gravity;
    for (int a = 0; a < 3; ++a) {
        if (scene.periodic[std::size_t(a)]) {
            weight[a] = 0;
        }
    }
    const double g = length(weight);
    Vec3d up = g > 0 ? weight / -g : Vec3d(0, 1, 0);
    double floor = 1e300, top = -1e300, initialSpeed = 0;
    for (int c = 0; c < 8; ++c) {
        Vec3d corner((c & 1) ? scene.container.max.x : scene.container.min.x,
                     (c & 2) ? scene.container.max.y : scene.container.min.y,
                     (c & 4) ? scene.container.max.z : scene.container.min.z);
        floor = std::min(floor, dot(corner, up));
    }
    for (const FluidBlock& b : scene.blocks) {
        for (int c = 0; c < 8; ++c) {
            Vec3d corner((c & 1) ? b.box.max.x : b.box.min.x, (c & 2) ? b.box.max.y : b.box.min.y,
                         (c & 4) ? b.box.max.z : b.box.min.z);
            top = std::max(top, dot(corner, up));
        }
        initialSpeed = std::max(initialSpeed, length(b.velocity));
    }
    for (const FluidSphere& s : scene.spheres) {
        top = std::max(top, dot(s.sphere.center, up) + s.sphere.radius);
        initialSpeed = std::max(initialSpeed, length(s.velocity));
    }
    report.fluidHeight = std::max(0.0, top - floor);
    // Bodies: a floating one falls from where it starts; each moves at its initial speed, a
    // driven one at its motion's peak.
    double bodyFall = 0;
    for (const BodySpec& body : scene.bodies) {
        const Box b = body.bounds();
        const double reach = length(b.max - b.min) * 0.5;
        if (body.drive == BodyDrive::Floating) {
            bodyFall = std::max(bodyFall, dot((b.min + b.max) * 0.5, up) - reach - floor);
            initialSpeed = std::max(initialSpeed,
                                    length(body.velocity) + length(body.angularVelocity) * reach);
        } else if (body.drive == BodyDrive::Oscillate) {
            initialSpeed = std::max(initialSpeed, length(body.amplitude) * 2 * kPi / body.period);
        } else {
            initialSpeed = std::max(initialSpeed, length(body.rate) * reach);
        }
    }
    report.expectedSpeed =
        std::sqrt(2.0 * g * std::max(report.fluidHeight, bodyFall)) + initialSpeed;
    // Emitters: their speed, and the fall from each to the floor.
    for (const EmitterSpec& e : scene.emitters) {
        report.expectedSpeed = std::max(
            report.expectedSpeed,
            std::sqrt(e.speed * e.speed + 2.0 * g * std::max(0.0, dot(e.center, up) - floor)));
    }
    if (report.expectedSpeed <= 0) {
        report.expectedSpeed = 0.1;
    }
    say("expected top speed " + fmt(report.expectedSpeed) +
        " m/s = sqrt(2 g H) + initial, H = " + fmt(report.fluidHeight) + " m");

    // Stiffness: speed of sound ten times the top speed keeps density within ~1% (Monaghan).
    double stiffness;
    if (scene.stiffness) {
        stiffness = *scene.stiffness;
        say("stiffness k = " + fmt(stiffness) + " m^2/s^2 (scene)");
        if (std::sqrt(stiffness) < 5.0 * report.expectedSpeed) {
            report.warnings.push_back(
                "stiffness k = " + fmt(stiffness) + " gives a speed of sound of " +
                fmt(std::sqrt(stiffness)) + " m/s, under 5x the expected speed " +
                fmt(report.expectedSpeed) + " m/s: the fluid will compress visibly; k >= " +
                fmt(std::pow(10 * report.expectedSpeed, 2)) + " keeps it within ~1%");
        }
    } else {
        stiffness = std::pow(10.0 * report.expectedSpeed, 2);
        say("stiffness k = " + fmt(stiffness) + " m^2/s^2: speed of sound c = 10 x expected speed");
    }
    const double c = std::sqrt(stiffness);
    report.speedOfSound = c;
    const double taitB = scene.restDensity * stiffness / 7.0;
    if (scene.eos == EquationOfState::Tait) {
        say("pressure by Tait's equation P = B ((rho / rho0)^7 - 1), B = rho0 c^2 / 7 = " +
            fmt(taitB) + " Pa: the same speed of sound, stiffer under compression");
    } else {
        say("pressure P = k (rho - rho0): the paper's eq. 3");
    }
    say(scene.paperPressureForce
            ? "pressure force by the paper's eq. 4, m_j (p_i + p_j) / (2 rho_j): it tends to "
              "grad p / 2, so pressures at rest read twice hydrostatic"
            : "pressure force m_j (p_i / rho_i^2 + p_j / rho_j^2) grad W (symmetric, Monaghan "
              "1992): conserves momentum and tends to grad p, so pressures are hydrostatic at "
              "rest (the paper's eq. 4 tends to grad p / 2)");
    if (scene.negativePressureScale == 0) {
        say("negative pressure clamped to 0: surface particles lack neighbours, read light and "
            "would pull into clumps");
    } else {
        say("negative pressure kept at " + fmt(scene.negativePressureScale) +
            " of its value (1 is the equation as written)");
    }

    if (!scene.preset.empty()) {
        const FluidPreset* preset = fluidPreset(scene.preset);
        say("fluid " + scene.preset + ": rho0 = " + fmt(preset->density) +
            " kg/m^3, mu = " + fmt(preset->viscosity) + " Pa s (" + preset->source + ")" +
            (scene.restDensity != preset->density
                 ? "; rho0 overridden to " + fmt(scene.restDensity) + " (scene)"
                 : ""));
    }
    // Viscosity. The paper's model: the scene's, or the fluid's own plus an artificial one that
    // damps the pressure waves of a weakly compressible fluid (kinematic nu = alpha h c / 10 with
    // alpha = 0.1, Monaghan's form), all of it through eq. 5. delta-SPH: the fluid's own alone
    // through Morris's operator; pressure waves are damped by density diffusion and a small
    // artificial viscosity between approaching particles only.
    double viscosity;  // the paper's model: mu of eq. 5; delta-SPH: the fluid's own mu
    double alpha = 0, delta = 0;
    const double halfH = 0.5 * h;  // the smoothing length of the codes that write h for h/2
    if (deltaModel) {
        viscosity = scene.viscosity.value_or(scene.physicalViscosity);
        alpha = scene.artificialViscosity.value_or(kDefaultArtificialViscosity);
        delta = scene.densityDiffusion.value_or(kDefaultDensityDiffusion);
        say("viscosity: the fluid's own mu = " + fmt(viscosity) +
            " Pa s (nu = " + fmt(viscosity / scene.restDensity) + " m^2/s" +
            (scene.viscosity ? ", scene" : (scene.preset.empty() ? ", no fluid.preset" : "")) +
            ") by Morris et al. 1997's operator (eta^2 = 0.01 (h/2)^2)");
        say("artificial viscosity alpha = " + fmt(alpha) +
            " between approaching particles only (Monaghan 1992): at most nu = alpha c (h/2) / "
            "10 = " +
            fmt(alpha * c * halfH / 10) + " m^2/s where particles close in, 0 elsewhere");
        say("density diffusion delta = " + fmt(delta) + " (Molteni & Colagrossi 2009): D = delta " +
            "c (h/2) = " + fmt(delta * c * halfH) +
            " m^2/s on density differences, less their hydrostatic part (Fourtakas et al. 2019)");
        say("kernel gradient divided by its lattice moment " + fmt(report.gradientMoment) +
            ", so that on the seeded lattice a linear pressure, a linear flow and a quadratic flow "
            "are differentiated exactly");
        const double tensile = tensileCorrectionOf(scene);
        if (!dfsph && tensile > 0) {
            say("tensile correction R = " + fmt(tensile) +
                " (Monaghan 2000's artificial pressure): a pair with a particle in tension gains "
                "R |p / rho^2| (W / W(h/3))^4 of repulsion, so tension cannot pull two particles "
                "onto one point (in spray and where a jet tears; nothing where p >= 0)");
        } else if (!dfsph && scene.tensileCorrection) {
            say("tensile correction off (fluid.tensileCorrection 0): particles in tension may "
                "close onto one point in violent flows, which stops the run");
        } else if (!dfsph) {
            say("tensile correction off below h = 2 d: its reach h / 3 is under 0.7 d, so it "
                "would act only on pairs already run together, stiffer than the time step "
                "(fluid.tensileCorrection turns it on)");
        }
        const double shifting = scene.shifting.value_or(0.0);
        if (shifting > 0) {
            say("particle shifting (Sun et al. 2017's delta-plus-SPH form" +
                std::string(shifting != 1 ? ", " + fmt(shifting) + " x its coefficient" : "") +
                "): each step particles move down the gradient of their concentration by A dt "
                "grad C, A = 2 h c / 10 = " +
                fmt(shifting * 2 * h * c / 10) + " m^2/s, at most " + fmt(kShiftingLimit) +
                " d a step, in full where neighbours' velocities differ by " +
                fmt(kShiftingGate * c / 10) +
                " m/s or more (none at rest), along the surface "
                "only at a free surface, none next to walls; keeps the particles from lining up "
                "and tearing apart where the flow stretches them");
        } else {
            say("particle shifting off (fluid.shifting 1 turns it on: it keeps a sheared or "
                "stretched flow's particles from tearing apart, as in the Taylor-Green vortex, "
                "but is not yet safe in violent flows, docs/physics.md)");
        }
        say(dfsph ? "density summed over the neighbours every step (solver dfsph); the "
                    "artificial viscosity's c is the one above, though no pressure uses it"
                  : "density by the continuity equation, starting hydrostatic in each fluid "
                    "block (rho = rho0 + rho0 |g| depth / c^2), rho0 in spheres");
    } else if (scene.viscosity) {
        const double artificial = scene.restDensity * 0.1 * h * c / 10.0;
        viscosity = *scene.viscosity;
        say("viscosity mu = " + fmt(viscosity) + " Pa s (scene)");
        if (viscosity < 0.05 * artificial) {
            report.warnings.push_back(
                "viscosity mu = " + fmt(viscosity) + " Pa s is under 5% of the " + fmt(artificial) +
                " Pa s that damps this resolution's pressure waves: expect a noisy, ringing "
                "density and possibly a blow-up; leave fluid.viscosity unset (the fluid's own "
                "viscosity comes from fluid.preset) or use mu >= " +
                fmt(artificial) + ", or fluid.model \"delta-sph\"");
        }
    } else {
        const double artificial = scene.restDensity * 0.1 * h * c / 10.0;
        viscosity = artificial + scene.physicalViscosity;
        say("viscosity mu = " + fmt(viscosity) + " Pa s = " + fmt(scene.physicalViscosity) +
            " (the fluid's) + " + fmt(artificial) +
            " (artificial, nu = 0.1 h c / 10, damps pressure waves)");
    }

    // Time step: CFL, viscous diffusion and body-force limits; whole steps per output frame.
    const double nu = viscosity / scene.restDensity;
    const double cfl = deltaModel ? kDeltaSphCfl : 0.4;
    // DFSPH: no speed of sound; the CFL condition on the flow's speed alone.
    double dtCfl =
        dfsph ? scene.dfsph.cfl * d / report.expectedSpeed : cfl * h / (c + report.expectedSpeed);
    const double viscousLength = deltaModel ? halfH : h;
    double dtViscous = nu > 0 ? 0.125 * viscousLength * viscousLength / nu : 1e300;
    double dtForce = g > 0 ? (dfsph ? kDfsphForceNumber : 0.25) * std::sqrt(h / g) : 1e300;
    double dtStable = std::min({dtCfl, dtViscous, dtForce});
    double dt = dtStable;
    const bool adaptive = scene.adaptiveTimeStep.value_or(!scene.timeStep);
    if (scene.timeStep) {
        dt = *scene.timeStep;
        if (dt > dtStable) {
            report.warnings.push_back("time step " + fmt(dt) + " s is above the stable limit " +
                                      fmt(dtStable) +
                                      " s (CFL, viscosity, force): expect the fluid to blow up; "
                                      "leave time.timeStep unset to use the limit");
        }
    }
    report.frameInterval = 1.0 / scene.frameRate;
    const double steps = std::ceil(report.frameInterval / dt - 1e-9);
    if (!(steps <= kMaxStepsPerFrame)) {
        throw SceneError(
            where + ": a time step of " + fmt(dt) + " s" +
            (scene.timeStep ? " (time.timeStep)"
                            : " (the stable limit: CFL " + fmt(dtCfl) + ", viscous " +
                                  fmt(dtViscous) + ", force " + fmt(dtForce) + " s)") +
            " takes " + fmt(steps) + " steps per frame of " + fmt(report.frameInterval) +
            " s, more than the " + fmt(kMaxStepsPerFrame) +
            " allowed; use a larger time.timeStep or time.frameRate, a larger particles.spacing, "
            "or a lower fluid.stiffness or fluid.viscosity");
    }
    report.stepsPerFrame = std::max(1, int(steps));
    dt = report.frameInterval / report.stepsPerFrame;
    report.frames = std::int64_t(std::floor(scene.duration * scene.frameRate + 1e-9));
    if (dfsph) {
        const Scene::DfsphSettings& settings = scene.dfsph;
        say("pressure solver dfsph (Bender & Koschier 2017): incompressible, no speed of sound "
            "(the stiffness above is unused); each step " +
            (settings.divergenceErrorPercent > 0
                 ? "a divergence-free solve (mean " + fmt(settings.divergenceErrorPercent) +
                       "% of rho0 per step) and "
                 : std::string("no divergence-free solve (dfsph.divergenceError 0) and ")) +
            "a constant-density solve (mean density error under " +
            fmt(scene.dfsph.densityErrorPercent) + "%" +
            (settings.worstDensityErrorPercent > 0
                 ? ", every particle's under " + fmt(settings.worstDensityErrorPercent) + "%"
                 : std::string()) +
            "), at most " + std::to_string(scene.dfsph.maxSweeps) +
            " Jacobi sweeps each (scene \"dfsph\")");
    }
    if (adaptive && dfsph) {
        say("time step adaptive, recomputed every step on the device: min(" + fmt(scene.dfsph.cfl) +
            " d / max(max|v|, " + fmt(report.expectedSpeed) + " m/s), " + fmt(kDfsphForceNumber) +
            " sqrt(h / max|a|), 0.125 (h/2)^2 / nu = " + fmt(dtViscous) +
            " s), the last step before each frame cut to land on it; about " + fmt(dt) + " s (" +
            std::to_string(report.stepsPerFrame) + " per frame at the expected speed; CFL " +
            fmt(dtCfl) + ", force " + fmt(dtForce) + ")");
    } else if (adaptive) {
        say("time step adaptive, recomputed every step on the device: min(" + fmt(cfl) +
            " h / (c + max|v|), 0.25 sqrt(h / max|a|), 0.125 " + (deltaModel ? "(h/2)" : "h") +
            "^2 / nu = " + fmt(dtViscous) +
            " s), the last step before each frame cut to land on it; " + "about " + fmt(dt) +
            " s (" + std::to_string(report.stepsPerFrame) +
            " per frame at the expected speed; CFL " + fmt(dtCfl) + ", force " + fmt(dtForce) +
            ")");
    } else {
        say("time step " + fmt(dt) + " s, fixed (" + std::to_string(report.stepsPerFrame) +
            " per frame; limits: CFL " + fmt(dtCfl) + ", viscous " + fmt(dtViscous) + ", force " +
            fmt(dtForce) + ")");
    }
    if (scene.smoothingRatio < 1.5) {
        report.warnings.push_back(
            "smoothingRatio " + fmt(scene.smoothingRatio) + " gives each particle only about " +
            fmt(4.0 / 3.0 * kPi * std::pow(scene.smoothingRatio, 3)) +
            " neighbours: density estimates will be noisy and particles may clump; use 1.8 to 2.5");
    } else if (scene.smoothingRatio > 3.0) {
        report.warnings.push_back(
            "smoothingRatio " + fmt(scene.smoothingRatio) + " gives about " +
            fmt(4.0 / 3.0 * kPi * std::pow(scene.smoothingRatio, 3)) +
            " neighbours: stable but slow and smeared (poly6 and spiky over-smooth); 2 is the "
            "usual choice");
    }

    SphParams& p = setup.params;
    p.kernel = KernelCoefficients::forRadius(h);
    p.mass = Real(mass);
    p.restDensity = Real(scene.restDensity);
    p.invRestDensity = Real(1.0 / scene.restDensity);
    p.eos = scene.eos == EquationOfState::Tait ? EosKind::Tait : EosKind::Linear;
    p.pressureForce = scene.paperPressureForce ? PressureForm::Paper : PressureForm::Symmetric;
    p.stiffness = Real(stiffness);
    p.taitB = Real(taitB);
    p.negativePressureScale = Real(scene.negativePressureScale);
    p.viscosity = Real(viscosity);
    p.gravity = Vec3(scene.gravity);
    p.timeStep = Real(dt);
    p.adaptiveTimeStep = adaptive;
    p.speedOfSound = Real(c);
    p.viscousLimit = Real(std::min(dtViscous, 1e30));
    p.maxTimeStep = Real(report.frameInterval);
    p.integrator = scene.integrator == Integrator::ExplicitEuler
                       ? IntegratorKind::ExplicitEuler
                       : IntegratorKind::SemiImplicitEuler;
    p.boxMin = Vec3(scene.container.min);
    p.boxMax = Vec3(scene.container.max);
    for (int a = 0; a < 3; ++a) {
        p.periodicAxes |= scene.periodic[std::size_t(a)] ? 1 << a : 0;  // solver/periodic_ghosts.h
    }
    p.restitution = Real(scene.wallRestitution);
    p.friction = Real(scene.wallFriction);
    // Ten times the free-fall speed: splashes reach two or three times it, a blow-up far more.
    p.maxSpeed = Real(scene.maxSpeed.value_or(10.0 * report.expectedSpeed));
    if (scene.maxSpeed && *scene.maxSpeed < 2.0 * report.expectedSpeed) {
        report.warnings.push_back(
            "limits.maxSpeed " + fmt(*scene.maxSpeed) + " m/s is under twice the expected " +
            fmt(report.expectedSpeed) +
            " m/s: splashes reach that, so the run will likely stop as a false blow-up; leave it "
            "unset (10x) or use >= " +
            fmt(3.0 * report.expectedSpeed));
    }
    p.maxDensityRatio = Real(1 + scene.maxCompression);
    say("blow-up bound: speed > " + fmt(p.maxSpeed) + " m/s, density > " +
        fmt(1 + scene.maxCompression) +
        " rho0 (limits.maxCompression), two particles on one point, NaN, or a particle outside "
        "the box");
    p.model = deltaModel ? FluidModel::DeltaSph : FluidModel::Paper;
    if (deltaModel) {
        p.wendland = WendlandKernel::forRadius(h, report.gradientMoment);
        p.dynamicViscosity = Real(viscosity);
        p.viscosity = 0;  // eq. 5 is the paper model's
        p.viscositySoftening = Real(0.01 * halfH * halfH);
        p.artificialViscosity = Real(alpha * c * halfH);
        p.densityDiffusion = Real(delta * c * halfH);
        p.hydrostaticGradient = Vec3(weight * (scene.restDensity / (c * c)));
        p.noSlip = scene.noSlip;
        p.cflNumber = Real(cfl);
        if (dfsph) {
            p.speedOfSound = 0;  // dt <= cflNumber h / max |v| (physics/time_step.h)
            p.cflNumber = Real(scene.dfsph.cfl * d / h);
            p.densityTolerance = Real(scene.dfsph.densityErrorPercent / 100);
            p.divergenceTolerance = Real(scene.dfsph.divergenceErrorPercent / 100);
            p.worstDensityTolerance = Real(scene.dfsph.worstDensityErrorPercent / 100);
            // Experimental (solver/dfsph/dfsph_stages.h, dfsphDensityRate): off by default.
            if (const char* order = std::getenv("WEIR_DFSPH_SECOND_ORDER")) {
                p.dfsphSecondOrder = std::string(order) == "1";
            }
            p.maxSolverIterations = scene.dfsph.maxSweeps;
            // The solves predict the summed density's change by its rate: the rate takes the
            // gradient of the very kernel the density sums (no lattice-moment correction), so
            // that the prediction is that of the sum.
            // The viscous forces keep the corrected gradient (Morris's Laplacian of a quadratic
            // flow exact on the lattice: with the raw one the fluid's viscosity read 5% low, and
            // a Poiseuille channel ran 6% fast), and so does the pressure the frames report (the
            // solves' pressure, pushing through the raw gradient, is 1 / moment of the pressure
            // that pushes as hard through the corrected one): rawGradientMoment.
            p.wendland = WendlandKernel::forRadius(h);
            p.rawGradientMoment = Real(report.gradientMoment);
            // (Starting the density solve warm from the seeded hydrostatic pressure was
            // measured and dropped: a dam break's column face, hydrostatic in the seeding, was
            // kicked out at 1 m/s in the first step, and a tank at rest settled no better.)
            p.forceNumber = Real(kDfsphForceNumber);
            // The CFL condition never takes the flow to be slower than the speed it is expected
            // to reach, sqrt(2 g H) + its initial speed: from rest the force condition alone
            // allowed steps (3.3 ms for a 1M dam break, 115 particles deep) whose compression
            // the sweeps could not remove within their limit, and it blew up in its seventh
            // step on the H200, where it ran at a fixed 0.5 or 1 ms.
            p.minCflSpeed = Real(report.expectedSpeed);
            // Half the sum of |m grad W|^2 over a full lattice neighbourhood: the factor's
            // floor (solver/dfsph/dfsph_stages.h).
            double squares = 0;
            const int reach = int(std::ceil(scene.smoothingRatio));
            for (int i = -reach; i <= reach; ++i) {
                for (int j = -reach; j <= reach; ++j) {
                    for (int k = -reach; k <= reach; ++k) {
                        const double r = d * std::sqrt(double(i * i + j * j + k * k));
                        if (r > 0 && r < h) {
                            const double grad =
                                mass * double(p.wendland.gradientFactor(Real(r))) * r;
                            squares += grad * grad;
                        }
                    }
                }
            }
            p.minFactorDenominator = Real(0.5 * squares);
            p.integrator = IntegratorKind::SemiImplicitEuler;  // the solves assume it
            p.densityDiffusion = 0;  // the density is summed, not integrated
        }
        if (!dfsph) {
            p.tensileCorrection = Real(tensileCorrectionOf(scene));
            // Monaghan's f = W(r) / W(dp), dp his initial spacing, about his support / 2.6: here
            // h / 3, which is d at delta-SPH's default h = 3 d. At h = 2 d, W(d) would make
            // (W(0) / W(dp))^4 = 808 (22 at 3 d), and a pair in slight tension at a free surface
            // shot apart (a floating box's tank blew up at 0.33 s, CPU 2026-12-04).
            p.invKernelAtReference = Real(1.0 / double(p.wendland.value(Real(h / 3))));
        }
        const double shifting = scene.shifting.value_or(0.0);
        if (shifting > 0) {
            p.shifting = Real(shifting * 2 * h * c / 10);
            p.shiftingInvW = Real(1.0 / double(p.wendland.value(Real(d))));
            p.shiftingLimit = Real(kShiftingLimit * d);
            p.shiftingGateSpeed = Real(kShiftingGate * c / 10);
            p.surfaceKernelSum = Real(kSurfaceKernelSum);  // the lattice reads 1 (mass calibration)
            p.surfaceNeighbourKernelSum = Real(kSurfaceNeighbourKernelSum);
            p.splashKernelSum = Real(kSplashKernelSum);
        }
    }

    for (const auto& [what, value] : std::initializer_list<std::pair<const char*, double>>{
             {"particle mass", mass},
             {"inverse rest density", 1.0 / scene.restDensity},
             {"kernel coefficient 315 / (64 pi h^9)", double(p.kernel.poly6)},
             {"kernel gradient coefficient 45 / (pi h^6)", double(p.kernel.spikyGrad)},
             {"kernel laplacian coefficient 45 / (pi h^6)", double(p.kernel.viscLaplace)},
             {"stiffness", stiffness},
             {"Tait coefficient B", taitB},
             {"viscosity", viscosity},
             {"time step", dt},
             {"speed bound", double(p.maxSpeed)},
             {"weight of gravity", length(scene.gravity) * mass}}) {
        requireReal(where, what, value);
    }

    // The particles, on the host or left to the simulation's backend, starting at the density
    // of a fluid at rest: hydrostatic down each block from its top (the continuity equation
    // keeps it; the paper's model recomputes density from positions anyway).
    for (SeedLattice& lattice : seeds.lattices) {
        lattice.up = up;
        lattice.densityAtTop = scene.restDensity;
        lattice.top = -1e300;
        if (lattice.shape < int(seeds.fluidBoxes.size())) {
            const Box& b = seeds.fluidBoxes[std::size_t(lattice.shape)];
            for (int k = 0; k < 8; ++k) {
                const Vec3d corner((k & 1) ? b.max.x : b.min.x, (k & 2) ? b.max.y : b.min.y,
                                   (k & 4) ? b.max.z : b.min.z);
                lattice.top = std::max(lattice.top, dot(corner, up));
            }
            lattice.densityPerDepth = scene.restDensity * g / (c * c);
        }
    }
    if (options.seedOnDevice && seeds.seedableOnDevice()) {
        setup.seeder = std::make_shared<LatticeSeeder>(std::move(seeds));
    } else {
        forEachSeed(seeds, [&](const Vec3d& x, const Vec3d& v, double rho) {
            setup.particles.push(x, v);
            setup.particles.rho.back() = Real(rho);
        });
    }

    try {
        // Past the paper's 1024 cells per axis the dense table, or the sparse grid with 64-bit
        // cell ids, takes over.
        setup.grid = makeGridSpec(scene.container.min, scene.container.max, h, 1 << 20);
    } catch (const std::exception& e) {
        throw SceneError(where + ": " + e.what());
    }
    for (const Box& b : scene.obstacleBoxes) {
        setup.obstacleBoxes.push_back({Vec3(b.min), Vec3(b.max)});
    }
    for (const SphereShape& s : scene.obstacleSpheres) {
        setup.obstacleSpheres.push_back({Vec3(s.center), Real(s.radius)});
    }
    if (scene.walls == WallModel::Particles) {
        // Boundary particles, bounded before they are sampled: their samples, sort and grid.
        double boundaryPoints = 0;
        try {
            boundaryPoints = boundarySampleBound(scene, d, h, boundaryLayers(h, d, deltaModel));
        } catch (const SceneError& e) {
            throw SceneError(where + ": " + e.what());
        }
        const double boundaryBytes = boundaryPoints * 200.0 + 8.0 * double(setup.grid.dims[0] + 2) *
                                                                  double(setup.grid.dims[1] + 2) *
                                                                  double(setup.grid.dims[2] + 2);
        const double spare =
            double(budget.usable) - double(setup.particleCount()) * double(budget.perParticle);
        if (boundaryPoints > double(kMaxParticles) || boundaryBytes > spare) {
            throw SceneError(
                where + ": the walls and obstacles take up to " + fmt(boundaryPoints) +
                " boundary particles at spacing " + fmt(d) + " m, about " +
                fmt(boundaryBytes / double(1 << 20)) +
                " MiB with their grid, but host memory has " +
                fmt(std::max(0.0, spare) / double(1 << 20)) +
                " MiB to spare; use a larger particles.spacing, a smaller container or "
                "obstacles, or walls.model \"simple\"");
        }
        const BoundaryKernel kernel = deltaModel ? BoundaryKernel::Wendland : BoundaryKernel::Poly6;
        std::array<Vec3d, 6> faceVelocity{};
        for (const MovingWall& moving : scene.movingWalls) {
            faceVelocity[std::size_t(2 * moving.axis + moving.side)] = moving.velocity;
        }
        setup.boundary =
            buildBoundary(samplePeriodicBoundary(scene, d, h, boundaryLayers(h, d, deltaModel)),
                          scene.container, h, scene.restDensity, mass / scene.restDensity, kernel,
                          scene.movingWalls.empty() ? nullptr : &faceVelocity);
        p.walls = WallKind::Particles;
        p.wallViscosity = Real(scene.wallFriction * viscosity);
        double psiMin = 1e300, psiMax = 0;
        for (const Real4& b : setup.boundary.pos) {
            psiMin = std::min(psiMin, double(b.w));
            psiMax = std::max(psiMax, double(b.w));
        }
        say("walls: " + std::to_string(setup.boundary.size()) +
            " boundary particles (Akinci et al. 2012) at spacing d in " +
            std::to_string(boundaryLayers(h, d, deltaModel)) +
            " layer(s) from d/2 behind each wall and obstacle surface; volume psi = rho0 / sum W "
            "over boundary neighbours, capped at a full neighbourhood's, " +
            fmt(psiMin / (scene.restDensity * d * d * d)) + " to " +
            fmt(psiMax / (scene.restDensity * d * d * d)) + " x rho0 d^3; " +
            (deltaModel
                 ? std::string("their pressure is the fluid particle's extrapolated "
                               "hydrostatically, ") +
                       (scene.noSlip ? "no-slip: the fluid's viscosity sees the wall velocity "
                                       "mirrored through the wall (Morris et al. 1997)"
                                     : "free slip (walls.slip)") +
                       (scene.movingWalls.empty()
                            ? ""
                            : "; " + std::to_string(scene.movingWalls.size()) + " moving face(s)")
                 : std::string("they add to density and push by the fluid's own pressure") +
                       (scene.wallFriction > 0
                            ? "; friction mu = " + fmt(scene.wallFriction * viscosity)
                            : "; free slip (walls.friction 0)")));
    } else {
        p.wallWeight =
            wallWeightTable(h, d, mass, scene.restDensity, c, deltaModel ? &p.wendland : nullptr);
        say("walls: the paper's simple collision response (restitution " +
            fmt(scene.wallRestitution) + ", friction " + fmt(scene.wallFriction) +
            "), and wall weight (Harada et al. 2007): each container plane stands for the fluid "
            "lattice beyond it, adds its density (" +
            fmt(double(p.wallWeight.share[0])) +
            " rho0 at the plane) and pushes by the particle's own pressure times that density's "
            "gradient, with a barrier of c^2 / d within d/2 of the plane; obstacles get the "
            "collision response only");
    }
    if (!scene.bodies.empty()) {
        setup.bodies = rigidBodySetup(scene, d, h, mass);
        std::size_t floating = 0;
        for (const BodySpec& body : scene.bodies) {
            floating += body.drive == BodyDrive::Floating ? 1 : 0;
        }
        say("bodies: " + std::to_string(scene.bodies.size()) + " (" + std::to_string(floating) +
            " floating, " + std::to_string(scene.bodies.size() - floating) + " driven), " +
            std::to_string(setup.bodies.particles.size()) +
            " boundary particles on their surfaces, moved with them each step; the fluid's force "
            "and torque on each are summed from its particles (Akinci et al. 2012)");
    }
    if (!scene.emitters.empty() || !scene.sinks.empty()) {
        FlowSetup& flow = setup.flow;
        std::int64_t capacity = setup.particleCount();
        for (std::size_t k = 0; k < scene.emitters.size(); ++k) {
            const EmitterSpec& spec = scene.emitters[k];
            Emitter e;
            e.centre = Vec3(spec.center);
            e.normal = Vec3(spec.direction);
            e.speed = Real(spec.speed);
            e.spacing = Real(d);
            e.start = Real(spec.start);
            e.stop = Real(std::min(spec.stop, 1e30));
            e.density = Real(scene.restDensity);
            e.firstSite = Index(flow.sites.size());
            for (const Vec3d& site : emitterSites(spec, d)) {
                flow.sites.push_back(Real4::from(Vec3(site)));
            }
            e.siteCount = Index(flow.sites.size()) - e.firstSite;
            const std::int64_t layers = emitterLayers(spec, d, scene.duration);
            capacity += std::int64_t(e.siteCount) * (layers + 1);
            flow.emitters.push_back(e);
            say("emitters[" + std::to_string(k) + "]: " + std::to_string(e.siteCount) +
                " sites d apart, a layer every " + fmt(d / spec.speed) + " s at " +
                fmt(spec.speed) + " m/s: " + fmt(double(e.siteCount) * spec.speed / d) +
                " particles/s, " + fmt(double(e.siteCount) * d * d * spec.speed * 1000.0) +
                " L/s, from " + fmt(spec.start) + " s" +
                (spec.stop < 1e29 ? " to " + fmt(spec.stop) + " s" : std::string()));
        }
        for (const Box& b : scene.sinks) {
            flow.sinks.push_back(Sink{Vec3(b.min), Vec3(b.max)});
        }
        if (capacity > budget.limit() || capacity >= std::int64_t(kMaxParticles)) {
            throw budget.tooMany(where +
                                     " (the initial fluid and what the emitters let in over "
                                     "the scene's duration of " +
                                     fmt(scene.duration) + " s)",
                                 double(capacity), d, false);
        }
        flow.capacity = Index(capacity);
        say("inflow and outflow: " + std::to_string(scene.emitters.size()) + " emitter(s), " +
            std::to_string(scene.sinks.size()) + " sink(s); room for " + std::to_string(capacity) +
            " particles at once (the initial ones and all that the emitters let in over " +
            fmt(scene.duration) + " s), the count kept on the backend");
    }
    say(std::to_string(setup.particleCount()) + " particles, grid " +
        std::to_string(setup.grid.dims[0]) + " x " + std::to_string(setup.grid.dims[1]) + " x " +
        std::to_string(setup.grid.dims[2]) + " cells of " + fmt(h) + " m; sparse grid cell ids " +
        cellIdDescription(setup.grid));
    if (out != nullptr) {
        *out = std::move(report);
    }
    return setup;
}

}  // namespace weir
