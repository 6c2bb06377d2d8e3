// Tests for writeFileAtomically: replacement, and no trace of a failed write.
#include "io/atomic_file.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>

#include "io/io_test_support.h"

namespace weir {
namespace {

using test::fileText;
using test::TempDir;

TEST(AtomicFile, WritesAndReplaces) {
    TempDir dir;
    const std::string path = dir / "out.txt";
    writeFileAtomically(path, [](std::ostream& out) { out << "first"; });
    EXPECT_EQ(fileText(path), "first");
    writeFileAtomically(path, [](std::ostream& out) { out << "second"; });
    EXPECT_EQ(fileText(path), "second");
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"out.txt"});
}

TEST(AtomicFile, ThrowingBodyKeepsOldFileAndLeavesNoTemporary) {
    TempDir dir;
    const std::string path = dir / "out.txt";
    test::writeText(path, "old");
    const auto failingBody = [](std::ostream& out) {
        out << "partial";
        throw std::runtime_error("body failed");
    };
    EXPECT_THROW(writeFileAtomically(path, failingBody), std::runtime_error);
    EXPECT_EQ(fileText(path), "old");
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"out.txt"});
}

TEST(AtomicFile, MissingDirectoryThrowsIoErrorWithPathAndReason) {
    TempDir dir;
    const std::string path = dir / "missing/out.txt";
    try {
        writeFileAtomically(path, [](std::ostream& out) { out << "x"; });
        FAIL() << "expected IoError";
    } catch (const IoError& e) {
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("No such file or directory"), std::string::npos)
            << e.what();
    }
}

TEST(AtomicFile, FailedRenameThrowsIoErrorAndRemovesTemporary) {
    TempDir dir;
    const std::string path = dir / "target";
    std::filesystem::create_directories(dir / "target/inside");  // a directory is in the way
    try {
        writeFileAtomically(path, [](std::ostream& out) { out << "x"; });
        FAIL() << "expected IoError";
    } catch (const IoError& e) {
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"target"});
}

// The pid of a process that has ended (a child, reaped).
pid_t endedProcess() {
    const pid_t child = ::fork();
    if (child == 0) {
        ::_exit(0);
    }
    int status = 0;
    ::waitpid(child, &status, 0);
    return child;
}

TEST(AtomicFile, StaleTemporariesOfEndedProcessesAreRemovedOthersKept) {
    TempDir dir;
    const std::string dead = std::to_string(endedProcess());
    const std::string alive = std::to_string(::getpid());
    for (const std::string& name : std::vector<std::string>{
             "frame_00003.vtu.tmp." + dead + ".0", "frames.json.tmp." + dead + ".7",
             "video.tmp." + dead + ".mp4", "frame_00004.vtu.tmp." + alive + ".1", "frame_00001.vtu",
             "notes.tmp.txt"}) {
        test::writeText(dir / name, "x");
    }
    std::vector<std::string> removed = removeStaleTemporaries(dir.path().string());
    std::sort(removed.begin(), removed.end());
    EXPECT_EQ(removed, (std::vector<std::string>{"frame_00003.vtu.tmp." + dead + ".0",
                                                 "frames.json.tmp." + dead + ".7",
                                                 "video.tmp." + dead + ".mp4"}));
    EXPECT_EQ(dir.entries(),
              (std::vector<std::string>{"frame_00001.vtu", "frame_00004.vtu.tmp." + alive + ".1",
                                        "notes.tmp.txt"}));
    EXPECT_TRUE(removeStaleTemporaries(dir / "missing").empty());
}

}  // namespace
}  // namespace weir
