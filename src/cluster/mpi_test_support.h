// The world communicator of the MPI test binary (weir_mpi_tests, run under mpirun).
#pragma once

#include <memory>

#include "cluster/communicator.h"

namespace weir::testing {

inline Communicator& world() {
    static std::unique_ptr<Communicator> comm = worldCommunicator();
    return *comm;
}

}  // namespace weir::testing
