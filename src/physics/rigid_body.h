// Rigid bodies in the fluid (issue 18), written once for CPU and CUDA: a body is a box, a sphere
// or a closed triangle mesh whose surface is sampled by boundary particles fixed in the body's
// frame (Akinci et al. 2012, "Versatile rigid-fluid coupling for incompressible SPH"). The fluid
// sees them as it sees the walls (delta-SPH's extrapolated wall pressure and no-slip velocity,
// physics/delta_sph.h); the body gets the opposite of every force its particles exert on the fluid,
// summed into a force and a torque about its centre, and moves as a rigid body under them and
// gravity (semi-implicit Euler, the fluid's own step). A driven body follows a prescribed motion
// instead and pushes the fluid without being pushed back.
//
// Contacts with the container's walls and between bodies are simple: the deepest point of a body
// past a wall (a box's corner, a sphere's lowest point, a corner of a mesh's bounding box) is
// moved back onto it and gets an inelastic impulse with Coulomb friction; two bodies whose
// bounding spheres overlap are pushed apart along the line between their centres.
#pragma once

#include <cmath>
#include <vector>

#include "core/config.h"
#include "core/vec3.h"

namespace weir {

enum class BodyShape : int { Box = 0, Sphere = 1, Mesh = 2 };
// Floating: moved by the fluid and gravity. Oscillating: centre = home + amplitude sin(2 pi t /
// period), its amplitude ramped up linearly over `ramp` seconds (a piston wave maker).
// Rotating: about its centre at a constant angular velocity (a paddle).
enum class BodyMotion : int { Floating = 0, Oscillating = 1, Rotating = 2 };

// A quaternion (x, y, z, w) rotating the body's frame into the world's.
WEIR_HD inline Vec3 rotate(const Real4& q, const Vec3& v) {
    const Vec3 u(q.x, q.y, q.z);
    const Vec3 t = cross(u, v) * Real(2);
    return v + t * q.w + cross(u, t);
}
WEIR_HD inline Vec3 rotateBack(const Real4& q, const Vec3& v) {
    return rotate(Real4{-q.x, -q.y, -q.z, q.w}, v);
}
// q advanced by the angular velocity w (world frame) over dt: q + dt/2 (w, 0) q, normalised.
WEIR_HD inline Real4 turned(const Real4& q, const Vec3& w, Real dt) {
    const Real hx = Real(0.5) * dt * w.x, hy = Real(0.5) * dt * w.y, hz = Real(0.5) * dt * w.z;
    Real4 r{q.x + hx * q.w + hy * q.z - hz * q.y, q.y + hy * q.w + hz * q.x - hx * q.z,
            q.z + hz * q.w + hx * q.y - hy * q.x, q.w - hx * q.x - hy * q.y - hz * q.z};
    const Real norm = std::sqrt(r.x * r.x + r.y * r.y + r.z * r.z + r.w * r.w);
    const Real inv = norm > Real(0) ? Real(1) / norm : Real(1);
    return {r.x * inv, r.y * inv, r.z * inv, r.w * inv};
}
// The rotation a after b: rotate(composed(a, b), v) == rotate(a, rotate(b, v)).
WEIR_HD inline Real4 composed(const Real4& a, const Real4& b) {
    return {a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
            a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x,
            a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w,
            a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z};
}
// The rotation by angle |a| about a / |a|.
WEIR_HD inline Real4 rotationOf(const Vec3& a) {
    const Real angle = length(a);
    if (!(angle > Real(0))) {
        return {0, 0, 0, 1};
    }
    const Real s = std::sin(Real(0.5) * angle) / angle;
    return {a.x * s, a.y * s, a.z * s, std::cos(Real(0.5) * angle)};
}

struct RigidBody {
    // State: the centre of mass, orientation, its velocity and angular velocity (world frame).
    // q turns the body's frame (the world's axes at the start, origin at the centre of mass) into
    // the world's: the identity at t = 0.
    Vec3 x;
    Real4 q{0, 0, 0, 1};
    Vec3 v, omega;
    // Constants. invMass 0: driven (infinitely heavy to the fluid and to contacts).
    Real invMass = 0;
    Vec3 invInertia;  // principal, about the axes below
    Real4 axes{0, 0, 0,
               1};  // the principal axes in the body's frame (a box's or sphere's: its own)
    BodyShape shape = BodyShape::Box;
    Vec3 halfSize;   // a box's half extents; a sphere's radius in each; a mesh's bounding box's
    Vec3 boxCentre;  // the bounding box's centre in the body's frame (a mesh's; 0 for a box)
    BodyMotion motion = BodyMotion::Floating;
    Vec3 home;       // driven: the centre at t = 0
    Vec3 amplitude;  // oscillating, m
    Real period = 1, ramp = 0;
    Vec3 rate;  // rotating, rad/s
    // The fluid's force and torque (about x) on it over the last step.
    Vec3 force, torque;
};

// The rotation from the body's principal axes to the world's.
WEIR_HD inline Real4 principalToWorld(const RigidBody& b) { return composed(b.q, b.axes); }

// The body's inverse inertia in the world frame applied to v.
WEIR_HD inline Vec3 inverseInertiaTimes(const RigidBody& b, const Vec3& v) {
    const Real4 p = principalToWorld(b);
    const Vec3 local = rotateBack(p, v);
    return rotate(
        p, Vec3(local.x * b.invInertia.x, local.y * b.invInertia.y, local.z * b.invInertia.z));
}

// A driven body's pose and velocities at time t.
WEIR_HD inline void placeDrivenBody(RigidBody& b, double t) {
    if (b.motion == BodyMotion::Oscillating) {
        const double w = 2 * 3.14159265358979323846 / double(b.period);
        const double ramp = double(b.ramp);
        const double s = ramp > 0 && t < ramp ? t / ramp : 1.0;
        const double ds = ramp > 0 && t < ramp ? 1.0 / ramp : 0.0;
        const double sine = std::sin(w * t), cosine = std::cos(w * t);
        b.x = b.home + b.amplitude * Real(s * sine);
        b.v = b.amplitude * Real(ds * sine + s * w * cosine);
        b.omega = Vec3();
    } else if (b.motion == BodyMotion::Rotating) {
        b.x = b.home;
        b.v = Vec3();
        b.q = rotationOf(b.rate * Real(t));
        b.omega = b.rate;
    }
}

// A floating body over dt under the fluid's force and torque (b.force, b.torque) and gravity:
// semi-implicit Euler, Euler's equations in the principal axes for the rotation.
WEIR_HD inline void advanceFloatingBody(RigidBody& b, const Vec3& gravity, Real dt) {
    b.v += (b.force * b.invMass + gravity) * dt;
    const Real4 principal = principalToWorld(b);
    Vec3 w = rotateBack(principal, b.omega);
    const Vec3 torque = rotateBack(principal, b.torque);
    const Vec3 momentum(w.x / b.invInertia.x, w.y / b.invInertia.y, w.z / b.invInertia.z);
    const Vec3 dw = torque - cross(w, momentum);
    w += Vec3(dw.x * b.invInertia.x, dw.y * b.invInertia.y, dw.z * b.invInertia.z) * dt;
    b.omega = rotate(principal, w);
    b.x += b.v * dt;
    b.q = turned(b.q, b.omega, dt);
}

// An impulse along n (unit, pointing away from the obstacle) at the body point x + r: an
// inelastic normal impulse that stops the point's approach, and a Coulomb friction impulse
// (at most `friction` times the normal one) against its sliding.
WEIR_HD inline void contactImpulse(RigidBody& b, const Vec3& r, const Vec3& n, Real friction) {
    const Vec3 pointVelocity = b.v + cross(b.omega, r);
    const Real approach = dot(pointVelocity, n);
    if (!(approach < Real(0))) {
        return;
    }
    const Real k = b.invMass + dot(n, cross(inverseInertiaTimes(b, cross(r, n)), r));
    if (!(k > Real(0))) {
        return;
    }
    const Real j = -approach / k;
    Vec3 impulse = n * j;
    const Vec3 slide = pointVelocity - n * approach;
    const Real slideSpeed = length(slide);
    if (slideSpeed > Real(0)) {
        const Vec3 t = slide / slideSpeed;
        const Real kt = b.invMass + dot(t, cross(inverseInertiaTimes(b, cross(r, t)), r));
        Real jt = kt > Real(0) ? slideSpeed / kt : Real(0);
        jt = jt < friction * j ? jt : friction * j;
        impulse -= t * jt;
    }
    b.v += impulse * b.invMass;
    b.omega += inverseInertiaTimes(b, cross(r, impulse));
}

// Keeps a floating body inside the box [lo, hi] (walls on the axes not in periodicAxes): the
// deepest point past each wall is moved back onto it, with a contact impulse there.
WEIR_HD inline void containBody(RigidBody& b, const Vec3& lo, const Vec3& hi, int periodicAxes,
                                Real friction) {
    for (int a = 0; a < 3; ++a) {
        if ((periodicAxes >> a) & 1) {
            continue;
        }
        for (int side = 0; side < 2; ++side) {
            const Real sign = side == 0 ? Real(1) : Real(-1);  // the wall's normal along a
            Real deepest = 0;
            Vec3 where;
            if (b.shape == BodyShape::Sphere) {
                Vec3 n;
                n[a] = sign;
                where = n * (-b.halfSize.x);
                const Real depth =
                    side == 0 ? lo[a] - (b.x[a] + where[a]) : (b.x[a] + where[a]) - hi[a];
                deepest = depth;
            } else {
                deepest = -1;
                for (int k = 0; k < 8; ++k) {
                    const Vec3 corner = b.boxCentre + Vec3((k & 1) ? b.halfSize.x : -b.halfSize.x,
                                                           (k & 2) ? b.halfSize.y : -b.halfSize.y,
                                                           (k & 4) ? b.halfSize.z : -b.halfSize.z);
                    const Vec3 r = rotate(b.q, corner);
                    const Real depth =
                        side == 0 ? lo[a] - (b.x[a] + r[a]) : (b.x[a] + r[a]) - hi[a];
                    if (depth > deepest) {
                        deepest = depth;
                        where = r;
                    }
                }
            }
            if (deepest > Real(0)) {
                b.x[a] += sign * deepest;
                Vec3 n;
                n[a] = sign;
                contactImpulse(b, where, n, friction);
            }
        }
    }
}

// The radius of a sphere around the body's centre that holds it.
WEIR_HD inline Real boundingRadius(const RigidBody& b) {
    return b.shape == BodyShape::Sphere ? b.halfSize.x : length(b.boxCentre) + length(b.halfSize);
}

// Two bodies whose bounding spheres overlap: pushed apart along the line of centres (by their
// inverse masses) and their approach along it stopped, momentum conserved.
WEIR_HD inline void separateBodies(RigidBody& a, RigidBody& b) {
    const Real inverseSum = a.invMass + b.invMass;
    if (!(inverseSum > Real(0))) {
        return;
    }
    Vec3 between = b.x - a.x;
    const Real distance = length(between);
    const Real overlap = boundingRadius(a) + boundingRadius(b) - distance;
    if (!(overlap > Real(0)) || !(distance > Real(0))) {
        return;
    }
    const Vec3 n = between / distance;
    a.x -= n * (overlap * a.invMass / inverseSum);
    b.x += n * (overlap * b.invMass / inverseSum);
    const Real approach = dot(b.v - a.v, n);
    if (approach < Real(0)) {
        const Real j = -approach / inverseSum;
        a.v -= n * (j * a.invMass);
        b.v += n * (j * b.invMass);
    }
}

// The bodies as the scene layer sets them up (scene/setup.cpp).
struct RigidBodySetup {
    std::vector<RigidBody> bodies;
    std::vector<Real4> particles;  // each body's boundary particles: x, y, z in its frame, psi
    std::vector<int> owner;        // the body of each particle; a body's particles are together
    std::size_t size() const { return bodies.size(); }
};

// Coulomb friction of a body's contacts with walls and other bodies.
constexpr Real kContactFriction = Real(0.5);

// What the stages see of the bodies: their states and, for each boundary particle slot in the
// wall grid's order, where it came from (static walls first, then the bodies' particles).
struct RigidBodyView {
    RigidBody* bodies = nullptr;
    int count = 0;
    const Index* slotSource = nullptr;  // wall grid slot -> source (< staticCount: a wall's)
    const int* bodyOf = nullptr;        // body particle -> its body
    Index staticCount = 0;              // static wall particles
    Index particleCount = 0;            // the bodies' particles
    // Per body particle: the fluid's force and torque on it (about its body's centre), six
    // arrays of particleCount one after the other (fx, fy, fz, tx, ty, tz).
    Real* loads = nullptr;
};

}  // namespace weir
