// The lattice seeder on the CUDA backend: the same rule, one thread per lattice point.
#include "core/exec_cuda.cuh"
#include "scene/lattice_seeder.h"
#include "scene/lattice_seeding.h"

namespace weir {

void LatticeSeeder::seed(CudaExec& exec, ParticleStore<CudaExec>& store) const {
    seedLattices(exec, store, seeds_, share_);
}

}  // namespace weir
