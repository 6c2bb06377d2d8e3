// Builds without CUDA have no interop: `weir view` copies particles through the host.
#include "render/particle_interop.h"

namespace weir {

#if !defined(WEIR_HAS_CUDA)
std::unique_ptr<ParticleInterop> makeParticleInterop(Simulation&, std::string* why) {
    if (why != nullptr) {
        *why = "this weir was built without CUDA";
    }
    return nullptr;
}
#endif

}  // namespace weir
