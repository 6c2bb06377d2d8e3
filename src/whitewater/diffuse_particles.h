// The diffuse (secondary) particles of whitewater: spray, foam and bubbles (Ihmsen et al. 2012),
// as structure-of-arrays on the host.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace weir {

// What a diffuse particle is, by the fluid around it (the count of fluid neighbours within h).
// The numbers are the `kind` column of whitewater_NNNNN.ply.
enum class DiffuseKind : std::uint8_t { Spray = 0, Foam = 1, Bubble = 2 };
constexpr int kDiffuseKinds = 3;

const char* diffuseKindName(DiffuseKind kind);

struct DiffuseParticles {
    std::vector<float> x, y, z;      // position [m]
    std::vector<float> vx, vy, vz;   // velocity [m/s]
    std::vector<std::uint8_t> kind;  // DiffuseKind
    std::vector<float> lifetime;     // seconds left; only foam's runs down

    std::size_t size() const { return x.size(); }
    DiffuseKind kindOf(std::size_t k) const { return DiffuseKind(kind[k]); }
    void resize(std::size_t n) {
        for (auto* a : {&x, &y, &z, &vx, &vy, &vz, &lifetime}) {
            a->resize(n);
        }
        kind.resize(n);
    }
    void push(float px, float py, float pz, float ux, float uy, float uz, DiffuseKind k,
              float life) {
        x.push_back(px);
        y.push_back(py);
        z.push_back(pz);
        vx.push_back(ux);
        vy.push_back(uy);
        vz.push_back(uz);
        kind.push_back(std::uint8_t(k));
        lifetime.push_back(life);
    }
    // How many are of this kind.
    std::size_t count(DiffuseKind k) const {
        std::size_t n = 0;
        for (std::uint8_t c : kind) {
            n += c == std::uint8_t(k) ? 1 : 0;
        }
        return n;
    }
};

}  // namespace weir
