// scatterToHostFrame: one parallel pass over the particles.
#include "solver/host_frame.h"

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
}

}  // namespace weir
