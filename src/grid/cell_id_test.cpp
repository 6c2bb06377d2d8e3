// Cell id layout of paper §6.2: round trip, bit positions, range errors.
#include "grid/cell_id.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

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
    EXPECT_NO_THROW(makeGridSpec({0, 0, 0}, {1.024, 1, 1}, 0.001));
    try {
        makeGridSpec({0, 0, 0}, {2.0, 1, 1}, 0.001);
        FAIL() << "expected an error";
    } catch (const SimulationError& e) {
        std::string msg = e.what();
        EXPECT_NE(msg.find("2000 grid cells along x"), std::string::npos) << msg;
        EXPECT_NE(msg.find("1024"), std::string::npos) << msg;
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
