// main() of the MPI test binary: MPI started and a GPU chosen per rank before GoogleTest runs;
// gtest's printer on rank 0 only; a failure on any rank fails every rank's exit code.
#include <gtest/gtest.h>

#include <cstdio>
#include <vector>

#include "cluster/communicator.h"
#include "cluster/mpi_test_support.h"
#include "core/backend.h"

namespace weir {
namespace {

using testing::world;

int runAllTests(int argc, char** argv) {
    ::testing::InitGoogleTest(&argc, argv);
    if (world().rank() != 0) {
        delete ::testing::UnitTest::GetInstance()->listeners().Release(
            ::testing::UnitTest::GetInstance()->listeners().default_result_printer());
    }
    const int mine = RUN_ALL_TESTS();
    std::vector<double> any{double(mine)};
    world().maxInPlace(any);
    if (mine != 0) {
        std::fprintf(stderr, "weir_mpi_tests: failures on %s\n", world().where().c_str());
    }
    return any[0] != 0 ? 1 : 0;
}

}  // namespace
}  // namespace weir

int main(int argc, char** argv) {
    weir::startCommunication(&argc, &argv);
    weir::selectCudaDevice(weir::localRank());
    const int code = weir::runAllTests(argc, argv);
    weir::endCommunication();
    return code;
}
