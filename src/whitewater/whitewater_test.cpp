// Whitewater (Ihmsen et al. 2012) on fluids built on a lattice: no whitewater from water at rest,
// spray and foam where a jet hits a pool and its splash breaks, the classification by the fluid
// around, spray's parabola, a bubble's rise at the speed its drag allows, foam's lifetime, the
// cap, and the same bytes from the same input on any thread count.
#include "whitewater/whitewater.h"

#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "whitewater/whitewater_files.h"

namespace weir {
namespace {

namespace fs = std::filesystem;

constexpr double kSpacing = 0.02;
constexpr double kFrame = 1.0 / 30.0;
const Vec3d kGravity{0, -9.81, 0};

// Particles on the lattice of kSpacing filling [lo, hi), all with velocity v.
void addBlock(HostParticles& p, const Vec3d& lo, const Vec3d& hi, const Vec3d& v) {
    for (double x = lo.x + kSpacing / 2; x < hi.x; x += kSpacing) {
        for (double y = lo.y + kSpacing / 2; y < hi.y; y += kSpacing) {
            for (double z = lo.z + kSpacing / 2; z < hi.z; z += kSpacing) {
                p.push({x, y, z}, v);
            }
        }
    }
}

WhitewaterScale scaleFor(const HostParticles& first, const Box& container) {
    WhitewaterScale s;
    s.spacing = kSpacing;
    s.smoothingRatio = 2;
    s.gravity = kGravity;
    s.container = container;
    s.flowSpeed = flowSpeedOf(first, kGravity, kSpacing);
    return s;
}

// The fluid moved on by its velocity for dt (the frame after it, to first order).
HostParticles movedOn(HostParticles p, double dt) {
    for (std::size_t i = 0; i < p.size(); ++i) {
        p.x[i] += Real(p.vx[i] * dt);
        p.y[i] += Real(p.vy[i] * dt);
        p.z[i] += Real(p.vz[i] * dt);
    }
    return p;
}

// A pool 40 x 10 x 40 cm at rest; a thin jet falling into its middle at 4 m/s; and the splash
// around the impact, a crown sheet thrown up and outwards at 3 and 1.5 m/s.
constexpr double kPoolTop = 0.1;
const Vec3d kImpact{0.21, kPoolTop, 0.21};
constexpr double kCrownRadius = 0.08;
const Box kSplashBox{{0, 0, 0}, {0.42, 0.6, 0.42}};

HostParticles jetAndSplash() {
    HostParticles p;
    addBlock(p, {0, 0, 0}, {0.42, kPoolTop, 0.42}, {0, 0, 0});
    for (int k = 0; k < 10; ++k) {
        p.push({kImpact.x, kPoolTop + kSpacing * (0.5 + k), kImpact.z}, {0, -4, 0});
    }
    for (int layer = 0; layer < 2; ++layer) {
        const double radius = kCrownRadius + layer * kSpacing;
        const int around = int(std::round(2 * 3.14159265358979 * radius / kSpacing));
        for (int a = 0; a < around; ++a) {
            const double angle = 2 * 3.14159265358979 * a / around;
            const Vec3d out(std::cos(angle), 0, std::sin(angle));
            for (int k = 0; k < 4; ++k) {
                const Vec3d at = kImpact + out * radius + Vec3d(0, kSpacing * (0.5 + k), 0);
                p.push(at, out * 1.5 + Vec3d(0, 3, 0));
            }
        }
    }
    return p;
}

TEST(Whitewater, TankAtRestMakesNoWhitewater) {
    HostParticles tank;
    addBlock(tank, {0, 0, 0}, {0.4, 0.2, 0.2}, {0, 0, 0});
    // The jitter of a settled SPH tank: a few mm/s.
    for (std::size_t i = 0; i < tank.size(); ++i) {
        tank.vx[i] = Real(0.003 * std::sin(double(i)));
        tank.vy[i] = Real(0.003 * std::cos(1.7 * double(i)));
    }
    const WhitewaterScale scale = scaleFor(tank, {{0, 0, 0}, {0.4, 0.4, 0.2}});
    Whitewater whitewater(scale, {});
    std::size_t born = 0;
    for (int frame = 0; frame < 10; ++frame) {
        born += whitewater.advance(tank, frame, tank, kFrame).born;
    }
    EXPECT_EQ(born, 0u);
    EXPECT_EQ(whitewater.particles().size(), 0u);
    const WhitewaterPotentials potentials = computePotentials(tank, scale, {});
    for (std::size_t i = 0; i < tank.size(); ++i) {
        ASSERT_EQ(potentials.kinetic[i], 0.0f) << i;
        ASSERT_EQ(potentials.trappedAir[i], 0.0f) << i;
    }
}

TEST(Whitewater, JetAndSplashMakeSprayAndFoamWhereTheyHit) {
    const HostParticles fluid = jetAndSplash();
    const WhitewaterScale scale = scaleFor(fluid, kSplashBox);
    const WhitewaterSettings settings;
    // The potentials: air is trapped where the jet meets the pool, the crown's rim is a crest;
    // the pool away from the impact has neither.
    const WhitewaterPotentials potentials = computePotentials(fluid, scale, settings);
    bool airAtImpact = false, crestAtRim = false;
    for (std::size_t i = 0; i < fluid.size(); ++i) {
        const Vec3d x(fluid.x[i], fluid.y[i], fluid.z[i]);
        const double fromAxis = std::hypot(x.x - kImpact.x, x.z - kImpact.z);
        const double fromImpact = length(x - kImpact);
        if (potentials.trappedAir[i] > 0) {
            EXPECT_LT(fromImpact, 3 * scale.neighbourRadius()) << "trapped air far from the jet";
            airAtImpact = airAtImpact || fromImpact < scale.neighbourRadius();
        }
        if (potentials.waveCrest[i] > 0) {
            EXPECT_GT(fromAxis, kCrownRadius - kSpacing) << "a crest inside the crown";
            crestAtRim = crestAtRim || x.y > kPoolTop + 3 * kSpacing;
        }
        if (fromAxis > kCrownRadius + 3 * scale.neighbourRadius()) {
            EXPECT_EQ(potentials.trappedAir[i] + potentials.waveCrest[i] + potentials.kinetic[i],
                      0.0f);
        }
    }
    EXPECT_TRUE(airAtImpact);
    EXPECT_TRUE(crestAtRim);

    Whitewater whitewater(scale, settings);
    const WhitewaterStep step = whitewater.advance(fluid, 0, movedOn(fluid, kFrame), kFrame);
    const DiffuseParticles& d = whitewater.particles();
    EXPECT_GT(step.born, 0u);
    EXPECT_GT(d.count(DiffuseKind::Spray), 0u);
    EXPECT_GT(d.count(DiffuseKind::Foam) + d.count(DiffuseKind::Bubble), 0u);
    for (std::size_t k = 0; k < d.size(); ++k) {
        const double fromAxis = std::hypot(d.x[k] - kImpact.x, d.z[k] - kImpact.z);
        EXPECT_LT(fromAxis, kCrownRadius + 0.15)
            << "diffuse particle " << k << " far from the splash";
        if (d.kindOf(k) == DiffuseKind::Spray) {
            EXPECT_GT(d.y[k], kPoolTop) << "spray inside the pool";
        }
        if (d.kindOf(k) == DiffuseKind::Bubble) {
            EXPECT_LT(d.y[k], kPoolTop) << "a bubble above the pool";
        }
    }
}

// Brute force: the fluid particles within h of p.
int neighboursWithin(const HostParticles& fluid, const Vec3d& p, double h) {
    int count = 0;
    for (std::size_t j = 0; j < fluid.size(); ++j) {
        const Vec3d d = Vec3d(fluid.x[j], fluid.y[j], fluid.z[j]) - p;
        count += dot(d, d) < h * h ? 1 : 0;
    }
    return count;
}

TEST(Whitewater, ClassificationFollowsTheFluidNeighbourCount) {
    HostParticles pool;
    addBlock(pool, {0, 0, 0}, {0.3, 0.2, 0.3}, {0, 0, 0});
    const WhitewaterScale scale = scaleFor(pool, {{0, 0, 0}, {0.3, 0.5, 0.3}});
    const WhitewaterSettings settings;
    Whitewater whitewater(scale, settings);
    // Points on a slanted line from the pool's depths out into the air, through its surface.
    for (int k = 0; k < 300; ++k) {
        const double s = k / 299.0;
        whitewater.particles().push(float(0.05 + 0.2 * s), float(0.05 + 0.25 * s),
                                    float(0.15 + 0.03 * std::sin(9 * s)), 0, 0, 0,
                                    DiffuseKind::Spray, 1);
    }
    whitewater.classify(pool);
    const double full = 4.0 / 3.0 * 3.14159265358979 * 8;  // (h / d)^3 = 8
    std::size_t kinds[kDiffuseKinds] = {};
    const DiffuseParticles& d = whitewater.particles();
    for (std::size_t k = 0; k < d.size(); ++k) {
        const int n = neighboursWithin(pool, {d.x[k], d.y[k], d.z[k]}, scale.neighbourRadius());
        const DiffuseKind expected = n < settings.sprayBelow * full    ? DiffuseKind::Spray
                                     : n > settings.bubbleAbove * full ? DiffuseKind::Bubble
                                                                       : DiffuseKind::Foam;
        EXPECT_EQ(d.kindOf(k), expected) << "point " << k << " has " << n << " neighbours";
        ++kinds[d.kind[k]];
    }
    for (int kind = 0; kind < kDiffuseKinds; ++kind) {
        EXPECT_GT(kinds[kind], 10u) << diffuseKindName(DiffuseKind(kind));
    }
}

TEST(Whitewater, SprayAloneFollowsTheBallisticParabola) {
    const HostParticles air;  // no fluid: everything is spray
    WhitewaterScale scale;
    scale.spacing = kSpacing;
    scale.gravity = kGravity;
    scale.container = {{-5, -5, -5}, {5, 5, 5}};
    scale.flowSpeed = 3;
    Whitewater whitewater(scale, {});
    const Vec3d x0(0.5, 0.5, 0.5), v0(1.0, 2.0, -0.5);
    whitewater.particles().push(float(x0.x), float(x0.y), float(x0.z), float(v0.x), float(v0.y),
                                float(v0.z), DiffuseKind::Spray, 1);
    // And one thrown out of the container, which leaves it.
    whitewater.particles().push(4.99f, 0, 0, 10, 0, 0, DiffuseKind::Spray, 1);
    std::size_t left = 0;
    for (int frame = 1; frame <= 12; ++frame) {
        left += whitewater.advance(air, frame - 1, air, kFrame).left;
        ASSERT_EQ(whitewater.particles().size(), 1u);
        const double t = frame * kFrame;
        const Vec3d expected = x0 + v0 * t + kGravity * (0.5 * t * t);
        const DiffuseParticles& d = whitewater.particles();
        EXPECT_NEAR(d.x[0], expected.x, 1e-5);
        EXPECT_NEAR(d.y[0], expected.y, 1e-5);
        EXPECT_NEAR(d.z[0], expected.z, 1e-5);
        EXPECT_NEAR(d.vy[0], v0.y + kGravity.y * t, 1e-5);
        EXPECT_EQ(d.kindOf(0), DiffuseKind::Spray);
    }
    EXPECT_EQ(left, 1u);
}

TEST(Whitewater, BubbleUnderWaterRisesAtItsTerminalSpeed) {
    HostParticles pool;
    addBlock(pool, {0, 0, 0}, {0.4, 0.4, 0.4}, {0, 0, 0});
    const WhitewaterScale scale = scaleFor(pool, {{0, 0, 0}, {0.4, 0.6, 0.4}});
    const WhitewaterSettings settings;
    Whitewater whitewater(scale, settings);
    whitewater.particles().push(0.2f, 0.1f, 0.2f, 0, 0, 0, DiffuseKind::Bubble, 1);
    // Buoyancy balances the drag towards the (resting) fluid at k_b |g| tau.
    const double tau = settings.dragTime * std::sqrt(scale.neighbourRadius() / 9.81);
    const double terminal = settings.buoyancy * 9.81 * tau;
    double y = 0.1;
    for (int frame = 0; frame < 6; ++frame) {
        whitewater.advance(pool, frame, pool, kFrame);
        const DiffuseParticles& d = whitewater.particles();
        ASSERT_EQ(d.size(), 1u);
        EXPECT_EQ(d.kindOf(0), DiffuseKind::Bubble);
        EXPECT_GT(d.y[0], y) << "frame " << frame;
        y = d.y[0];
        EXPECT_NEAR(d.x[0], 0.2, 1e-6);
        EXPECT_NEAR(d.z[0], 0.2, 1e-6);
    }
    // tau is a few ms: after 0.2 s the bubble rises at its terminal speed, and has risen about
    // that speed times the time.
    EXPECT_NEAR(whitewater.particles().vy[0], terminal, 1e-3 * terminal);
    EXPECT_NEAR(y - 0.1, terminal * (6 * kFrame - tau), 0.02 * terminal * 6 * kFrame);
}

TEST(Whitewater, FoamDissolvesAfterItsLifetime) {
    HostParticles pool;
    addBlock(pool, {0, 0, 0}, {0.4, 0.2, 0.4}, {0, 0, 0});
    const WhitewaterScale scale = scaleFor(pool, {{0, 0, 0}, {0.4, 0.5, 0.4}});
    Whitewater whitewater(scale, {});
    const double lifetime = 0.19;
    whitewater.particles().push(0.21f, 0.2f, 0.21f, 0, 0, 0, DiffuseKind::Foam, float(lifetime));
    std::size_t dissolved = 0;
    for (int frame = 1; frame <= 8; ++frame) {
        dissolved += whitewater.advance(pool, frame - 1, pool, kFrame).dissolved;
        const bool alive = frame * kFrame < lifetime - 1e-6;
        ASSERT_EQ(whitewater.particles().size(), alive ? 1u : 0u) << "at " << frame * kFrame;
        if (alive) {
            EXPECT_EQ(whitewater.particles().kindOf(0), DiffuseKind::Foam);
            EXPECT_NEAR(whitewater.particles().lifetime[0], lifetime - frame * kFrame, 1e-5);
        }
    }
    EXPECT_EQ(dissolved, 1u);
}

TEST(Whitewater, TheCapHolds) {
    const HostParticles fluid = jetAndSplash();
    WhitewaterSettings settings;
    settings.maxParticles = 25;
    Whitewater whitewater(scaleFor(fluid, kSplashBox), settings);
    HostParticles from = fluid;
    std::size_t capped = 0;
    for (int frame = 0; frame < 4; ++frame) {
        const HostParticles to = movedOn(from, kFrame);
        capped += whitewater.advance(from, frame, to, kFrame).capped;
        EXPECT_LE(whitewater.particles().size(), settings.maxParticles);
        from = to;
    }
    EXPECT_GT(capped, 0u);
}

std::string bytesOf(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(Whitewater, SameInputGivesTheSameBytesOnAnyThreadCount) {
    const fs::path dir = fs::temp_directory_path() / "weir_whitewater_same_bytes";
    fs::remove_all(dir);
    const HostParticles fluid = jetAndSplash();
    const int threads = omp_get_max_threads();
    for (int run = 0; run < 2; ++run) {
        omp_set_num_threads(run == 0 ? 1 : std::max(2, threads));
        // Four times the default rate: many particles, each from its own stream of numbers.
        WhitewaterSettings settings;
        settings.trappedAirRate = settings.waveCrestRate = 400;
        WhitewaterSequence sequence((dir / std::to_string(run)).string(),
                                    scaleFor(fluid, kSplashBox), settings);
        HostParticles frame = fluid;
        for (int index = 0; index < 4; ++index) {
            sequence.add(index, index * kFrame, frame);
            frame = movedOn(frame, kFrame);
        }
    }
    omp_set_num_threads(threads);
    for (int index = 0; index < 4; ++index) {
        const std::string name = whitewaterFileName(index);
        const std::string a = bytesOf(dir / "0" / name), b = bytesOf(dir / "1" / name);
        EXPECT_FALSE(a.empty());
        EXPECT_EQ(a, b) << name;
    }
    EXPECT_GT(fs::file_size(dir / "0" / whitewaterFileName(3)), 500u);  // not all empty
    fs::remove_all(dir);
}

}  // namespace
}  // namespace weir
