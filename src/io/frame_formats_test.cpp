// The frame format table: every entry is a complete format (names unique, help and how to open
// it given, writer and reader agree), and the parser, FrameWriter and readFrameFile all go
// through it, so a new entry needs nothing else.
#include "io/frame_formats.h"

#include <gtest/gtest.h>

#include <set>

#include "io/frame_index.h"
#include "io/frame_writer.h"
#include "io/io_test_support.h"
#include "io/optional_formats.h"

namespace weir {
namespace {

using test::TempDir;

TEST(FrameFormats, EveryEntryIsCompleteAndNamedOnce) {
    std::set<std::string> names;
    for (const FrameFormatEntry& entry : frameFormatTable()) {
        SCOPED_TRACE(entry.name);
        EXPECT_TRUE(names.insert(entry.name).second) << "named twice";
        EXPECT_GT(std::string(entry.help).size(), 10u);
        EXPECT_NE(std::string(entry.openHint).find("BASE"), std::string::npos);
        ASSERT_NE(entry.write, nullptr);
        ASSERT_NE(entry.read, nullptr);
        EXPECT_EQ(parseFrameFormat(entry.name).name(), std::string(entry.name));
        EXPECT_NE(frameFormatHelp().find(entry.name), std::string::npos);
    }
    EXPECT_EQ(names.size(), frameFormatNames().size());
    EXPECT_EQ(frameFormatList(), openVdbBuilt() ? "vtu, ply, csv, vdb" : "vtu, ply, csv");
    EXPECT_EQ(std::string(frameFormatTable().front().name), "vtu");  // the default first
}

TEST(FrameFormats, EveryEntryRoundTripsThroughFrameWriterAndReadFrameFile) {
    const HostParticles particles = test::randomParticles(17, 3);
    for (const std::string& name : frameFormatNames()) {
        SCOPED_TRACE(name);
        TempDir dir;
        const FrameFormat format = parseFrameFormat(name);
        FrameWriter writer(dir.path().string(), format);
        writer.write(2, 0.25, particles);
        EXPECT_EQ(frameFormatOfFile(writer.framePath(2)), format);
        const HostParticles back = readFrameFile(writer.framePath(2));
        ASSERT_EQ(back.size(), particles.size());
        // Exact but for vdb, whose points are stored as offsets in their voxel (float).
        const double tolerance = name == "vdb" ? 1e-6 * 1e3 : 0;
        for (std::size_t i = 0; i < particles.size(); ++i) {
            ASSERT_NEAR(back.x[i], particles.x[i], tolerance) << i;
            ASSERT_EQ(back.p[i], particles.p[i]) << i;
        }
        EXPECT_EQ(std::filesystem::exists(dir / "frame.pvd"), format.entry().pvdSeries);
        const std::vector<FrameEntry> frames = readFrameIndex(dir.path().string());
        ASSERT_EQ(frames.size(), 1u);
        EXPECT_EQ(frames[0].time, 0.25);
    }
}

TEST(FrameFormats, AFormatThisBuildLacksSaysWhy) {
    if (openVdbBuilt()) {
        EXPECT_EQ(missingFormatReason("vdb"), "");
        EXPECT_EQ(parseFrameFormat("vdb").name(), std::string("vdb"));
        return;
    }
    try {
        parseFrameFormat("vdb");
        FAIL() << "expected std::invalid_argument";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("this build has no OpenVDB"), std::string::npos)
            << e.what();
    }
    try {
        frameFormatOfFile("/some/frame_00001.vdb");
        FAIL() << "expected IoError";
    } catch (const IoError& e) {
        EXPECT_NE(std::string(e.what()).find("'/some/frame_00001.vdb': this build has no OpenVDB"),
                  std::string::npos)
            << e.what();
    }
}

TEST(FrameFormats, UnknownExtensionsNameTheFileAndTheAllowed) {
    try {
        frameFormatOfFile("/some/frame_00001.xyz");
        FAIL() << "expected IoError";
    } catch (const IoError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("/some/frame_00001.xyz"), std::string::npos) << what;
        EXPECT_NE(what.find(".vtu, .ply, .csv"), std::string::npos) << what;
    }
}

}  // namespace
}  // namespace weir
