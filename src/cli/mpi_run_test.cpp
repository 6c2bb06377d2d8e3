// `mpirun -n R weir run` end to end (in weir_mpi_tests, at 1, 2 and 3 ranks).
#include <gtest/gtest.h>

#include <string>

#include "cli/commands.h"
#include "cluster/mpi_test_support.h"
#include "io/frame_reader.h"
#include "solver/solver_test_support.h"

namespace weir {
namespace {

using testing::world;

// `mpirun -n R weir run` writes one set of frames (rank 0 gathers them) holding the single-rank
// run's fluid.
TEST(Distributed, RunWritesTheFramesOfTheSingleRankRun) {
    const std::string out = ::testing::TempDir() + "weir_mpi_run_" + std::to_string(world().size());
    RunOptions options;
    options.scene = "dam_break";
    options.backend = "cpu";
    options.particles = 3000;
    options.frames = 3;
    options.outDir = out;
    options.overwrite = true;  // a folder of an earlier run of this test
    options.quiet = true;
    ASSERT_EQ(runCommand(options), 0);
    if (world().rank() != 0) {
        return;
    }
    SetupOptions setupOptions;
    setupOptions.particleCount = 3000;
    SetupReport report;
    auto plain = makeSimulation(Backend::Cpu, NeighbourMode::Auto,
                                buildSetup(builtinScene("dam_break"), setupOptions, &report));
    for (int frame = 1; frame <= 3; ++frame) {  // landing on each frame time, as the run does
        plain->advanceTo(frame * report.frameInterval);
    }
    HostParticles want;
    plain->download(want);
    double time = 0;
    const HostParticles got = readVtu(out + "/frame_00003.vtu", &time);
    EXPECT_DOUBLE_EQ(time, 3 * report.frameInterval);
    ASSERT_EQ(got.size(), want.size());
    EXPECT_LT(testing::maxPositionDifference(got, want), 1e-3 * report.spacing);
}

}  // namespace
}  // namespace weir
