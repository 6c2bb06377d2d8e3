// Tests for particle ids in every frame format: written as the row number, read back into id
// order (rows another tool re-sorted come back as weir wrote them), bad ids refused, files from
// before ids still read.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <numeric>
#include <string>
#include <vector>

#include "io/csv_writer.h"
#include "io/field_registry.h"
#include "io/frame_reader.h"
#include "io/io_test_support.h"
#include "io/io_util.h"
#include "io/ply_writer.h"
#include "io/vtu_writer.h"

namespace weir {
namespace {

using test::TempDir;

using test::expectIoError;

TEST(ParticleIds, OrderByIdPermutesEveryColumn) {
    HostParticles particles = test::randomParticles(5, 3);
    const HostParticles original = particles;
    // Row k holds the particle whose id is ids[k]; reading puts particle `id` at row `id`.
    const std::vector<std::int64_t> ids = {3, 0, 4, 1, 2};
    orderParticlesById(particles, ids, "f.csv");
    const auto before = particleColumns(original);
    const auto after = particleColumns(particles);
    for (std::size_t c = 0; c < before.size(); ++c) {
        for (std::size_t row = 0; row < ids.size(); ++row) {
            EXPECT_EQ((*after[c])[std::size_t(ids[row])], (*before[c])[row]) << c << " " << row;
        }
    }
}

TEST(ParticleIds, DuplicateOrOutOfRangeIdsAreRefused) {
    HostParticles particles = test::randomParticles(4);
    const auto orderBy = [&](std::vector<std::int64_t> ids) {
        return [&particles, ids](const std::string& path) {
            orderParticlesById(particles, ids, path);
        };
    };
    expectIoError(orderBy({0, 1, 1, 3}), "f.vdb", "particles 1 and 2 have the same id 1");
    expectIoError(orderBy({0, 1, 2, 2147483648LL}), "f.vdb",
                  "particle 3 has id 2147483648 (allowed: 0..2147483647");
    expectIoError(orderBy({0, -1, 2, 3}), "f.vdb", "particle 1 has id -1");
    expectIoError(orderBy({0, 1}), "f.vdb", "2 particle ids for 4 particles");
}

// A run with emitters and sinks: ids with gaps come back sorted, and kept.
TEST(ParticleIds, IdsWithGapsAreSortedAndKept) {
    HostParticles particles = test::randomParticles(4, 7);
    const HostParticles original = particles;
    orderParticlesById(particles, {9, 0, 41, 5}, "f.csv");
    EXPECT_EQ(particles.id, (std::vector<Index>{0, 5, 9, 41}));
    const std::size_t rowOfSorted[4] = {1, 3, 0, 2};
    for (std::size_t k = 0; k < 4; ++k) {
        EXPECT_EQ(particles.x[k], original.x[rowOfSorted[k]]) << k;
        EXPECT_EQ(particles.p[k], original.p[rowOfSorted[k]]) << k;
    }
}

// Frames of such a run carry their ids through every format that writes them.
TEST(ParticleIds, IdsWithGapsRoundTripThroughCsvAndPly) {
    TempDir dir;
    HostParticles particles = test::randomParticles(3, 5);
    particles.id = {2, 17, 300};
    writeCsv(dir / "f.csv", particles);
    writePly(dir / "f.ply", particles);
    for (const HostParticles& back : {readCsv(dir / "f.csv"), readPly(dir / "f.ply")}) {
        EXPECT_EQ(back.id, particles.id);
        EXPECT_EQ(back.x, particles.x);
    }
}

TEST(ParticleIds, CsvRowsResortedByAnotherToolReadBackInIdOrder) {
    TempDir dir;
    HostParticles particles = test::randomParticles(3, 5);
    writeCsv(dir / "f.csv", particles);
    const std::string text = test::fileText(dir / "f.csv");
    std::vector<std::string> lines;
    for (std::size_t at = 0, end; (end = text.find('\n', at)) != std::string::npos; at = end + 1) {
        lines.push_back(text.substr(at, end - at));
    }
    ASSERT_EQ(lines.size(), 4u);
    EXPECT_EQ(lines[0], "x,y,z,vx,vy,vz,density,pressure,id");
    EXPECT_EQ(lines[3].substr(lines[3].rfind(',')), ",2");
    test::writeText(dir / "sorted.csv",
                    lines[0] + "\n" + lines[3] + "\n" + lines[1] + "\n" + lines[2] + "\n");
    test::expectSameBits(particles, readCsv(dir / "sorted.csv"));
    test::writeText(dir / "twice.csv", lines[0] + "\n" + lines[1] + "\n" + lines[1] + "\n");
    expectIoError(readCsv, dir / "twice.csv", "the same id 0");
    test::writeText(dir / "bad.csv",
                    lines[0] + "\n" + lines[1].substr(0, lines[1].rfind(',')) + ",zero\n");
    expectIoError(readCsv, dir / "bad.csv", "line 2, column 'id': 'zero' is not an integer");
}

TEST(ParticleIds, PlyRowsSwappedReadBackInIdOrder) {
    TempDir dir;
    HostParticles particles = test::randomParticles(3, 9);
    writePly(dir / "f.ply", particles);
    std::string bytes = test::fileText(dir / "f.ply");
    const std::size_t rowBytes = 8 * sizeof(Real) + 4;
    const std::size_t body = bytes.size() - 3 * rowBytes;
    std::string swapped = bytes;
    swapped.replace(body, rowBytes, bytes, body + 2 * rowBytes, rowBytes);
    swapped.replace(body + 2 * rowBytes, rowBytes, bytes, body, rowBytes);
    test::writeText(dir / "swapped.ply", swapped);
    test::expectSameBits(particles, readPly(dir / "swapped.ply"));
    // A float id is refused: ids are integers.
    std::string floatId = bytes;
    floatId.replace(floatId.find("property int id"), 15, "property float id");
    test::writeText(dir / "float_id.ply", floatId);
    expectIoError(readPly, dir / "float_id.ply",
                  "vertex property 'id' has type float, expected an integer type");
}

TEST(ParticleIds, VtuHasAnInt32IdArray) {
    TempDir dir;
    HostParticles particles = test::randomParticles(6, 2);
    writeVtu(dir / "f.vtu", particles, 0.5);
    EXPECT_NE(test::fileText(dir / "f.vtu").find("<DataArray type=\"Int32\" Name=\"id\""),
              std::string::npos);
    test::expectSameBits(particles, readVtu(dir / "f.vtu"));
}

// Files as weir wrote them before ids: no id column, property or array.
TEST(ParticleIds, FilesWithoutIdsStillRead) {
    TempDir dir;
    HostParticles particles = test::randomParticles(7, 4);
    // CSV: the old header and rows.
    writeCsv(dir / "f.csv", particles);
    std::string csv;
    const std::string text = test::fileText(dir / "f.csv");
    for (std::size_t at = 0, end; (end = text.find('\n', at)) != std::string::npos; at = end + 1) {
        const std::string line = text.substr(at, end - at);
        csv += line.substr(0, line.rfind(',')) + "\n";
    }
    ASSERT_EQ(csv.substr(0, 32), "x,y,z,vx,vy,vz,density,pressure\n");
    test::writeText(dir / "old.csv", csv);
    test::expectSameBits(particles, readCsv(dir / "old.csv"));
    // PLY: float columns only.
    const std::string type = sizeof(Real) == 8 ? "double" : "float";
    std::string ply = "ply\nformat binary_little_endian 1.0\nelement vertex 7\n";
    for (const std::string& name : particleColumnNames()) {
        ply += "property " + type + " " + name + "\n";
    }
    ply += "end_header\n";
    for (std::size_t i = 0; i < particles.size(); ++i) {
        for (const std::vector<Real>* column : particleColumns(particles)) {
            ply.append(reinterpret_cast<const char*>(&(*column)[i]), sizeof(Real));
        }
    }
    test::writeText(dir / "old.ply", ply);
    test::expectSameBits(particles, readPly(dir / "old.ply"));
    // VTU: the id array's tag taken out of the header.
    writeVtu(dir / "f.vtu", particles, 0.5);
    std::string vtu = test::fileText(dir / "f.vtu");
    const std::size_t tag = vtu.find("<DataArray type=\"Int32\" Name=\"id\"");
    ASSERT_NE(tag, std::string::npos);
    vtu.erase(tag, vtu.find('\n', tag) + 1 - tag);
    test::writeText(dir / "old.vtu", vtu);
    test::expectSameBits(particles, readVtu(dir / "old.vtu"));
}

}  // namespace
}  // namespace weir
