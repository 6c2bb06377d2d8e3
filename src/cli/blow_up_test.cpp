// A blow-up that used to pass unnoticed (issue 21): a dam-break block thrown at 1000 m/s with a
// fixed 1 ms step finished with exit 0 and 31 frames, 5,184 of its 5,200 particles on one point
// at +100,521% density. The compression and collapse checks (physics/faults.h) must stop it: exit
// 3, a diagnosis, and only frames from before the blow-up kept.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <string>
#include <tuple>

#include "cli/cli_test_support.h"
#include "io/frame_reader.h"

namespace weir {
namespace {

using namespace cli_testing;

TEST_F(Cli, BlockThrownAt1000MetresPerSecondExits3WithOnlyValidFrames) {
    // scenes/dam_break.json with the block's velocity and a fixed step.
    writeFile("thrown.json", R"({
        "name": "thrown",
        "container": {"min": [0, 0, 0], "max": [1.6, 1.0, 0.6]},
        "blocks": [{"min": [0, 0, 0], "max": [0.4, 0.6, 0.6], "velocity": [1000, 0, 0]}],
        "fluid": {"restDensity": 1000},
        "particles": {"count": 5200, "smoothingRatio": 2.0},
        "gravity": [0, -9.81, 0],
        "time": {"duration": 1.0, "frameRate": 30, "timeStep": 0.001}
    })");
    const RunResult run = weir("run thrown.json --backend cpu --quiet --out thrown");
    ASSERT_EQ(run.exitCode, 3) << run.output;
    EXPECT_TRUE(contains(run.output, "blew up at step"));
    // The diagnosis names what happened (it said "unknown fault code 4" for a compression).
    EXPECT_TRUE(contains(run.output, "times the rest density") ||
                contains(run.output, "collapsed onto one point"));
    EXPECT_EQ(run.output.find("unknown fault code"), std::string::npos) << run.output;

    // The frames kept are the ones frames.json lists, and each is a fluid, not a blow-up:
    // finite, no denser than the compression bound (rho0 (1 + 0.5)), no particles stacked.
    const nlohmann::json index = nlohmann::json::parse(fileText(dir_ / "thrown" / "frames.json"));
    const std::size_t kept = index["frames"].size();
    EXPECT_LT(kept, 31u);
    std::size_t files = 0;
    for (const auto& entry : fs::directory_iterator(dir_ / "thrown")) {
        files += entry.path().extension() == ".vtu";
    }
    EXPECT_EQ(files, kept);
    for (const auto& frame : index["frames"]) {
        const std::string file = (dir_ / "thrown" / frame["file"].get<std::string>()).string();
        SCOPED_TRACE(file);
        const HostParticles p = readVtu(file);
        ASSERT_GT(p.size(), 5000u);
        EXPECT_NO_THROW(checkFramePositions(p, file));
        std::set<std::tuple<Real, Real, Real>> points;
        for (std::size_t i = 0; i < p.size(); ++i) {
            ASSERT_TRUE(std::isfinite(p.rho[i])) << i;
            ASSERT_LE(p.rho[i], 1000 * 1.5 * 1.001) << i;
            points.emplace(p.x[i], p.y[i], p.z[i]);
        }
        EXPECT_GT(points.size(), p.size() * 99 / 100) << "particles on the same point";
    }
}

}  // namespace
}  // namespace weir
