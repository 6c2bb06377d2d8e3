// NCCL point-to-point transfer of particle arrays; without NCCL, a transport that cannot start.
#include "cluster/nccl_transport.h"

#include <cstring>
#include <stdexcept>
#include <string>

#if defined(WEIR_HAS_NCCL)
#include <cuda_runtime.h>
#include <nccl.h>
#endif

namespace weir {

#if defined(WEIR_HAS_NCCL)

namespace {

void check(ncclResult_t status, const char* what) {
    if (status != ncclSuccess) {
        throw std::runtime_error(std::string("NCCL ") + what +
                                 " failed: " + ncclGetErrorString(status));
    }
}

constexpr ncclDataType_t kRealType = sizeof(Real) == 8 ? ncclFloat64 : ncclFloat32;

}  // namespace

struct NcclTransport::State {
    ncclComm_t comm = nullptr;
    int rank = 0, size = 1;
};

bool NcclTransport::available() { return true; }

NcclTransport::NcclTransport(Communicator& comm) : state_(std::make_unique<State>()) {
    state_->rank = comm.rank();
    state_->size = comm.size();
    ncclUniqueId id;
    Bytes mine(sizeof id, 0);
    if (comm.rank() == 0) {
        check(ncclGetUniqueId(&id), "GetUniqueId");
        std::memcpy(mine.data(), &id, sizeof id);
    }
    const std::vector<Bytes> all = comm.allGather(mine);
    std::memcpy(&id, all[0].data(), sizeof id);
    check(ncclCommInitRank(&state_->comm, comm.size(), id, comm.rank()), "CommInitRank");
}

NcclTransport::~NcclTransport() {
    if (state_ && state_->comm != nullptr) {
        ncclCommDestroy(state_->comm);
    }
}

void NcclTransport::exchange(const ParticleSpans& from, const std::vector<int>& toRanks,
                             const std::vector<std::int64_t>& sendCounts, const ParticleSpans& into,
                             const std::vector<std::int64_t>& receiveCounts, void* stream) {
    cudaStream_t s = static_cast<cudaStream_t>(stream);
    check(ncclGroupStart(), "GroupStart");
    std::int64_t sent = 0;
    for (std::size_t k = 0; k < toRanks.size(); ++k) {
        const std::size_t n = std::size_t(sendCounts[k]);
        if (n > 0) {
            const int to = toRanks[k];
            check(ncclSend(from.pos + sent, 4 * n, kRealType, to, state_->comm, s), "Send");
            check(ncclSend(from.vel + sent, 4 * n, kRealType, to, state_->comm, s), "Send");
            check(ncclSend(from.id + sent, n, ncclInt32, to, state_->comm, s), "Send");
        }
        sent += std::int64_t(n);
    }
    std::int64_t received = 0;
    for (int r = 0; r < int(receiveCounts.size()); ++r) {
        const std::size_t n = std::size_t(receiveCounts[std::size_t(r)]);
        if (n > 0) {
            check(ncclRecv(into.pos + received, 4 * n, kRealType, r, state_->comm, s), "Recv");
            check(ncclRecv(into.vel + received, 4 * n, kRealType, r, state_->comm, s), "Recv");
            check(ncclRecv(into.id + received, n, ncclInt32, r, state_->comm, s), "Recv");
        }
        received += std::int64_t(n);
    }
    check(ncclGroupEnd(), "GroupEnd");
}

#else

struct NcclTransport::State {};

bool NcclTransport::available() { return false; }

NcclTransport::NcclTransport(Communicator&) {
    throw std::runtime_error("this weir was built without NCCL");
}

NcclTransport::~NcclTransport() = default;

void NcclTransport::exchange(const ParticleSpans&, const std::vector<int>&,
                             const std::vector<std::int64_t>&, const ParticleSpans&,
                             const std::vector<std::int64_t>&, void*) {
    throw std::runtime_error("this weir was built without NCCL");
}

#endif

}  // namespace weir
