// Cell id layout of paper §6.2 and its 64-bit widening: round trip, bit positions, when the
// wide id is used, range errors.
#include "grid/cell_id.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "core/check.h"

namespace weir {
namespace {

TEST(CellId, RoundTripsEveryAxisValue) {
    std::mt19937 rng(7);
    std::uniform_int_distribution<int> axis(0, kMaxCellsPerAxis - 1);
    for (int n = 0; n < 100000; ++n) {
        int x = axis(rng), y = axis(rng), z = axis(rng);
        CellCoord c = decodeCell(encodeCell(x, y, z));
        ASSERT_EQ(c.x, x);
        ASSERT_EQ(c.y, y);
        ASSERT_EQ(c.z, z);
    }
}

TEST(CellId, LayoutIsTwoUnusedBitsThenYZX) {
    EXPECT_EQ(encodeCell(1, 0, 0), 1u);
    EXPECT_EQ(encodeCell(0, 0, 1), 1u << 10);
    EXPECT_EQ(encodeCell(0, 1, 0), 1u << 20);
    EXPECT_EQ(encodeCell(1023, 1023, 1023), (1u << 30) - 1);  // top two bits stay 0
    // Neighbours along X are consecutive ids: the property the row-wise neighbour loop uses.
    EXPECT_EQ(encodeCell(6, 3, 9), encodeCell(5, 3, 9) + 1);
}

TEST(CellId, WideIdsRoundTripPastTheNarrowRange) {
    std::mt19937 rng(11);
    std::uniform_int_distribution<int> axis(0, kMaxWideCellsPerAxis - 1);
    for (int n = 0; n < 100000; ++n) {
        // Every other sample keeps one axis just past the 32-bit id's 1024.
        int x = axis(rng), y = axis(rng), z = axis(rng);
        if (n % 2 == 1) {
            (n % 3 == 0 ? x : n % 3 == 1 ? y : z) = 1024 + n % 7;
        }
        CellCoord c = decodeCell(encodeCell<WideCellKey>(x, y, z));
        ASSERT_EQ(c.x, x);
        ASSERT_EQ(c.y, y);
        ASSERT_EQ(c.z, z);
    }
    for (int v : {1024, 1025, 4095, kMaxWideCellsPerAxis - 1}) {
        CellCoord c = decodeCell(encodeCell<WideCellKey>(v, v - 1, v - 2));
        EXPECT_EQ(c.x, v);
        EXPECT_EQ(c.y, v - 1);
        EXPECT_EQ(c.z, v - 2);
    }
}

TEST(CellId, WideLayoutIsTheSameOrderAt21BitsPerAxis) {
    EXPECT_EQ(encodeCell<WideCellKey>(1, 0, 0), 1u);
    EXPECT_EQ(encodeCell<WideCellKey>(0, 0, 1), WideCellKey(1) << 21);
    EXPECT_EQ(encodeCell<WideCellKey>(0, 1, 0), WideCellKey(1) << 42);
    const int top = kMaxWideCellsPerAxis - 1;
    EXPECT_EQ(encodeCell<WideCellKey>(top, top, top), (WideCellKey(1) << 63) - 1);  // top bit 0
    EXPECT_EQ(encodeCell<WideCellKey>(1500, 3, 9), encodeCell<WideCellKey>(1499, 3, 9) + 1);
    // Where both hold a cell, both widths order cells alike (Y, then Z, then X): the grid's
    // tables do not depend on the width.
    std::mt19937 rng(13);
    std::uniform_int_distribution<int> axis(0, kMaxCellsPerAxis - 1);
    for (int n = 0; n < 10000; ++n) {
        int a[3] = {axis(rng), axis(rng), axis(rng)}, b[3] = {axis(rng), axis(rng), axis(rng)};
        if (n % 4 == 0) {
            b[1] = a[1];  // equal Y: Z and X decide
        }
        ASSERT_EQ(
            encodeCell(a[0], a[1], a[2]) < encodeCell(b[0], b[1], b[2]),
            encodeCell<WideCellKey>(a[0], a[1], a[2]) < encodeCell<WideCellKey>(b[0], b[1], b[2]));
    }
}

TEST(CellId, WideIdsOnlyPast1024CellsOnSomeAxis) {
    const GridSpec fits = makeGridSpec({0, 0, 0}, {1.024, 1.024, 1.024}, 0.001);
    EXPECT_EQ(fits.dims[0], 1024);
    EXPECT_FALSE(needsWideCellIds(fits));
    EXPECT_EQ(cellIdBytesFor(fits), 4u);
    EXPECT_EQ(cellIdDescription(fits), "32-bit (10 bits per axis)");
    for (int a = 0; a < 3; ++a) {
        Vec3d boxMax(0.1, 0.1, 0.1);
        boxMax[a] = 1.025;
        const GridSpec past = makeGridSpec({0, 0, 0}, boxMax, 0.001);
        EXPECT_EQ(past.dims[a], 1025);
        EXPECT_TRUE(needsWideCellIds(past)) << "axis " << a;
        EXPECT_EQ(cellIdBytesFor(past), 8u);
        EXPECT_EQ(cellIdDescription(past), "64-bit (21 bits per axis)");
    }
}

TEST(CellId, GridSpecSizesAndClamps) {
    GridSpec g = makeGridSpec({0, 0, 0}, {1.0, 0.5, 0.25}, 0.1);
    EXPECT_EQ(g.dims[0], 10);
    EXPECT_EQ(g.dims[1], 5);
    EXPECT_EQ(g.dims[2], 3);
    CellCoord far = g.cellOf(Real(1.0), Real(0.5), Real(0.25));  // on the far walls
    EXPECT_EQ(far.x, 9);
    EXPECT_EQ(far.y, 4);
    EXPECT_EQ(far.z, 2);
    CellCoord before = g.cellOf(Real(-0.5), Real(0.05), Real(0.15));
    EXPECT_EQ(before.x, 0);
    EXPECT_EQ(before.y, 0);
    EXPECT_EQ(before.z, 1);
}

TEST(CellId, TooManyCellsIsAClearError) {
    // By default a grid may have what the 64-bit id holds, 2^21 cells per axis.
    EXPECT_NO_THROW(makeGridSpec({0, 0, 0}, {2.0, 1, 1}, 0.001));
    try {
        makeGridSpec({0, 0, 0}, {3000.0, 1, 1}, 0.001);
        FAIL() << "expected an error";
    } catch (const SimulationError& e) {
        std::string msg = e.what();
        EXPECT_NE(msg.find("3000000 grid cells along x"), std::string::npos) << msg;
        EXPECT_NE(msg.find("2097152 that the 64-bit cell id holds"), std::string::npos) << msg;
    }
    // A caller may still ask for the paper's limit.
    EXPECT_NO_THROW(makeGridSpec({0, 0, 0}, {1.024, 1, 1}, 0.001, kMaxCellsPerAxis));
    try {
        makeGridSpec({0, 0, 0}, {2.0, 1, 1}, 0.001, kMaxCellsPerAxis);
        FAIL() << "expected an error";
    } catch (const SimulationError& e) {
        std::string msg = e.what();
        EXPECT_NE(msg.find("2000 grid cells along x"), std::string::npos) << msg;
        EXPECT_NE(msg.find("1024 that the 32-bit cell id"), std::string::npos) << msg;
    }
    EXPECT_THROW(makeGridSpec({0, 0, 0}, {1, 1, 1}, 0.0), SimulationError);
}

TEST(GridSpec, SliceKeepsTheCellsOfASlab) {
    const GridSpec whole = makeGridSpec({0, 0, 0}, {1.0, 0.5, 0.5}, 0.1);
    const GridSpec slice = sliceOf(whole, 0, 0.25, 0.61);
    EXPECT_EQ(slice.dims[0], 5);  // cells 2..6: [0.2, 0.7)
    EXPECT_NEAR(slice.origin.x, 0.2, 1e-6);
    EXPECT_EQ(slice.dims[1], whole.dims[1]);
    // A point keeps its place: its cell in the slice is its cell in the whole, shifted.
    EXPECT_EQ(slice.cellOf(0.45f, 0.3f, 0.1f).x, whole.cellOf(0.45f, 0.3f, 0.1f).x - 2);
    const GridSpec open = sliceOf(whole, 0, -INFINITY, INFINITY);
    EXPECT_EQ(open.dims[0], whole.dims[0]);
    EXPECT_EQ(sliceOf(whole, 0, 5.0, 6.0).dims[0], 1);  // past the end: the last cell
}

}  // namespace
}  // namespace weir
