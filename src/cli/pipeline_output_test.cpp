// End-to-end tests of the output that artists' tools open (issue 22): frame numbers from 1, ids,
// OpenVDB frames and meshes, the USD stage, and damaged VDB files given to weir mesh.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/cli_test_support.h"
#include "io/frame_reader.h"
#include "io/optional_formats.h"
#include "io/vdb_file.h"

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

TEST_F(Cli, VdbFramesAndSurfacesOrAClearNoOpenVdb) {
    writeFile("tiny.json", kTinyDrawScene);
    if (!openVdbBuilt()) {
        for (const std::string args : {std::string(kTinyRun) + " --frames 1 --format vdb --out v",
                                       std::string("mesh v --format obj,vdb")}) {
            const RunResult result = weir(args);
            EXPECT_EQ(result.exitCode, 2) << args << "\n" << result.output;
            EXPECT_TRUE(contains(result.output, "this build has no OpenVDB"));
            EXPECT_TRUE(contains(result.output, "libopenvdb-dev"));
        }
        return;
    }
    RunResult run = weir(std::string(kTinyRun) + " --frames 1 --format vdb --out v");
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_TRUE(contains(run.output, "frame_NNNNN.vdb volumes in Houdini"));
    EXPECT_EQ(entries(dir_ / "v"),
              (std::vector<std::string>{"frame_00000.vdb", "frame_00001.vdb", "frames.json"}));
    double time = -1;
    const HostParticles frame = readVdbFrame((dir_ / "v" / "frame_00001.vdb").string(), &time);
    EXPECT_EQ(frame.size(), 144u);
    EXPECT_NEAR(time, 1 / 30.0, 1e-12);
    // weir mesh reads the vdb frames and writes vdb surfaces beside the OBJ files.
    RunResult mesh = weir("mesh v --format obj,vdb --quiet");
    ASSERT_EQ(mesh.exitCode, 0) << mesh.output;
    EXPECT_EQ(entries(dir_ / "v" / "mesh"),
              (std::vector<std::string>{"surface_00000.obj", "surface_00000.vdb",
                                        "surface_00001.obj", "surface_00001.vdb"}));
    EXPECT_EQ(readVdbFrame((dir_ / "v" / "mesh" / "surface_00001.vdb").string()).x, frame.x);
}

TEST_F(Cli, ATruncatedOrForeignVdbFrameIsRefusedNamingIt) {
    if (!openVdbBuilt()) {
        GTEST_SKIP() << "this build has no OpenVDB";
    }
    writeFile("tiny.json", kTinyDrawScene);
    ASSERT_EQ(weir(std::string(kTinyRun) + " --frames 1 --format vdb --out v").exitCode, 0);
    const std::string bytes = fileText(dir_ / "v" / "frame_00001.vdb");
    for (const std::string& damaged :
         {bytes.substr(0, bytes.size() / 2), bytes.substr(0, 100), std::string("not a vdb\n")}) {
        writeFile("v/frame_00001.vdb", damaged);
        for (const std::string args : {"mesh v --frame 1 --quiet", "mesh v --quiet"}) {
            const RunResult mesh = weir(args);
            EXPECT_EQ(mesh.exitCode, 1) << args << "\n" << mesh.output;
            EXPECT_TRUE(contains(mesh.output, "cannot read '"));
            EXPECT_TRUE(contains(mesh.output, "frame_00001.vdb'"));
        }
#if defined(WEIR_HAS_RENDER)
        const RunResult render = weir("render v --frame 1 --quiet");
        EXPECT_EQ(render.exitCode, 1) << render.output;
        EXPECT_TRUE(contains(render.output, "frame_00001.vdb'"));
        EXPECT_FALSE(fs::exists(dir_ / "v" / "images" / "frame_00001.png"));
#endif
    }
}

// weir writes USD stages but reads no USD: a frames.json that lists one (made by hand or by
// another tool) gets an error naming the file and the formats weir reads.
TEST_F(Cli, AUsdFileListedAsAFrameIsRefusedNamingIt) {
    fs::create_directories(dir_ / "u");
    writeFile("u/frames.json",
              R"({"frames": [{"index": 0, "time": 0, "file": "frame_00000.usda"}]})");
    writeFile("u/frame_00000.usda", "#usda 1.0\n");
    const RunResult mesh = weir("mesh u --quiet");
    EXPECT_EQ(mesh.exitCode, 1) << mesh.output;
    EXPECT_TRUE(contains(mesh.output, "frame_00000.usda': unknown frame format '.usda'"));
}

TEST_F(Cli, UsdStageOfARunIsWrittenAtomically) {
    writeFile("tiny.json", kTinyDrawScene);
    const RunResult run = weir(std::string(kTinyRun) + " --frames 2 --usd --out frames");
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_TRUE(contains(run.output, "frames.usda: 3 frames (particles, container and obstacles)"));
    EXPECT_EQ(entries(dir_ / "frames"),
              (std::vector<std::string>{"frame.pvd", "frame_00000.vtu", "frame_00001.vtu",
                                        "frame_00002.vtu", "frames.json", "frames.usda"}));
    const std::string stage = fileText(dir_ / "frames" / "frames.usda");
    EXPECT_EQ(stage.rfind("#usda 1.0\n", 0), 0u);
    EXPECT_TRUE(contains(stage, "startTimeCode = 0\n"));
    EXPECT_TRUE(contains(stage, "endTimeCode = 2\n"));
    EXPECT_TRUE(contains(stage, "def Points \"particles\""));
    EXPECT_TRUE(contains(stage, "            2: [0, 1, 2, 3, "));  // the ids of frame 2
    // --overwrite removes the earlier run's stage with its frames.
    const RunResult again = weir(std::string(kTinyRun) + " --frames 0 --overwrite --out frames");
    ASSERT_EQ(again.exitCode, 0) << again.output;
    EXPECT_EQ(entries(dir_ / "frames"),
              (std::vector<std::string>{"frame.pvd", "frame_00000.vtu", "frames.json"}));
    ASSERT_EQ(weir(std::string(kTinyRun) + " --frames 1 --usd --overwrite --out frames").exitCode,
              0);
    // An unwritable stage: exit 1 naming it, nothing left behind.
    const RunResult bad = weir("usd frames --out frames/no/such/dir/s.usda");
    EXPECT_EQ(bad.exitCode, 1) << bad.output;
    EXPECT_TRUE(contains(bad.output, "frames/no/such/dir/s.usda"));
}

}  // namespace
}  // namespace weir
