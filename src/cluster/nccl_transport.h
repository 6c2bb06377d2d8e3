// GPU-to-GPU particle transfer between ranks by NCCL (NVLink or the network, no host staging):
// the halo exchange of distributed CUDA runs. Built where NCCL is found (WEIR_HAS_NCCL).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "cluster/communicator.h"
#include "solver/particles.h"

namespace weir {

class NcclTransport {
   public:
    // Whether this weir was built with NCCL.
    static bool available();
    // One NCCL communicator over the ranks of `comm` (collective; each rank's GPU already set).
    explicit NcclTransport(Communicator& comm);
    ~NcclTransport();
    NcclTransport(const NcclTransport&) = delete;
    NcclTransport& operator=(const NcclTransport&) = delete;

    // Sends sendCounts[k] particles, taken in turn from `from`, to rank toRanks[k], and
    // receives receiveCounts[r] particles from each rank r into `into`, rank after rank; all on
    // `stream` (a cudaStream_t), in one NCCL group. Zero counts send nothing.
    void exchange(const ParticleSpans& from, const std::vector<int>& toRanks,
                  const std::vector<std::int64_t>& sendCounts, const ParticleSpans& into,
                  const std::vector<std::int64_t>& receiveCounts, void* stream);

   private:
    struct State;
    std::unique_ptr<State> state_;
};

}  // namespace weir
