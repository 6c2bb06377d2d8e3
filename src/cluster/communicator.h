// The ranks of a distributed run and what they say to each other: MPI when weir was started by
// mpirun (mpi_communicator.cpp, built where MPI is found), else one rank on its own. Messages are
// bytes; cluster/particle_messages.h packs particles into them.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace weir {

using Bytes = std::vector<char>;

class Communicator {
   public:
    virtual ~Communicator() = default;
    virtual int rank() const = 0;
    virtual int size() const = 0;
    // "rank 1 of 2 on host-a": how errors name the rank.
    virtual std::string where() const = 0;

    // Element-wise max / sum over all ranks, in place.
    virtual void maxInPlace(std::vector<double>& values) = 0;
    virtual void sumInPlace(std::vector<std::int64_t>& values) = 0;
    // Each rank sends toRank[r] to rank r; returns what rank r sent here, by r.
    virtual std::vector<Bytes> exchange(const std::vector<Bytes>& toRank) = 0;
    // Every rank's `mine`, by rank, on every rank.
    virtual std::vector<Bytes> allGather(const Bytes& mine) = 0;
    // Every rank's `mine`, by rank, on rank 0 (empty elsewhere).
    virtual std::vector<Bytes> gatherToRoot(const Bytes& mine) = 0;
    virtual void barrier() = 0;
    // Ends every rank of the run with `exitCode` (after this rank printed why).
    [[noreturn]] virtual void abort(int exitCode) = 0;
    // A communicator of ranks 0..count-1 of this one (nullptr on the others); collective.
    virtual std::unique_ptr<Communicator> firstRanks(int count) = 0;
};

// One rank, alone: what a run without mpirun uses.
std::unique_ptr<Communicator> makeSoloCommunicator();

// Ranks the launcher says it started (its environment), 0 when none did.
int launcherRankCount();
// True when this process was started by an MPI launcher (mpirun, srun) and weir has MPI.
bool launchedByMpi();
// MPI_Init when launched by MPI (else nothing); call once, first thing in main.
void startCommunication(int* argc, char*** argv);
// MPI_Finalize when it was started.
void endCommunication();
// All ranks of the run: MPI_COMM_WORLD under mpirun, else a solo communicator.
std::unique_ptr<Communicator> worldCommunicator();
// The rank's number among the ranks on its own host (picks its GPU); 0 without MPI.
int localRank();

}  // namespace weir
