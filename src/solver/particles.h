// Host-side particle data, structure of arrays, as written to frames.
#pragma once

#include <cstddef>
#include <vector>

#include "core/config.h"
#include "core/vec3.h"

namespace weir {

struct HostParticles {
    std::vector<Real> x, y, z;     // position [m]
    std::vector<Real> vx, vy, vz;  // velocity [m/s]
    std::vector<Real> rho;         // density [kg/m^3]
    std::vector<Real> p;           // pressure [Pa]

    std::size_t size() const { return x.size(); }
    void resize(std::size_t n) {
        for (auto* a : {&x, &y, &z, &vx, &vy, &vz, &rho, &p}) {
            a->resize(n);
        }
    }
    void push(const Vec3d& pos, const Vec3d& vel) {
        x.push_back(Real(pos.x));
        y.push_back(Real(pos.y));
        z.push_back(Real(pos.z));
        vx.push_back(Real(vel.x));
        vy.push_back(Real(vel.y));
        vz.push_back(Real(vel.z));
        rho.push_back(0);
        p.push_back(0);
    }
};

}  // namespace weir
