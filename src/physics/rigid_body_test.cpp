// A rigid body's free motion (physics/rigid_body.h): with no force or torque its angular
// momentum stays what it was, and a body whose principal axes are turned from its frame moves as
// the same body with its frame turned.
#include "physics/rigid_body.h"

#include <gtest/gtest.h>

namespace weir {
namespace {

// The angular momentum I_world omega of a body.
Vec3 angularMomentum(const RigidBody& b) {
    const Real4 p = principalToWorld(b);
    const Vec3 w = rotateBack(p, b.omega);
    return rotate(p, Vec3(w.x / b.invInertia.x, w.y / b.invInertia.y, w.z / b.invInertia.z));
}

RigidBody tumblingBody(const Real4& axes, const Real4& q) {
    RigidBody b;
    b.invMass = Real(1);
    b.invInertia = Vec3(Real(1) / Real(1), Real(1) / Real(2), Real(1) / Real(3));
    b.axes = axes;
    b.q = q;
    b.omega = Vec3(Real(0.3), Real(1.0), Real(0.2));  // near the unstable middle axis: it tumbles
    return b;
}

TEST(RigidBodyMotion, TorqueFreeTumblingKeepsItsAngularMomentum) {
    RigidBody b =
        tumblingBody(rotationOf(Vec3(Real(0.4), Real(-0.7), Real(0.2))), Real4{0, 0, 0, 1});
    const Vec3 start = angularMomentum(b);
    const Real dt = Real(2e-4);
    for (int step = 0; step < 10000; ++step) {  // 2 s, several turns
        advanceFloatingBody(b, Vec3(), dt);
    }
    const Vec3 end = angularMomentum(b);
    // Semi-implicit Euler drifts by O(dt) per unit time.
    EXPECT_LT(length(end - start), 5e-3 * length(start));
    EXPECT_GT(length(b.omega - Vec3(Real(0.3), Real(1.0), Real(0.2))), Real(0.05));  // it moved
}

TEST(RigidBodyMotion, TurnedPrincipalAxesMoveAsATurnedFrame) {
    // Body A: its frame the world's, its principal axes turned by R. Body B: principal axes its
    // frame's, the frame turned by R. The same solid: its spin and its principal axes' pose must
    // agree at every step.
    const Real4 turn = rotationOf(Vec3(Real(0.5), Real(0.1), Real(-0.8)));
    RigidBody a = tumblingBody(turn, Real4{0, 0, 0, 1});
    RigidBody b = tumblingBody(Real4{0, 0, 0, 1}, turn);
    const Real dt = Real(1e-3);
    for (int step = 0; step < 1000; ++step) {
        a.torque = b.torque = Vec3(Real(0.01), Real(0), Real(0.02));
        advanceFloatingBody(a, Vec3(0, -9.81f, 0), dt);
        advanceFloatingBody(b, Vec3(0, -9.81f, 0), dt);
    }
    EXPECT_LT(length(a.omega - b.omega), Real(1e-4));
    EXPECT_LT(length(a.x - b.x), Real(1e-5));
    const Vec3 probe(Real(0.3), Real(-0.2), Real(0.9));
    EXPECT_LT(length(rotate(principalToWorld(a), probe) - rotate(principalToWorld(b), probe)),
              Real(1e-4));
}

}  // namespace
}  // namespace weir
