// The paper's simple collision response: particles put back on the container walls and off
// obstacle boxes and spheres, losing their velocity into the surface (walls.model "simple", and the
// safety net under boundary particles); periodic axes have no walls but wrap around.
#pragma once

#include <cmath>

#include "core/config.h"
#include "core/vec3.h"
#include "physics/sph_params.h"

namespace weir {

struct ObstacleBox {
    Vec3 min, max;
};
struct ObstacleSphere {
    Vec3 center;
    Real radius;
};
struct ObstacleView {
    const ObstacleBox* boxes;
    int boxCount;
    const ObstacleSphere* spheres;
    int sphereCount;
};

// Removes the part of v along unit normal n that points into the wall, keeping `restitution` of
// it (bounced back), and `1 - friction` of the tangential part.
WEIR_HD inline void reflectVelocity(Vec3& v, const Vec3& n, const SphParams& params) {
    Real vn = dot(v, n);
    if (vn < 0) {
        Vec3 tangential = v - n * vn;
        v = tangential * (Real(1) - params.friction) - n * (vn * params.restitution);
    }
}

// On a periodic axis, a particle that left through one face comes back through the other (a step
// moves a particle far less than the container's length).
WEIR_HD inline void wrapPeriodic(Vec3& x, const SphParams& params) {
    for (int a = 0; a < 3; ++a) {
        if (isPeriodic(params, a)) {
            const Real length = params.boxMax[a] - params.boxMin[a];
            if (x[a] < params.boxMin[a]) {
                x[a] += length;
            } else if (x[a] >= params.boxMax[a]) {
                x[a] -= length;
            }
        }
    }
}

// The paper's simple collision response: particles are put back on the container walls and off
// obstacle boxes and spheres, and lose their velocity into the surface.
WEIR_HD inline void collide(Vec3& x, Vec3& v, const SphParams& params,
                            const ObstacleView& obstacles) {
    for (int a = 0; a < 3; ++a) {
        if (isPeriodic(params, a)) {
            continue;  // no wall there (wrapPeriodic)
        }
        Vec3 n;
        if (x[a] < params.boxMin[a]) {
            x[a] = params.boxMin[a];
            n[a] = 1;
            reflectVelocity(v, n, params);
        } else if (x[a] > params.boxMax[a]) {
            x[a] = params.boxMax[a];
            n[a] = -1;
            reflectVelocity(v, n, params);
        }
    }
    for (int b = 0; b < obstacles.boxCount; ++b) {
        const ObstacleBox box = obstacles.boxes[b];
        // A face on or past a container wall (a box standing on the floor) is blocked: the wall
        // holds particles there, on the face itself, so the box is closed on that side and no
        // particle is sent out through it (it would land on the wall, still under the box, and
        // slide through).
        bool blocked[6];
        bool inside = true;
        for (int a = 0; a < 3; ++a) {
            const bool wall = !isPeriodic(params, a);
            blocked[2 * a] = wall && box.min[a] <= params.boxMin[a];
            blocked[2 * a + 1] = wall && box.max[a] >= params.boxMax[a];
            inside = inside && (x[a] > box.min[a] || (blocked[2 * a] && x[a] >= box.min[a])) &&
                     (x[a] < box.max[a] || (blocked[2 * a + 1] && x[a] <= box.max[a]));
        }
        if (!inside) {
            continue;
        }
        // Leave through the nearest open face (the nearest of all if every face is blocked: a
        // box that fills the container).
        int axis = -1;
        Real best = Real(1e30), side = 1;
        for (int pass = 0; pass < 2 && axis < 0; ++pass) {
            for (int a = 0; a < 3; ++a) {
                const Real toMin = x[a] - box.min[a], toMax = box.max[a] - x[a];
                if (toMin < best && (pass == 1 || !blocked[2 * a])) {
                    best = toMin;
                    axis = a;
                    side = -1;
                }
                if (toMax < best && (pass == 1 || !blocked[2 * a + 1])) {
                    best = toMax;
                    axis = a;
                    side = 1;
                }
            }
        }
        x[axis] = side < 0 ? box.min[axis] : box.max[axis];
        Vec3 n;
        n[axis] = side;
        reflectVelocity(v, n, params);
    }
    for (int s = 0; s < obstacles.sphereCount; ++s) {
        const ObstacleSphere sphere = obstacles.spheres[s];
        Vec3 d = x - sphere.center;
        Real r2 = lengthSquared(d);
        if (r2 >= sphere.radius * sphere.radius) {
            continue;
        }
        Real r = std::sqrt(r2);
        Vec3 n = r > Real(0) ? d / r : Vec3(0, 1, 0);
        x = sphere.center + n * sphere.radius;
        reflectVelocity(v, n, params);
    }
}

}  // namespace weir
