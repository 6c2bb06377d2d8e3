// `weir run`'s frame output (issue 17): frames written on a background thread are the same files
// as frames written in between steps (WEIR_FRAME_OUTPUT=foreground); a run stopped by Ctrl-C or
// by the stop flag keeps every frame handed over with a frames.json that lists exactly them; a
// write error ends the run with the error and exit 1, whichever thread wrote.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "cli/cli_test_support.h"
#include "cli/commands.h"
#include "cli/interrupt.h"
#include "io/frame_index.h"

namespace weir {
namespace {

using namespace cli_testing;

// kTinyDrawScene for 100 simulated seconds (3000 frames): a run that is still going when a test
// stops it.
constexpr const char* kLongTinyScene = R"({
    "name": "long_tiny",
    "container": {"min": [0, 0, 0], "max": [0.3, 0.2, 0.08]},
    "blocks": [{"min": [0, 0, 0], "max": [0.12, 0.12, 0.08]}],
    "particles": {"spacing": 0.02},
    "time": {"duration": 100, "frameRate": 30}
})";

// The names and bytes of every file in dir.
std::map<std::string, std::string> filesIn(const fs::path& dir) {
    std::map<std::string, std::string> files;
    for (const auto& entry : fs::directory_iterator(dir)) {
        files[entry.path().filename().string()] = fileText(entry.path());
    }
    return files;
}

// frames.json lists exactly the frame files in dir, numbered 0..count-1, each one readable; no
// temporaries are left. Returns the count.
std::size_t expectConsistentRun(const fs::path& dir) {
    const nlohmann::json index = nlohmann::json::parse(fileText(dir / "frames.json"));
    const std::size_t count = index["frames"].size();
    EXPECT_EQ(index["count"], count);
    std::size_t frameFiles = 0;
    for (const auto& entry : fs::directory_iterator(dir)) {
        const std::string name = entry.path().filename().string();
        EXPECT_EQ(name.find(".tmp."), std::string::npos) << name;
        frameFiles += name.rfind("frame_", 0) == 0 ? 1 : 0;
    }
    EXPECT_EQ(frameFiles, count);
    for (std::size_t k = 0; k < count; ++k) {
        EXPECT_EQ(index["frames"][k]["index"], k);
        const fs::path file = dir / index["frames"][k]["file"].get<std::string>();
        EXPECT_NO_THROW(EXPECT_EQ(readFrameFile(file.string()).size(), 144u)) << file;
    }
    return count;
}

TEST_F(Cli, BackgroundFramesAreTheForegroundsByteForByte) {
    writeFile("tiny.json", kTinyDrawScene);
    for (const std::string format : {"vtu", "ply", "csv"}) {
        SCOPED_TRACE(format);
        const std::string run = "run tiny.json --backend cpu --quiet --frames 6 --format " + format;
        const RunResult background = weir(run + " --out bg_" + format);
        ASSERT_EQ(background.exitCode, 0) << background.output;
        const RunResult foreground = shell("WEIR_FRAME_OUTPUT=foreground " + quoted(WEIR_BINARY) +
                                           " " + run + " --out fg_" + format);
        ASSERT_EQ(foreground.exitCode, 0) << foreground.output;
        const auto written = filesIn(dir_ / ("bg_" + format));
        EXPECT_EQ(written.size(), format == "vtu" ? 9u : 8u);
        EXPECT_TRUE(written == filesIn(dir_ / ("fg_" + format)));
    }
}

TEST_F(Cli, FrameOutputOffWritesNoFrames) {
    writeFile("tiny.json", kTinyDrawScene);
    const RunResult run = shell("WEIR_FRAME_OUTPUT=off " + quoted(WEIR_BINARY) +
                                " run tiny.json --backend cpu --quiet --frames 3 --out off");
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_TRUE(contains(run.output, "frame output off"));
    EXPECT_FALSE(fs::exists(dir_ / "off" / "frames.json"));
    const RunResult bad = shell("WEIR_FRAME_OUTPUT=sometimes " + quoted(WEIR_BINARY) +
                                " run tiny.json --backend cpu --quiet --frames 1 --out bad");
    EXPECT_EQ(bad.exitCode, 2) << bad.output;
    EXPECT_TRUE(contains(bad.output, "WEIR_FRAME_OUTPUT=\"sometimes\""));
}

TEST_F(Cli, CtrlCKeepsEveryFrameHandedOverAndAConsistentIndex) {
    writeFile("long.json", kLongTinyScene);
    const fs::path out = dir_ / "long";
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        // The child: weir run in the test directory, its output to a file.
        if (::chdir(dir_.c_str()) != 0) {
            ::_exit(126);
        }
        const std::string log = (dir_ / "log.txt").string();
        if (!std::freopen(log.c_str(), "w", stderr) || !std::freopen(log.c_str(), "a", stdout)) {
            ::_exit(126);
        }
        ::setenv("OMP_WAIT_POLICY", "passive", 1);
        ::execl(WEIR_BINARY, WEIR_BINARY, "run", "long.json", "--backend", "cpu", "--quiet",
                "--out", "long", static_cast<char*>(nullptr));
        ::_exit(127);
    }
    // Once frames.json lists 3 frames (the run has thousands to go), Ctrl-C.
    int status = 0;
    bool exited = false;
    for (;;) {
        if (::waitpid(child, &status, WNOHANG) == child) {
            exited = true;
            break;
        }
        std::error_code ec;
        if (fs::exists(out / "frames.json", ec)) {
            try {
                if (nlohmann::json::parse(fileText(out / "frames.json"))["count"] >= 3) {
                    break;
                }
            } catch (const std::exception&) {
                // never a partial file (atomic renames), but be safe: look again
            }
        }
        ::usleep(20'000);
    }
    ASSERT_FALSE(exited) << "weir ended before it was stopped:\n" << fileText(dir_ / "log.txt");
    ASSERT_EQ(::kill(child, SIGINT), 0);
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    const std::string log = fileText(dir_ / "log.txt");
    ASSERT_TRUE(WIFEXITED(status)) << log;
    EXPECT_EQ(WEXITSTATUS(status), 128 + SIGINT) << log;
    EXPECT_TRUE(contains(log, "stopped by Ctrl-C (SIGINT)"));
    EXPECT_TRUE(contains(log, "complete and kept"));
    const std::size_t kept = expectConsistentRun(out);
    EXPECT_GE(kept, 3u);
    EXPECT_LT(kept, 3001u);
    EXPECT_TRUE(contains(log, "frames 0.." + std::to_string(kept - 1) + " in long/ are"));
}

// Asks the run to stop (as Ctrl-C does) once frame `at` is handed over.
class StopAt : public RunObserver {
   public:
    explicit StopAt(std::int64_t at) : at_(at) {}
    void start(const Scene&, const SetupReport&, const std::string&) override {}
    void frame(std::int64_t index, double, const HostParticles&) override {
        if (index == at_) {
            requestStop();
        }
    }

   private:
    std::int64_t at_;
};

TEST_F(Cli, StopFlagEndsTheRunAfterTheFramesHandedOver) {
    for (const char* mode : {"background", "foreground"}) {
        SCOPED_TRACE(mode);
        ::setenv("WEIR_FRAME_OUTPUT", mode, 1);
        RunOptions options;
        options.scene = path("tiny.json");
        writeFile("tiny.json", kTinyDrawScene);
        options.backend = "cpu";
        options.quiet = true;
        options.outDir = path(std::string("stop_") + mode);
        StopAt stop(4);
        EXPECT_EQ(runCommand(options, &stop), 128 + SIGINT);
        ::unsetenv("WEIR_FRAME_OUTPUT");
        EXPECT_EQ(expectConsistentRun(options.outDir), 5u);  // frames 0..4
        EXPECT_FALSE(stopRequested());  // a later run in this process starts unasked
    }
}

TEST_F(Cli, WriteErrorEndsTheRunWithItsMessageInEitherMode) {
    writeFile("tiny.json", kTinyDrawScene);
    for (const char* mode : {"background", "foreground"}) {
        SCOPED_TRACE(mode);
        const fs::path out = dir_ / (std::string("err_") + mode);
        // A directory where frame 2's file goes: its rename fails, also for root.
        fs::create_directories(out / "frame_00002.vtu");
        const RunResult run =
            shell(std::string("WEIR_FRAME_OUTPUT=") + mode + " " + quoted(WEIR_BINARY) +
                  " run tiny.json --backend cpu --quiet --frames 8 --overwrite "
                  "--out " +
                  out.filename().string());
        EXPECT_EQ(run.exitCode, 1) << run.output;
        EXPECT_TRUE(contains(run.output, "weir: error: cannot write '" + out.filename().string() +
                                             "/frame_00002.vtu': cannot rename temporary"));
        fs::remove(out / "frame_00002.vtu");
        EXPECT_EQ(expectConsistentRun(out), 2u);  // frames 0 and 1, listed and complete
    }
}

}  // namespace
}  // namespace weir
