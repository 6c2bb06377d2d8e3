// scatterToHostFrame: one parallel pass over the particles.
#include "solver/host_frame.h"

#include <algorithm>
#include <vector>

#include "physics/eos.h"

namespace weir {

void scatterToHostFrame(const Index* ids, const Real4* pos, const Real4* vel, std::size_t n,
                        const SphParams& params, HostParticles& out) {
    out.resize(n);
    Real *x = out.x.data(), *y = out.y.data(), *z = out.z.data();
    Real *vx = out.vx.data(), *vy = out.vy.data(), *vz = out.vz.data();
    Real *rho = out.rho.data(), *p = out.p.data();
    const std::ptrdiff_t count = std::ptrdiff_t(n);
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t i = 0; i < count; ++i) {
        const std::size_t k = std::size_t(ids[i]);
        x[k] = pos[i].x;
        y[k] = pos[i].y;
        z[k] = pos[i].z;
        vx[k] = vel[i].x;
        vy[k] = vel[i].y;
        vz[k] = vel[i].z;
        rho[k] = vel[i].w;
        p[k] = pressureFromDensity(params, vel[i].w);
    }
    out.id.clear();
}

void sortToHostFrame(const Index* ids, const Real4* pos, const Real4* vel, std::size_t n,
                     const SphParams& params, HostParticles& out) {
    std::vector<std::size_t> order(n);
    for (std::size_t i = 0; i < n; ++i) {
        order[i] = i;
    }
    std::sort(order.begin(), order.end(),
              [&](std::size_t a, std::size_t b) { return ids[a] < ids[b]; });
    out.resize(n);
    out.id.resize(n);
    const std::ptrdiff_t count = std::ptrdiff_t(n);
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t k = 0; k < count; ++k) {
        const std::size_t i = order[std::size_t(k)];
        out.x[k] = pos[i].x;
        out.y[k] = pos[i].y;
        out.z[k] = pos[i].z;
        out.vx[k] = vel[i].x;
        out.vy[k] = vel[i].y;
        out.vz[k] = vel[i].z;
        out.rho[k] = vel[i].w;
        out.p[k] = pressureFromDensity(params, vel[i].w);
        out.id[k] = ids[i];
    }
}

}  // namespace weir
