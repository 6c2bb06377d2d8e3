// Tests for the frame readers on damaged input: every failure is an IoError naming the file.
#include "io/frame_reader.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>

#include "io/csv_writer.h"
#include "io/io_test_support.h"
#include "io/ply_writer.h"
#include "io/vtu_writer.h"

namespace weir {
namespace {

using test::TempDir;

using test::expectIoError;

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

TEST(FrameReader, CountsPastTheFileAreRefusedBeforeAllocating) {
    TempDir dir;
    writeVtu(dir / "f.vtu", test::randomParticles(4), 1.0);
    std::string text = test::fileText(dir / "f.vtu");
    text.replace(text.find("NumberOfPoints=\"4\""), 18, "NumberOfPoints=\"4611686018427387904\"");
    test::writeText(dir / "many.vtu", text);
    expectIoError(readVtuOnly, dir / "many.vtu", "NumberOfPoints=\"4611686018427387904\" is more");
    writePly(dir / "f.ply", test::randomParticles(4));
    text = test::fileText(dir / "f.ply");
    text.replace(text.find("element vertex 4"), 16, "element vertex 4000000000");
    test::writeText(dir / "many.ply", text);
    expectIoError(readPly, dir / "many.ply", "4000000000 vertices");
}

// Expects checkFramePositions to refuse particles with `detail` in the message.
void expectPositionsRefused(const HostParticles& particles, const std::string& detail) {
    try {
        checkFramePositions(particles, "frames/frame_00007.csv");
        ADD_FAILURE() << "accepted: " << detail;
    } catch (const IoError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("frames/frame_00007.csv"), std::string::npos) << message;
        EXPECT_NE(message.find(detail), std::string::npos) << message;
    }
}

TEST(FrameReader, NonFiniteOrAbsurdPositionsAreRefusedWithTheParticleAndValue) {
    HostParticles particles = test::randomParticles(200);  // within 1 m of the origin
    for (auto* axis : {&particles.x, &particles.y, &particles.z}) {
        for (Real& value : *axis) {
            value /= 1000;
        }
    }
    EXPECT_NO_THROW(checkFramePositions(particles, "ok.csv"));
    EXPECT_NO_THROW(checkFramePositions(HostParticles{}, "empty.csv"));
    HostParticles bad = particles;
    bad.y[17] = std::numeric_limits<Real>::quiet_NaN();
    expectPositionsRefused(bad, "particle 17 of 200 has y = nan (positions must be finite");
    bad = particles;
    bad.z[3] = -std::numeric_limits<Real>::infinity();
    expectPositionsRefused(bad, "particle 3 of 200 has z = -inf");
    bad = particles;
    bad.x[150] = Real(3e38);
    expectPositionsRefused(bad, "particle 150 of 200 has x = 3e+38");
    // Past 1e6 times the plausible extent (about 1 m here) but under the absolute bound.
    bad = particles;
    bad.x[5] = Real(5e7);
    expectPositionsRefused(bad, "particle 5 of 200 has x = 5e+07 (more than 1e6 times");
    // Every particle far away: the absolute bound.
    bad = particles;
    std::fill(bad.x.begin(), bad.x.end(), Real(2e9));
    expectPositionsRefused(bad, "particle 0 of 200 has x = 2e+09 (positions must lie within 1e+09");
    // A small fluid 1 km from the origin is fine.
    bad = particles;
    for (Real& x : bad.x) {
        x += 1000;
    }
    EXPECT_NO_THROW(checkFramePositions(bad, "far.csv"));
}

}  // namespace
}  // namespace weir
