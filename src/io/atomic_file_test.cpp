// Tests for writeFileAtomically: replacement, and no trace of a failed write.
#include "io/atomic_file.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace weir
