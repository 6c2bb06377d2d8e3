// Tests for writeCsv: header, round trips through readCsv, no particles.
#include "io/csv_writer.h"

#include <gtest/gtest.h>

#include <cmath>

#include "io/field_registry.h"
#include "io/frame_reader.h"
#include "io/io_test_support.h"

namespace weir {
namespace {

using test::TempDir;

TEST(CsvWriter, WritesHeaderThenShortestRoundTripRows) {
    TempDir dir;
    HostParticles particles;
    particles.push({0.5, -1, 1e-3}, {0, 2, 3});
    particles.rho[0] = Real(1000.25);
    particles.p[0] = Real(0.1);
    writeCsv(dir / "f.csv", particles);
    EXPECT_EQ(test::fileText(dir / "f.csv"),
              "x,y,z,vx,vy,vz,density,pressure,id\n0.5,-1,0.001,0,2,3,1000.25,0.1,0\n");
}

TEST(CsvWriter, RoundTripsExactly) {
    TempDir dir;
    HostParticles particles = test::randomParticles(2000, 3);
    test::addSpecialValues(particles);
    writeCsv(dir / "f.csv", particles);
    HostParticles read = readCsv(dir / "f.csv");
    ASSERT_EQ(read.size(), particles.size());
    // Shortest round-trip text reads back to the very same Real (well within 1e-7 relative).
    const auto expected = particleColumns(particles);
    const auto actual = particleColumns(read);
    for (std::size_t c = 0; c < expected.size(); ++c) {
        for (std::size_t i = 0; i < particles.size(); ++i) {
            const Real e = (*expected[c])[i];
            const Real a = (*actual[c])[i];
            if (std::isnan(e)) {
                EXPECT_TRUE(std::isnan(a));
            } else {
                EXPECT_EQ(a, e) << "column " << c << " row " << i;
                EXPECT_EQ(std::signbit(a), std::signbit(e));
            }
        }
    }
}

TEST(CsvWriter, ZeroParticlesWriteOnlyTheHeader) {
    TempDir dir;
    writeCsv(dir / "empty.csv", HostParticles{});
    EXPECT_EQ(test::fileText(dir / "empty.csv"), "x,y,z,vx,vy,vz,density,pressure,id\n");
    EXPECT_EQ(readCsv(dir / "empty.csv").size(), 0u);
}

}  // namespace
}  // namespace weir
