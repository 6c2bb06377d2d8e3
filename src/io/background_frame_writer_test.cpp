// Tests for BackgroundFrameWriter: the same files as writing in the foreground, every frame handed
// over written (also when the writer is dropped early), the bound on frames held, write errors
// thrown on the stepping thread.
#include "io/background_frame_writer.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>

#include "io/frame_reader.h"
#include "io/io_test_support.h"

namespace weir {
namespace {

namespace fs = std::filesystem;
using test::TempDir;

// Writes frames 0..count-1 (frame k: 50 + k random particles at time k / 30) through a writer
// with room for `held` frames; each frame is filled in a frame of the pool.
void writeFrames(BackgroundFrameWriter& out, int count) {
    for (int k = 0; k < count; ++k) {
        std::shared_ptr<HostParticles> frame = out.acquire();
        *frame = test::randomParticles(50 + std::size_t(k), unsigned(k + 1));
        out.submit(k, k / 30.0, std::move(frame));
    }
}

// The names and bytes of every file in dir.
std::map<std::string, std::string> filesIn(const fs::path& dir) {
    std::map<std::string, std::string> files;
    for (const auto& entry : fs::directory_iterator(dir)) {
        files[entry.path().filename().string()] = test::fileText(entry.path().string());
    }
    return files;
}

TEST(BackgroundFrameWriter, WritesTheSameBytesAsTheForeground) {
    for (FrameFormat format : {FrameFormat::Vtu, FrameFormat::Ply, FrameFormat::Csv}) {
        SCOPED_TRACE(format.name());
        TempDir dir;
        {
            BackgroundFrameWriter background(
                std::make_unique<FrameWriter>(dir / "background", format), 3);
            BackgroundFrameWriter foreground(
                std::make_unique<FrameWriter>(dir / "foreground", format), 1,
                FrameOutputMode::Foreground);
            writeFrames(background, 7);
            writeFrames(foreground, 7);
            background.finish();
            EXPECT_EQ(background.framesWritten(), 7);
            EXPECT_EQ(background.lastWrittenIndex(), 6);
            EXPECT_EQ(foreground.framesWritten(), 7);
        }
        const auto written = filesIn(dir / "background");
        EXPECT_EQ(written.size(), format == FrameFormat::Vtu ? 9u : 8u);  // + frames.json, .pvd
        EXPECT_TRUE(written == filesIn(dir / "foreground"));
    }
}

TEST(BackgroundFrameWriter, DroppedWriterStillWritesEveryFrameHandedOver) {
    TempDir dir;
    {
        BackgroundFrameWriter out(std::make_unique<FrameWriter>(dir / "out", FrameFormat::Ply), 2);
        writeFrames(out, 5);
        // No finish(): as when a run ends by an exception or a blow-up.
    }
    const auto index = nlohmann::json::parse(test::fileText(dir / "out/frames.json"));
    EXPECT_EQ(index["count"], 5);
    ASSERT_EQ(index["frames"].size(), 5u);
    for (int k = 0; k < 5; ++k) {
        EXPECT_EQ(index["frames"][k]["index"], k);
        EXPECT_EQ(readPly(dir / ("out/" + index["frames"][k]["file"].get<std::string>())).size(),
                  50u + std::size_t(k));
    }
}

TEST(BackgroundFrameWriter, HoldsNoMoreFramesThanItsBound) {
    TempDir dir;
    BackgroundFrameWriter out(std::make_unique<FrameWriter>(dir / "out", FrameFormat::Vtu), 2);
    writeFrames(out, 20);
    out.finish();
    EXPECT_EQ(out.framesWritten(), 20);
    EXPECT_GE(out.peakFrames(), 1);
    EXPECT_LE(out.peakFrames(), 2);
    // Both frames held by the caller: a third would wait forever, so acquire says so instead.
    auto a = out.acquire();
    auto b = out.acquire();
    EXPECT_EQ(out.peakFrames(), 2);
    EXPECT_THROW(out.acquire(), std::logic_error);
    b.reset();
    EXPECT_NO_THROW(out.acquire());
}

TEST(BackgroundFrameWriter, WriteErrorIsThrownOnTheSteppingThreadAndStopsTheWriter) {
    TempDir dir;
    const fs::path folder = dir / "out";
    BackgroundFrameWriter out(std::make_unique<FrameWriter>(folder.string(), FrameFormat::Vtu), 3);
    writeFrames(out, 2);
    out.finish();
    // A directory where frame 2's file goes: its rename fails (also for root, unlike chmod).
    fs::create_directory(folder / "frame_00002.vtu");
    auto frame = out.acquire();
    *frame = test::randomParticles(10);
    out.submit(2, 2 / 30.0, std::move(frame));
    try {
        out.finish();
        FAIL() << "expected IoError";
    } catch (const IoError& e) {
        EXPECT_NE(std::string(e.what()).find("frame_00002.vtu"), std::string::npos) << e.what();
    }
    EXPECT_THROW(out.acquire(), IoError);
    EXPECT_THROW(out.submit(3, 0.1, std::make_shared<HostParticles>()), IoError);
    // frames.json still lists exactly the frames written before the error.
    const auto index = nlohmann::json::parse(test::fileText((folder / "frames.json").string()));
    EXPECT_EQ(index["count"], 2);
    EXPECT_EQ(out.framesWritten(), 2);
}

TEST(BackgroundFrameWriter, FramesThatFitLeaveHalfTheMemory) {
    EXPECT_EQ(framesThatFit(100, 10'000), 3);
    EXPECT_EQ(framesThatFit(100, 500), 2);  // 250 bytes: 2 frames of 100
    EXPECT_EQ(framesThatFit(100, 100), 1);  // never fewer than 1
    EXPECT_EQ(framesThatFit(100, 1'000, 2), 2);
    EXPECT_THROW(BackgroundFrameWriter(
                     std::make_unique<FrameWriter>(TempDir().path().string(), FrameFormat::Csv), 0),
                 std::invalid_argument);
}

TEST(BackgroundFrameWriter, OutputModeComesFromTheEnvironment) {
    const char* saved = std::getenv("WEIR_FRAME_OUTPUT");
    const std::string before = saved != nullptr ? saved : "";
    ::unsetenv("WEIR_FRAME_OUTPUT");
    EXPECT_EQ(frameOutputModeFromEnvironment(), FrameOutputMode::Background);
    ::setenv("WEIR_FRAME_OUTPUT", "foreground", 1);
    EXPECT_EQ(frameOutputModeFromEnvironment(), FrameOutputMode::Foreground);
    ::setenv("WEIR_FRAME_OUTPUT", "off", 1);
    EXPECT_EQ(frameOutputModeFromEnvironment(), FrameOutputMode::Off);
    ::setenv("WEIR_FRAME_OUTPUT", "sometimes", 1);
    EXPECT_THROW(frameOutputModeFromEnvironment(), std::invalid_argument);
    if (saved != nullptr) {
        ::setenv("WEIR_FRAME_OUTPUT", before.c_str(), 1);
    } else {
        ::unsetenv("WEIR_FRAME_OUTPUT");
    }
}

}  // namespace
}  // namespace weir
