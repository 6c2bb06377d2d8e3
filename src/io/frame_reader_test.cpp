// Tests for the frame readers on damaged input: every failure is an IoError naming the file.
#include "io/frame_reader.h"

#include <gtest/gtest.h>

#include "io/csv_writer.h"
#include "io/io_test_support.h"
#include "io/ply_writer.h"
#include "io/vtu_writer.h"

namespace weir {
namespace {

using test::TempDir;

// Expects read(path) to throw an IoError whose message names path and contains `detail`.
template <class Read>
void expectIoError(Read read, const std::string& path, const std::string& detail) {
    try {
        read(path);
        ADD_FAILURE() << "no IoError for " << path;
    } catch (const IoError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find(path), std::string::npos) << message;
        EXPECT_NE(message.find(detail), std::string::npos) << message;
    }
}

// Rewrites `from` cut to every length shorter than the complete file (the final newline is
// not required) and expects read to reject each.
template <class Read>
void expectEveryTruncationRejected(Read read, const std::string& from, const std::string& to) {
    const std::string text = test::fileText(from);
    for (std::size_t length = 0; length + 1 < text.size(); ++length) {
        test::writeText(to, text.substr(0, length));
        SCOPED_TRACE("truncated to " + std::to_string(length) + " of " +
                     std::to_string(text.size()) + " bytes");
        expectIoError(read, to, "");
        if (::testing::Test::HasFailure()) {
            return;
        }
    }
}

const auto readVtuOnly = [](const std::string& path) { return readVtu(path); };

TEST(FrameReader, MissingFileNamesPathAndReason) {
    TempDir dir;
    expectIoError(readVtuOnly, dir / "none.vtu", "No such file or directory");
    expectIoError(readPly, dir / "none.ply", "No such file or directory");
    expectIoError(readCsv, dir / "none.csv", "No such file or directory");
}

TEST(FrameReader, TruncatedVtuThrowsIoErrorNamingTheFile) {
    TempDir dir;
    writeVtu(dir / "f.vtu", test::randomParticles(4), 1.0);
    expectIoError(readVtuOnly,
                  (test::writeText(dir / "cut.vtu", test::fileText(dir / "f.vtu").substr(0, 900)),
                   dir / "cut.vtu"),
                  "truncated");
    expectEveryTruncationRejected(readVtuOnly, dir / "f.vtu", dir / "cut.vtu");
}

TEST(FrameReader, VtuWithOtherHeaderTypeOrMissingArrayIsRejected) {
    TempDir dir;
    writeVtu(dir / "f.vtu", test::randomParticles(4), 1.0);
    std::string text = test::fileText(dir / "f.vtu");
    std::string uint32 = text;
    uint32.replace(uint32.find("UInt64"), 6, "UInt32");
    test::writeText(dir / "bad.vtu", uint32);
    expectIoError(readVtuOnly, dir / "bad.vtu", "header_type");
    std::string renamed = text;
    renamed.replace(renamed.find("Name=\"density\""), 14, "Name=\"densitx\"");
    test::writeText(dir / "bad.vtu", renamed);
    expectIoError(readVtuOnly, dir / "bad.vtu", "no DataArray 'density'");
    test::writeText(dir / "bad.vtu", "not xml at all");
    expectIoError(readVtuOnly, dir / "bad.vtu", "AppendedData");
}

TEST(FrameReader, TruncatedOrForeignPlyIsRejected) {
    TempDir dir;
    writePly(dir / "f.ply", test::randomParticles(4));
    expectEveryTruncationRejected(readPly, dir / "f.ply", dir / "cut.ply");
    std::string ascii = test::fileText(dir / "f.ply");
    ascii.replace(ascii.find("binary_little_endian"), 20, "ascii");
    test::writeText(dir / "bad.ply", ascii);
    expectIoError(readPly, dir / "bad.ply", "binary_little_endian");
    test::writeText(dir / "bad.ply", "solid cube\nend_header\n");
    expectIoError(readPly, dir / "bad.ply", "'ply'");
}

TEST(FrameReader, MalformedCsvNamesTheLine) {
    TempDir dir;
    const std::string header = "x,y,z,vx,vy,vz,density,pressure\n";
    test::writeText(dir / "bad.csv", header + "1,2,3,4,5,6,7,8\n1,2,3,4,5,6,seven,8\n");
    expectIoError(readCsv, dir / "bad.csv", "line 3, column 'density': 'seven' is not a number");
    test::writeText(dir / "bad.csv", header + "1,2,3\n");
    expectIoError(readCsv, dir / "bad.csv", "line 2 has 3 values, expected 8");
    test::writeText(dir / "bad.csv", "a,b\n");
    expectIoError(readCsv, dir / "bad.csv", "header");
    test::writeText(dir / "bad.csv", header + "1,2,3,4,5,6,7,8");
    expectIoError(readCsv, dir / "bad.csv", "truncated");
}

}  // namespace
}  // namespace weir
