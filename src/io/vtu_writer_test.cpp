// Tests for writeVtu: bit-exact round trips through readVtu, the header ParaView reads, no points.
#include "io/vtu_writer.h"

#include <gtest/gtest.h>

#include "io/frame_reader.h"
#include "io/io_test_support.h"

namespace weir {
namespace {

using test::TempDir;

TEST(VtuWriter, RoundTripsBitForBitWithTime) {
    TempDir dir;
    HostParticles particles = test::randomParticles(5000);
    test::addSpecialValues(particles);
    const double time = 0.1 + 0.2;  // not a short decimal
    writeVtu(dir / "f.vtu", particles, time);
    double readTime = 0;
    const HostParticles read = readVtu(dir / "f.vtu", &readTime);
    test::expectSameBits(particles, read);
    EXPECT_EQ(readTime, time);
    EXPECT_EQ(readVtuTime(dir / "f.vtu"), time);
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"f.vtu"});
}

TEST(VtuWriter, ZeroParticlesMakeAValidFile) {
    TempDir dir;
    writeVtu(dir / "empty.vtu", HostParticles{}, 2.5);
    double time = 0;
    EXPECT_EQ(readVtu(dir / "empty.vtu", &time).size(), 0u);
    EXPECT_EQ(time, 2.5);
    const std::string text = test::fileText(dir / "empty.vtu");
    EXPECT_NE(text.find("NumberOfPoints=\"0\" NumberOfCells=\"0\""), std::string::npos);
}

TEST(VtuWriter, HeaderDescribesPointsFieldsAndVertexCells) {
    TempDir dir;
    writeVtu(dir / "f.vtu", test::randomParticles(3), 0.0);
    const std::string text = test::fileText(dir / "f.vtu");
    const std::string real = sizeof(Real) == 8 ? "Float64" : "Float32";
    for (const std::string& expected : std::vector<std::string>{
             std::string("<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" "
                         "byte_order=\"LittleEndian\" header_type=\"UInt64\">"),
             "<DataArray type=\"Float64\" Name=\"TimeValue\" NumberOfTuples=\"1\"",
             "<Piece NumberOfPoints=\"3\" NumberOfCells=\"3\">",
             "<DataArray type=\"" + real + "\" Name=\"velocity\" NumberOfComponents=\"3\"",
             "<DataArray type=\"" + real + "\" Name=\"density\" format",
             "<DataArray type=\"" + real + "\" Name=\"pressure\" format",
             "<DataArray type=\"" + real + "\" Name=\"Points\" NumberOfComponents=\"3\"",
             "<DataArray type=\"Int32\" Name=\"connectivity\"",
             "<DataArray type=\"Int32\" Name=\"offsets\"",
             "<DataArray type=\"UInt8\" Name=\"types\"", "<AppendedData encoding=\"raw\">"}) {
        EXPECT_NE(text.find(expected), std::string::npos) << expected;
    }
    // The last block is the cell types: its byte count (3) then three VTK_VERTEX (1) bytes.
    const char tail[] = "\x03\0\0\0\0\0\0\0\x01\x01\x01\n  </AppendedData>\n</VTKFile>\n";
    const std::string expectedTail(tail, sizeof(tail) - 1);
    ASSERT_GE(text.size(), expectedTail.size());
    EXPECT_EQ(text.substr(text.size() - expectedTail.size()), expectedTail);
}

}  // namespace
}  // namespace weir
