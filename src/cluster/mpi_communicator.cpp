// The communicator over MPI (built only where MPI is found): MPI_COMM_WORLD under mpirun.
#include <mpi.h>
#include <unistd.h>

#include <cstdlib>
#include <limits>
#include <stdexcept>

#include "cluster/communicator.h"

namespace weir {

namespace {

bool started = false;

void check(int status, const char* what) {
    if (status != MPI_SUCCESS) {
        char text[MPI_MAX_ERROR_STRING];
        int length = 0;
        MPI_Error_string(status, text, &length);
        throw std::runtime_error(std::string("MPI ") + what +
                                 " failed: " + std::string(text, std::size_t(length)));
    }
}

int byteCount(std::size_t bytes) {
    if (bytes > std::size_t(std::numeric_limits<int>::max())) {
        throw std::runtime_error("an MPI message of " + std::to_string(bytes) +
                                 " bytes is past MPI's 2 GiB count limit: use more ranks");
    }
    return int(bytes);
}

// Displacements of a list of counts, and the total.
std::vector<int> offsetsOf(const std::vector<int>& counts, std::size_t* total) {
    std::vector<int> offsets(counts.size());
    std::size_t sum = 0;
    for (std::size_t r = 0; r < counts.size(); ++r) {
        offsets[r] = byteCount(sum);
        sum += std::size_t(counts[r]);
    }
    byteCount(sum);
    *total = sum;
    return offsets;
}

std::vector<Bytes> split(const Bytes& all, const std::vector<int>& counts,
                         const std::vector<int>& offsets) {
    std::vector<Bytes> parts(counts.size());
    for (std::size_t r = 0; r < counts.size(); ++r) {
        parts[r].assign(all.begin() + offsets[r], all.begin() + offsets[r] + counts[r]);
    }
    return parts;
}

class MpiCommunicator final : public Communicator {
   public:
    explicit MpiCommunicator(MPI_Comm comm, bool owned) : comm_(comm), owned_(owned) {
        MPI_Comm_rank(comm_, &rank_);
        MPI_Comm_size(comm_, &size_);
        char host[256] = {};
        gethostname(host, sizeof host - 1);
        host_ = host;
    }
    ~MpiCommunicator() override {
        if (owned_ && comm_ != MPI_COMM_NULL) {
            MPI_Comm_free(&comm_);
        }
    }
    int rank() const override { return rank_; }
    int size() const override { return size_; }
    std::string where() const override {
        return "rank " + std::to_string(rank_) + " of " + std::to_string(size_) + " on " + host_;
    }
    void maxInPlace(std::vector<double>& values) override {
        check(MPI_Allreduce(MPI_IN_PLACE, values.data(), int(values.size()), MPI_DOUBLE, MPI_MAX,
                            comm_),
              "Allreduce(max)");
    }
    void sumInPlace(std::vector<std::int64_t>& values) override {
        check(MPI_Allreduce(MPI_IN_PLACE, values.data(), int(values.size()), MPI_INT64_T, MPI_SUM,
                            comm_),
              "Allreduce(sum)");
    }
    std::vector<Bytes> exchange(const std::vector<Bytes>& toRank) override {
        std::vector<int> sendCounts(static_cast<std::size_t>(size_)),
            receiveCounts(static_cast<std::size_t>(size_));
        for (int r = 0; r < size_; ++r) {
            sendCounts[std::size_t(r)] = byteCount(toRank[std::size_t(r)].size());
        }
        check(MPI_Alltoall(sendCounts.data(), 1, MPI_INT, receiveCounts.data(), 1, MPI_INT, comm_),
              "Alltoall");
        std::size_t sendTotal = 0, receiveTotal = 0;
        const std::vector<int> sendOffsets = offsetsOf(sendCounts, &sendTotal);
        const std::vector<int> receiveOffsets = offsetsOf(receiveCounts, &receiveTotal);
        Bytes send(sendTotal), receive(receiveTotal);
        for (int r = 0; r < size_; ++r) {
            std::copy(toRank[std::size_t(r)].begin(), toRank[std::size_t(r)].end(),
                      send.begin() + sendOffsets[std::size_t(r)]);
        }
        check(MPI_Alltoallv(send.data(), sendCounts.data(), sendOffsets.data(), MPI_BYTE,
                            receive.data(), receiveCounts.data(), receiveOffsets.data(), MPI_BYTE,
                            comm_),
              "Alltoallv");
        return split(receive, receiveCounts, receiveOffsets);
    }
    std::vector<Bytes> allGather(const Bytes& mine) override {
        std::vector<int> counts(static_cast<std::size_t>(size_));
        const int count = byteCount(mine.size());
        check(MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, comm_), "Allgather");
        std::size_t total = 0;
        const std::vector<int> offsets = offsetsOf(counts, &total);
        Bytes all(total);
        check(MPI_Allgatherv(mine.data(), count, MPI_BYTE, all.data(), counts.data(),
                             offsets.data(), MPI_BYTE, comm_),
              "Allgatherv");
        return split(all, counts, offsets);
    }
    std::vector<Bytes> gatherToRoot(const Bytes& mine) override {
        std::vector<int> counts(static_cast<std::size_t>(size_));
        const int count = byteCount(mine.size());
        check(MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm_), "Gather");
        std::size_t total = 0;
        const std::vector<int> offsets = offsetsOf(counts, &total);
        Bytes all(rank_ == 0 ? total : 0);
        check(MPI_Gatherv(mine.data(), count, MPI_BYTE, all.data(), counts.data(), offsets.data(),
                          MPI_BYTE, 0, comm_),
              "Gatherv");
        return rank_ == 0 ? split(all, counts, offsets) : std::vector<Bytes>{};
    }
    void barrier() override { check(MPI_Barrier(comm_), "Barrier"); }
    [[noreturn]] void abort(int exitCode) override {
        MPI_Abort(MPI_COMM_WORLD, exitCode);
        std::exit(exitCode);
    }
    std::unique_ptr<Communicator> firstRanks(int count) override {
        if (count < 1 || count > size_) {
            throw std::invalid_argument("asked for the first " + std::to_string(count) +
                                        " ranks of " + std::to_string(size_));
        }
        MPI_Comm sub = MPI_COMM_NULL;
        check(MPI_Comm_split(comm_, rank_ < count ? 0 : MPI_UNDEFINED, rank_, &sub), "Comm_split");
        if (sub == MPI_COMM_NULL) {
            return nullptr;
        }
        return std::make_unique<MpiCommunicator>(sub, true);
    }

   private:
    MPI_Comm comm_;
    bool owned_;
    int rank_ = 0, size_ = 1;
    std::string host_;
};

}  // namespace

bool launchedByMpi() { return launcherRankCount() > 0; }

void startCommunication(int* argc, char*** argv) {
    if (launchedByMpi() && !started) {
        MPI_Init(argc, argv);
        // Errors come back as codes (check() turns them into exceptions that name the rank).
        MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
        started = true;
    }
}

void endCommunication() {
    if (started) {
        MPI_Finalize();
        started = false;
    }
}

std::unique_ptr<Communicator> worldCommunicator() {
    if (!started) {
        return makeSoloCommunicator();
    }
    return std::make_unique<MpiCommunicator>(MPI_COMM_WORLD, false);
}

int localRank() {
    for (const char* name : {"OMPI_COMM_WORLD_LOCAL_RANK", "MPI_LOCALRANKID", "SLURM_LOCALID"}) {
        if (const char* value = std::getenv(name)) {
            return std::atoi(value);
        }
    }
    return 0;
}

}  // namespace weir
