// Tests for writePly: the header other tools read, bit-exact round trips through readPly.
#include "io/ply_writer.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>

#include "io/frame_reader.h"
#include "io/io_test_support.h"

namespace weir {
namespace {

using test::TempDir;

TEST(PlyWriter, RoundTripsBitForBit) {
    TempDir dir;
    HostParticles particles = test::randomParticles(5000, 7);
    test::addSpecialValues(particles);
    writePly(dir / "f.ply", particles);
    test::expectSameBits(particles, readPly(dir / "f.ply"));
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"f.ply"});
}

TEST(PlyWriter, WritesHeaderThenRows) {
    TempDir dir;
    writePly(dir / "f.ply", test::randomParticles(2));
    const std::string type = sizeof(Real) == 8 ? "double" : "float";
    std::string header =
        "ply\nformat binary_little_endian 1.0\ncomment weir SPH particles\n"
        "element vertex 2\n";
    for (const char* name : {"x", "y", "z", "vx", "vy", "vz", "density", "pressure"}) {
        header += "property " + type + " " + name + "\n";
    }
    header += "property int id\nend_header\n";
    const std::string text = test::fileText(dir / "f.ply");
    EXPECT_EQ(text.substr(0, header.size()), header);
    EXPECT_EQ(text.size(), header.size() + 2 * (8 * sizeof(Real) + 4));
    // The second row's id, after its eight Reals: 1.
    std::int32_t id = -1;
    std::memcpy(&id, text.data() + text.size() - 4, 4);
    EXPECT_EQ(id, 1);
}

TEST(PlyWriter, ZeroParticles) {
    TempDir dir;
    writePly(dir / "empty.ply", HostParticles{});
    EXPECT_EQ(readPly(dir / "empty.ply").size(), 0u);
    EXPECT_NE(test::fileText(dir / "empty.ply").find("element vertex 0\n"), std::string::npos);
}

}  // namespace
}  // namespace weir
