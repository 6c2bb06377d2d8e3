// Whitewater: the potentials, the generation, the classification and the advection of diffuse
// particles (Ihmsen et al. 2012).
#include "whitewater/whitewater.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/counter_random.h"
#include "physics/kernels.h"
#include "whitewater/fluid_grid.h"

namespace weir {

namespace {

// The random numbers of a fluid particle's new diffuse particles in one frame interval: a stream
// keyed by (frame, fluid particle id) (core/counter_random.h), so the diffuse particles are the
// same whatever the thread count or the order the work runs in.
CounterStream drawStream(std::int64_t frame, std::int64_t particle) {
    return CounterStream(mixBits(
        std::uint32_t(particle) * 0x9e3779b9U ^ mixBits(std::uint32_t(frame) + 0x632be5abU) ^
        mixBits(std::uint32_t(std::uint64_t(particle) >> 32) + 0x1b873593U)));
}

// The paper's clamp of a potential to [0, 1].
double clampPotential(double value, double lo, double hi) {
    return (std::min(value, hi) - std::min(value, lo)) / (hi - lo);
}

Vec3d positionOf(const HostParticles& p, std::size_t i) {
    return {double(p.x[i]), double(p.y[i]), double(p.z[i])};
}
Vec3d velocityOf(const HostParticles& p, std::size_t i) {
    return {double(p.vx[i]), double(p.vy[i]), double(p.vz[i])};
}

// The count of fluid particles within h of a point and their velocity there (Shepard-normalised,
// weights (1 - r^2 / h^2)^3: smooth, so that foam does not jump as particles cross the edge).
struct FluidAround {
    int count = 0;
    Vec3d velocity;
};

FluidAround fluidAround(const FluidGrid& grid, const HostParticles& fluid, const Vec3d& p,
                        bool withVelocity) {
    FluidAround around;
    const double h2 = grid.radius() * grid.radius();
    double weights = 0;
    grid.forEachWithin(p, [&](std::size_t j, double r2) {
        ++around.count;
        if (withVelocity) {
            const double s = 1.0 - r2 / h2;
            const double w = s * s * s;
            around.velocity += velocityOf(fluid, j) * w;
            weights += w;
        }
    });
    if (weights > 0) {
        around.velocity = around.velocity / weights;
    }
    return around;
}

DiffuseKind kindFor(int neighbours, double fullNeighbourhood, const WhitewaterSettings& s) {
    if (neighbours < s.sprayBelow * fullNeighbourhood) {
        return DiffuseKind::Spray;
    }
    if (neighbours > s.bubbleAbove * fullNeighbourhood) {
        return DiffuseKind::Bubble;
    }
    return DiffuseKind::Foam;
}

// Two unit vectors perpendicular to a unit vector and to each other.
void perpendiculars(const Vec3d& axis, Vec3d& e1, Vec3d& e2) {
    const Vec3d other = std::abs(axis.x) < 0.9 ? Vec3d(1, 0, 0) : Vec3d(0, 1, 0);
    e1 = cross(axis, other);
    e1 = e1 / length(e1);
    e2 = cross(axis, e1);
}

bool inside(const Box& box, const Vec3d& p) {
    for (int a = 0; a < 3; ++a) {
        if (!(p[a] >= box.min[a] && p[a] <= box.max[a])) {
            return false;  // outside, or not finite
        }
    }
    return true;
}

}  // namespace

const char* diffuseKindName(DiffuseKind kind) {
    switch (kind) {
        case DiffuseKind::Spray:
            return "spray";
        case DiffuseKind::Foam:
            return "foam";
        case DiffuseKind::Bubble:
            return "bubbles";
    }
    return "?";
}

double flowSpeedOf(const HostParticles& first, const Vec3d& gravity, double spacing) {
    const double g = length(gravity);
    const Vec3d down = g > 0 ? gravity / g : Vec3d(0, -1, 0);
    double lo = INFINITY, hi = -INFINITY, fastest = 0;
    for (std::size_t i = 0; i < first.size(); ++i) {
        const double along = dot(positionOf(first, i), down);
        lo = std::min(lo, along);
        hi = std::max(hi, along);
        fastest = std::max(fastest, length(velocityOf(first, i)));
    }
    const double height = first.size() > 0 ? std::max(hi - lo, spacing) : spacing;
    return std::max(std::sqrt(2.0 * g * height) + fastest, 1e-3);
}

void WhitewaterSettings::check() const {
    auto range = [](double lo, double hi, const char* name) {
        if (!(lo >= 0) || !(hi > lo) || !std::isfinite(hi)) {
            throw std::invalid_argument(std::string("whitewater ") + name + " range [" +
                                        std::to_string(lo) + ", " + std::to_string(hi) +
                                        "] must have 0 <= min < max");
        }
    };
    range(trappedAirMin, trappedAirMax, "trapped-air");
    range(waveCrestMin, waveCrestMax, "wave-crest");
    range(kineticSpeedMin, kineticSpeedMax, "kinetic-speed");
    range(sprayBelow, bubbleAbove, "spray/bubble neighbour share");
    auto nonNegative = [](double value, const char* name) {
        if (!(value >= 0) || !std::isfinite(value)) {
            throw std::invalid_argument(std::string("whitewater ") + name + " " +
                                        std::to_string(value) + " must be >= 0 and finite");
        }
    };
    nonNegative(trappedAirRate, "trapped-air rate");
    nonNegative(waveCrestRate, "wave-crest rate");
    nonNegative(buoyancy, "buoyancy");
    nonNegative(spread, "spread");
    if (!(foamLifetime > 0) || !std::isfinite(foamLifetime)) {
        throw std::invalid_argument("--lifetime " + std::to_string(foamLifetime) +
                                    " must be a time in seconds > 0");
    }
    if (!(dragTime > 0) || !std::isfinite(dragTime)) {
        throw std::invalid_argument("whitewater drag time must be > 0");
    }
    if (substeps < 0 || substeps > 10000) {
        throw std::invalid_argument("--substeps " + std::to_string(substeps) +
                                    " must be within 0..10000 (0: automatic)");
    }
}

WhitewaterPotentials computePotentials(const HostParticles& fluid, const WhitewaterScale& scale,
                                       const WhitewaterSettings& s) {
    const std::size_t n = fluid.size();
    const double h = scale.neighbourRadius();
    const FluidGrid grid(fluid, h);
    // The surface normals: the weighted mean direction away from the neighbours (W = 1 - r / h,
    // the paper's weighting), and its length as the surface test.
    std::vector<Vec3d> normal(n);
    std::vector<char> atSurface(n);
#pragma omp parallel for schedule(static)
    for (std::int64_t ii = 0; ii < std::int64_t(n); ++ii) {
        const auto i = std::size_t(ii);
        const Vec3d xi = positionOf(fluid, i);
        Vec3d away;
        double weights = 0;
        grid.forEachWithin(xi, [&](std::size_t j, double r2) {
            if (j == i || r2 <= 0) {
                return;
            }
            const double r = std::sqrt(r2);
            const double w = 1.0 - r / h;
            away += (xi - positionOf(fluid, j)) * (w / r);
            weights += w;
        });
        const double asymmetry = weights > 0 ? length(away) / weights : 0;
        atSurface[i] = asymmetry >= s.surfaceAsymmetry;
        normal[i] = asymmetry > 0 ? away / length(away) : Vec3d();
    }

    WhitewaterPotentials out;
    for (auto* v : {&out.trappedAir, &out.waveCrest, &out.kinetic, &out.rawTrappedAir,
                    &out.rawWaveCrest, &out.rawKinetic}) {
        v->resize(n);
    }
    // The paper's sums grow with the neighbour count, (h / d)^3: divided by the sum of W over a
    // full lattice neighbourhood, (pi / 3) (h / d)^3, they are weighted means, the same for any
    // smoothing ratio, and trapped air is a relative speed in m/s.
    const double fullWeight = kPi / 3.0 * std::pow(scale.smoothingRatio, 3);
    const double u = scale.flowSpeed;
    const double kineticLo = 0.5 * std::pow(s.kineticSpeedMin * u, 2);
    const double kineticHi = 0.5 * std::pow(s.kineticSpeedMax * u, 2);
#pragma omp parallel for schedule(static)
    for (std::int64_t ii = 0; ii < std::int64_t(n); ++ii) {
        const auto i = std::size_t(ii);
        const Vec3d xi = positionOf(fluid, i), vi = velocityOf(fluid, i);
        double trappedAir = 0, curvature = 0;
        grid.forEachWithin(xi, [&](std::size_t j, double r2) {
            if (j == i || r2 <= 0) {
                return;
            }
            const double r = std::sqrt(r2);
            const double w = 1.0 - r / h;
            const Vec3d xij = (xi - positionOf(fluid, j)) / r;
            const Vec3d vij = vi - velocityOf(fluid, j);
            const double speed = length(vij);
            if (speed > 0) {
                // Particles that approach each other trap air (1 - cos > 1); parting ones less.
                trappedAir += speed * (1.0 - dot(vij / speed, xij)) * w;
            }
            // Convex crests: the neighbours behind i's surface whose normals turn away from its
            // own. Interior neighbours have no meaningful normal and are left out.
            if (atSurface[i] && atSurface[j] && dot(xij, normal[i]) > 0) {
                curvature += (1.0 - dot(normal[i], normal[j])) * w;
            }
        });
        trappedAir /= fullWeight;
        curvature /= fullWeight;
        const double speed = length(vi);
        const bool movesOutwards = speed > 0 && dot(vi / speed, normal[i]) >= s.waveCrestAlignment;
        const double waveCrest = atSurface[i] && movesOutwards ? curvature : 0;
        const double kinetic = 0.5 * speed * speed;
        out.rawTrappedAir[i] = float(trappedAir);
        out.rawWaveCrest[i] = float(waveCrest);
        out.rawKinetic[i] = float(kinetic);
        out.trappedAir[i] =
            float(clampPotential(trappedAir, s.trappedAirMin * u, s.trappedAirMax * u));
        out.waveCrest[i] = float(clampPotential(waveCrest, s.waveCrestMin, s.waveCrestMax));
        out.kinetic[i] = float(clampPotential(kinetic, kineticLo, kineticHi));
    }
    return out;
}

Whitewater::Whitewater(const WhitewaterScale& scale, const WhitewaterSettings& settings)
    : scale_(scale), settings_(settings) {
    settings_.check();
    if (!(scale.spacing > 0) || !(scale.smoothingRatio > 0) || !(scale.flowSpeed > 0) ||
        !std::isfinite(scale.spacing * scale.smoothingRatio * scale.flowSpeed)) {
        throw std::invalid_argument(
            "whitewater: the particle spacing, smoothing ratio and flow speed must be > 0");
    }
}

void Whitewater::classify(const HostParticles& fluid) {
    const double h = scale_.neighbourRadius();
    const double full = 4.0 / 3.0 * kPi * std::pow(scale_.smoothingRatio, 3);
    const FluidGrid grid(fluid, h);
    DiffuseParticles& d = particles_;
#pragma omp parallel for schedule(static)
    for (std::int64_t kk = 0; kk < std::int64_t(d.size()); ++kk) {
        const auto k = std::size_t(kk);
        const FluidAround around = fluidAround(grid, fluid, {d.x[k], d.y[k], d.z[k]}, false);
        d.kind[k] = std::uint8_t(kindFor(around.count, full, settings_));
    }
}

WhitewaterStep Whitewater::advance(const HostParticles& from, std::int64_t fromIndex,
                                   const HostParticles& to, double dt) {
    if (!(dt > 0) || !std::isfinite(dt)) {
        throw std::invalid_argument("whitewater: the frame interval must be > 0 s, not " +
                                    std::to_string(dt));
    }
    const WhitewaterSettings& s = settings_;
    const double h = scale_.neighbourRadius();
    const double full = 4.0 / 3.0 * kPi * std::pow(scale_.smoothingRatio, 3);
    const Vec3d g = scale_.gravity;
    WhitewaterStep step;
    DiffuseParticles& d = particles_;
    const std::size_t before = d.size();

    // Generation: the count per fluid particle, then the cap in fluid order, then the
    // new particles, each from its fluid particle's own random stream.
    const WhitewaterPotentials potentials = computePotentials(from, scale_, s);
    const std::size_t n = from.size();
    std::vector<std::uint32_t> count(n);
#pragma omp parallel for schedule(static)
    for (std::int64_t ii = 0; ii < std::int64_t(n); ++ii) {
        const auto i = std::size_t(ii);
        const double expected = double(potentials.kinetic[i]) *
                                (s.trappedAirRate * potentials.trappedAir[i] +
                                 s.waveCrestRate * potentials.waveCrest[i]) *
                                dt;
        if (expected > 0) {
            CounterStream random = drawStream(fromIndex, from.idOf(i));
            const double whole = std::floor(expected);
            count[i] = std::uint32_t(whole) + (random.next() < expected - whole ? 1 : 0);
        }
    }
    std::vector<std::size_t> first(n + 1, 0);
    for (std::size_t i = 0; i < n; ++i) {
        first[i + 1] = first[i] + count[i];
    }
    const std::size_t room = s.maxParticles > before ? s.maxParticles - before : 0;
    const std::size_t wanted = first[n];
    step.born = std::min(wanted, room);
    step.capped = wanted - step.born;
    d.resize(before + step.born);
    std::vector<float> birth(step.born);  // the time into the interval each is born at [s]
    const double tubeRadius = 0.5 * scale_.spacing;
#pragma omp parallel for schedule(static)
    for (std::int64_t ii = 0; ii < std::int64_t(n); ++ii) {
        const auto i = std::size_t(ii);
        if (count[i] == 0 || first[i] >= step.born) {
            continue;
        }
        CounterStream random = drawStream(fromIndex, from.idOf(i));
        random.next();  // the draw that rounded the count
        const Vec3d x = positionOf(from, i), v = velocityOf(from, i);
        const double speed = length(v);
        Vec3d axis = speed > 0 ? v / speed : Vec3d(0, 1, 0), e1, e2;
        perpendiculars(axis, e1, e2);
        for (std::size_t k = first[i]; k < std::min(first[i + 1], step.born); ++k) {
            // A point of the cylinder the fluid particle sweeps in the interval: born at time
            // tau along its path, up to a particle radius off it, moving with it and outwards.
            const double tau = random.next() * dt;
            const double r = tubeRadius * std::sqrt(random.next());
            const double angle = 2 * kPi * random.next();
            const Vec3d out = e1 * std::cos(angle) + e2 * std::sin(angle);
            const Vec3d p = x + v * tau + out * r;
            const Vec3d u = v + out * (s.spread * speed * r / tubeRadius);
            const std::size_t at = before + k;
            d.x[at] = float(p.x);
            d.y[at] = float(p.y);
            d.z[at] = float(p.z);
            d.vx[at] = float(u.x);
            d.vy[at] = float(u.y);
            d.vz[at] = float(u.z);
            d.kind[at] = std::uint8_t(DiffuseKind::Spray);  // classified at the first sub-step
            d.lifetime[at] = float(s.foamLifetime * (0.5 + random.next()));
            birth[k] = float(tau);
        }
    }

    // Advection in sub-steps through the fluid at the interval's start.
    step.substeps = s.substeps > 0
                        ? s.substeps
                        : std::max(1, int(std::ceil(2 * scale_.flowSpeed * dt / (h / 2))));
    const double sub = dt / step.substeps;
    const double tau = s.dragTime * std::sqrt(h / std::max(length(g), 1e-9));
    const FluidGrid grid(from, h);
#pragma omp parallel for schedule(dynamic, 256)
    for (std::int64_t kk = 0; kk < std::int64_t(d.size()); ++kk) {
        const auto k = std::size_t(kk);
        const double born = k >= before ? double(birth[k - before]) : 0.0;
        Vec3d x(d.x[k], d.y[k], d.z[k]), v(d.vx[k], d.vy[k], d.vz[k]);
        double life = d.lifetime[k];
        DiffuseKind kind = d.kindOf(k);
        for (int j = 0; j < step.substeps; ++j) {
            const double end = (j + 1) * sub;
            const double h0 = std::max(j * sub, born);
            if (h0 >= end) {
                continue;
            }
            const double t = end - h0;
            const FluidAround around = fluidAround(grid, from, x, true);
            kind = kindFor(around.count, full, s);
            if (kind == DiffuseKind::Spray) {
                x += v * t + g * (0.5 * t * t);  // exact under constant gravity
                v += g * t;
            } else if (kind == DiffuseKind::Foam) {
                v = around.velocity;
                x += v * t;
                life -= t;
            } else {
                // dv/dt = -k_b g + (v_f - v) / tau, exactly over the sub-step: v relaxes to the
                // fluid's velocity plus the rise speed.
                const Vec3d terminal = around.velocity - g * (s.buoyancy * tau);
                v = terminal + (v - terminal) * std::exp(-t / tau);
                x += v * t;
            }
        }
        d.x[k] = float(x.x);
        d.y[k] = float(x.y);
        d.z[k] = float(x.z);
        d.vx[k] = float(v.x);
        d.vy[k] = float(v.y);
        d.vz[k] = float(v.z);
        d.kind[k] = std::uint8_t(kind);
        d.lifetime[k] = float(life);
    }

    // Removal, keeping the survivors' order: foam past its lifetime, what left the container.
    std::size_t kept = 0;
    for (std::size_t k = 0; k < d.size(); ++k) {
        const Vec3d x(d.x[k], d.y[k], d.z[k]);
        if (!inside(scale_.container, x)) {
            ++step.left;
            continue;
        }
        if (d.kindOf(k) == DiffuseKind::Foam && !(d.lifetime[k] > 0)) {
            ++step.dissolved;
            continue;
        }
        if (kept != k) {
            d.x[kept] = d.x[k];
            d.y[kept] = d.y[k];
            d.z[kept] = d.z[k];
            d.vx[kept] = d.vx[k];
            d.vy[kept] = d.vy[k];
            d.vz[kept] = d.vz[k];
            d.kind[kept] = d.kind[k];
            d.lifetime[kept] = d.lifetime[k];
        }
        ++kept;
    }
    d.resize(kept);
    classify(to);
    return step;
}

}  // namespace weir
