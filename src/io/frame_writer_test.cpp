// Tests for FrameWriter (names, directories, .pvd and frames.json) and the format names.
#include "io/frame_writer.h"

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "io/frame_index.h"
#include "io/frame_reader.h"
#include "io/io_test_support.h"

namespace weir {
namespace {

using test::TempDir;

TEST(FrameFormat, ParsesNamesAndRejectsOthersListingTheAllowed) {
    EXPECT_EQ(parseFrameFormat("vtu"), FrameFormat::Vtu);
    EXPECT_EQ(parseFrameFormat("ply"), FrameFormat::Ply);
    EXPECT_EQ(parseFrameFormat("csv"), FrameFormat::Csv);
    EXPECT_EQ(formatExtension(FrameFormat::Ply), "ply");
    try {
        parseFrameFormat("xyz");
        FAIL() << "expected std::invalid_argument";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("\"xyz\""), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("vtu, ply, csv"), std::string::npos) << e.what();
    }
}

TEST(FrameWriter, CreatesNestedDirectoriesAndNamesFrames) {
    TempDir dir;
    const std::string nested = dir / "a/b/c";
    FrameWriter writer(nested, FrameFormat::Ply, "splash");
    EXPECT_TRUE(std::filesystem::is_directory(nested));
    EXPECT_EQ(writer.dir(), nested);
    EXPECT_EQ(writer.framePath(7), nested + "/splash_00007.ply");
    EXPECT_EQ(writer.framePath(123456), nested + "/splash_123456.ply");
    EXPECT_EQ(FrameWriter(dir / "d", FrameFormat::Vtu).framePath(0), dir / "d/frame_00000.vtu");
}

TEST(FrameWriter, VtuFramesKeepPvdAndIndexUpToDate) {
    TempDir dir;
    FrameWriter writer(dir / "out", FrameFormat::Vtu);
    const std::vector<double> times = {0.0, 0.04, 1.0 / 3.0};
    for (int i = 0; i < 3; ++i) {
        writer.write(i, times[i], test::randomParticles(10 + i, i));
        // After every frame both indexes list exactly the frames so far.
        const std::string pvd = test::fileText(dir / "out/frame.pvd");
        const auto index = nlohmann::json::parse(test::fileText(dir / "out/frames.json"));
        EXPECT_EQ(index["format"], "vtu");
        EXPECT_EQ(index["count"], i + 1);
        ASSERT_EQ(index["frames"].size(), std::size_t(i + 1));
        for (int j = 0; j <= i; ++j) {
            const std::string file = "frame_0000" + std::to_string(j) + ".vtu";
            EXPECT_NE(pvd.find("file=\"" + file + "\""), std::string::npos) << pvd;
            EXPECT_EQ(index["frames"][j]["index"], j);
            EXPECT_EQ(index["frames"][j]["time"].get<double>(), times[j]);
            EXPECT_EQ(index["frames"][j]["file"], file);
        }
    }
    EXPECT_EQ(readVtuTime(writer.framePath(2)), times[2]);
    EXPECT_EQ(readVtu(writer.framePath(1)).size(), 11u);
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"out"});
    std::vector<std::string> files;
    for (const auto& entry : std::filesystem::directory_iterator(dir / "out")) {
        files.push_back(entry.path().filename().string());
    }
    std::sort(files.begin(), files.end());
    EXPECT_EQ(files, (std::vector<std::string>{"frame.pvd", "frame_00000.vtu", "frame_00001.vtu",
                                               "frame_00002.vtu", "frames.json"}));
}

TEST(FrameWriter, PlyAndCsvWriteIndexButNoPvd) {
    for (FrameFormat format : {FrameFormat::Ply, FrameFormat::Csv}) {
        TempDir dir;
        FrameWriter writer(dir.path().string(), format);
        const HostParticles particles = test::randomParticles(5);
        writer.write(3, 0.5, particles);
        const auto read = format == FrameFormat::Ply ? readPly(writer.framePath(3))
                                                     : readCsv(writer.framePath(3));
        EXPECT_EQ(read.size(), 5u);
        const std::string file = "frame_00003." + formatExtension(format);
        EXPECT_EQ(dir.entries(), (std::vector<std::string>{file, "frames.json"}));
        const auto index = nlohmann::json::parse(test::fileText(dir / "frames.json"));
        EXPECT_EQ(index["format"], formatExtension(format));
        EXPECT_EQ(index["frames"][0]["file"], file);
    }
}

// Rigid bodies' poses ride with their frame into frames.json and read back as they were written;
// an index whose poses are malformed is refused naming the field.
TEST(FrameWriter, BodyPosesGoIntoTheIndexAndReadBack) {
    TempDir dir;
    FrameWriter writer(dir.path().string(), FrameFormat::Csv);
    HostParticles particles = test::randomParticles(4);
    BodyPose pose;
    pose.position = Vec3d(0.5, 0.25, -1);
    pose.orientation[0] = 0.6;
    pose.orientation[3] = 0.8;
    pose.velocity = Vec3d(1, 2, 3);
    pose.angularVelocity = Vec3d(0, 0, -4);
    particles.bodies = {BodyPose{}, pose};
    writer.write(0, 0.0, test::randomParticles(4));  // a frame without bodies has no field
    writer.write(1, 0.1, particles);
    const std::vector<FrameEntry> frames = readFrameIndex(dir.path().string());
    ASSERT_EQ(frames.size(), 2u);
    EXPECT_TRUE(frames[0].bodies.empty());
    ASSERT_EQ(frames[1].bodies.size(), 2u);
    const BodyPose& read = frames[1].bodies[1];
    EXPECT_EQ(read.position.y, 0.25);
    EXPECT_EQ(read.orientation[0], 0.6);
    EXPECT_EQ(read.orientation[3], 0.8);
    EXPECT_EQ(read.velocity.z, 3);
    EXPECT_EQ(read.angularVelocity.z, -4);
    EXPECT_EQ(frames[1].bodies[0].orientation[3], 1);

    auto index = nlohmann::json::parse(test::fileText(dir / "frames.json"));
    index["frames"][1]["bodies"][1]["orientation"] = {0, 0, 1};
    std::ofstream(dir / "frames.json") << index.dump();
    try {
        readFrameIndex(dir.path().string());
        FAIL() << "a pose of three numbers was read";
    } catch (const IoError& e) {
        EXPECT_NE(std::string(e.what()).find("frames[1].bodies[1].orientation"), std::string::npos)
            << e.what();
    }
}

TEST(FrameWriter, ImpossibleDirectoryThrowsIoErrorNamingIt) {
    TempDir dir;
    test::writeText(dir / "file", "x");
    const std::string path = dir / "file/frames";
    try {
        FrameWriter writer(path, FrameFormat::Vtu);
        FAIL() << "expected IoError";
    } catch (const IoError& e) {
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
    EXPECT_THROW(FrameWriter(dir / "file", FrameFormat::Csv), IoError);
}

TEST(FrameWriter, NegativeFrameIndexIsRejected) {
    TempDir dir;
    FrameWriter writer(dir.path().string(), FrameFormat::Csv);
    EXPECT_THROW(writer.write(-1, 0.0, HostParticles{}), std::invalid_argument);
}

}  // namespace
}  // namespace weir
