// End-to-end tests of the output that artists' tools open (issue 22): frame numbers from 1 and
// particle ids.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/cli_test_support.h"
#include "io/frame_reader.h"

namespace weir {
namespace {

using namespace cli_testing;
using Json = nlohmann::json;

constexpr const char* kTinyRun = "run tiny.json --backend cpu --quiet";

TEST_F(Cli, FirstFrameNumberOneNumbersFilesIndexAndMeshesFromOne) {
    writeFile("tiny.json", kTinyDrawScene);
    RunResult run = weir(std::string(kTinyRun) +
                         " --frames 2 --format csv --first-frame-number 1 --mesh --out frames");
    ASSERT_EQ(run.exitCode, 0) << run.output;
    const fs::path out = dir_ / "frames";
    EXPECT_EQ(entries(out), (std::vector<std::string>{"frame_00001.csv", "frame_00002.csv",
                                                      "frame_00003.csv", "frames.json", "mesh"}));
    EXPECT_EQ(
        entries(out / "mesh"),
        (std::vector<std::string>{"surface_00001.obj", "surface_00001.ply", "surface_00002.obj",
                                  "surface_00002.ply", "surface_00003.obj", "surface_00003.ply"}));
    const Json index = Json::parse(fileText(out / "frames.json"));
    ASSERT_EQ(index["frames"].size(), 3u);
    for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(index["frames"][k]["index"], k + 1);
        EXPECT_NEAR(index["frames"][k]["time"].get<double>(), k / 30.0, 1e-12);
    }
    // Frame number 1 is the initial state: the particles at rest, ids 0 .. n - 1 in order.
    const HostParticles first = readCsv((out / "frame_00001.csv").string());
    ASSERT_EQ(first.size(), 144u);
    for (std::size_t i = 0; i < first.size(); ++i) {
        ASSERT_EQ(first.vy[i], 0) << i;
    }
    const std::string text = fileText(out / "frame_00001.csv");
    EXPECT_TRUE(contains(text, "density,pressure,id\n"));
    EXPECT_EQ(text.substr(text.rfind(',', text.size() - 2)), ",143\n");
    // weir mesh selects frames by these numbers.
    RunResult mesh = weir("mesh frames --frame 3 --format obj --out again --quiet");
    ASSERT_EQ(mesh.exitCode, 0) << mesh.output;
    EXPECT_EQ(entries(dir_ / "again"), std::vector<std::string>{"surface_00003.obj"});
    EXPECT_EQ(weir("mesh frames --frame 0 --quiet").exitCode, 2);
}

}  // namespace
}  // namespace weir
