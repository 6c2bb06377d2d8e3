// Tests for PvdCollection: every frame listed with its time, rewritten per frame.
#include "io/pvd_writer.h"

#include <gtest/gtest.h>

#include "io/io_test_support.h"

namespace weir {
namespace {

using test::TempDir;

TEST(PvdCollection, ListsEveryFileWithItsExactTime) {
    TempDir dir;
    PvdCollection pvd(dir.path().string(), "frame");
    EXPECT_EQ(pvd.path(), dir / "frame.pvd");
    const std::vector<double> times = {0.0, 1.0 / 3.0, 0.1 + 0.2, 12.5};
    for (std::size_t i = 0; i < times.size(); ++i) {
        pvd.add(times[i], "frame_0000" + std::to_string(i) + ".vtu");
        EXPECT_EQ(pvd.size(), i + 1);
    }
    const std::string text = test::fileText(pvd.path());
    EXPECT_EQ(text.rfind("<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\"", 0), 0u);
    EXPECT_NE(text.find("<Collection>"), std::string::npos);
    EXPECT_EQ(text.substr(text.size() - 27), "  </Collection>\n</VTKFile>\n");
    // Each DataSet in order: timestep="<time>" ... file="<name>".
    const auto valueAfter = [&](const std::string& key, std::size_t& at) {
        at = text.find(key + "=\"", at) + key.size() + 2;
        return text.substr(at, text.find('"', at) - at);
    };
    std::size_t at = 0;
    std::size_t i = 0;
    for (; (at = text.find("<DataSet ", at)) != std::string::npos; ++i) {
        ASSERT_LT(i, times.size());
        EXPECT_EQ(std::stod(valueAfter("timestep", at)), times[i]);
        EXPECT_EQ(valueAfter("file", at), "frame_0000" + std::to_string(i) + ".vtu");
    }
    EXPECT_EQ(i, times.size());
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"frame.pvd"});
}

TEST(PvdCollection, ReaddingAFileReplacesItsTimeAndNamesAreEscaped) {
    TempDir dir;
    PvdCollection pvd(dir.path().string(), "run");
    pvd.add(1.0, "a&b.vtu");
    pvd.add(2.0, "a&b.vtu");
    EXPECT_EQ(pvd.size(), 1u);
    const std::string text = test::fileText(dir / "run.pvd");
    EXPECT_NE(text.find("timestep=\"2\" group=\"\" part=\"0\" file=\"a&amp;b.vtu\""),
              std::string::npos)
        << text;
}

}  // namespace
}  // namespace weir
