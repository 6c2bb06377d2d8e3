// The one-rank communicator, and the MPI entry points of a build without MPI.
#include "cluster/communicator.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

namespace weir {

namespace {

class SoloCommunicator final : public Communicator {
   public:
    int rank() const override { return 0; }
    int size() const override { return 1; }
    std::string where() const override { return "rank 0 of 1"; }
    void maxInPlace(std::vector<double>&) override {}
    void sumInPlace(std::vector<std::int64_t>&) override {}
    std::vector<Bytes> exchange(const std::vector<Bytes>& toRank) override { return toRank; }
    std::vector<Bytes> allGather(const Bytes& mine) override { return {mine}; }
    std::vector<Bytes> gatherToRoot(const Bytes& mine) override { return {mine}; }
    void barrier() override {}
    [[noreturn]] void abort(int exitCode) override { std::exit(exitCode); }
    std::unique_ptr<Communicator> firstRanks(int count) override {
        if (count != 1) {
            throw std::invalid_argument("a solo run has one rank, not " + std::to_string(count));
        }
        return std::make_unique<SoloCommunicator>();
    }
};

}  // namespace

std::unique_ptr<Communicator> makeSoloCommunicator() {
    return std::make_unique<SoloCommunicator>();
}

int launcherRankCount() {
    for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE", "SLURM_NTASKS"}) {
        if (const char* value = std::getenv(name)) {
            return std::max(1, std::atoi(value));
        }
    }
    return 0;
}

#if !defined(WEIR_HAS_MPI)
bool launchedByMpi() { return false; }
void startCommunication(int*, char***) {
    if (launcherRankCount() > 1) {
        // Each process would run the whole scene alone and write the same frames.
        std::fprintf(stderr,
                     "weir: error: started as %d ranks by an MPI launcher, but this weir was "
                     "built without MPI. On Debian/Ubuntu: apt-get install libopenmpi-dev "
                     "openmpi-bin, then configure and build again (or run scripts/setup.sh).\n",
                     launcherRankCount());
        std::exit(2);
    }
}
void endCommunication() {}
std::unique_ptr<Communicator> worldCommunicator() { return makeSoloCommunicator(); }
int localRank() { return 0; }
#endif

}  // namespace weir
