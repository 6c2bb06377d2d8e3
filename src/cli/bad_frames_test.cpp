// `weir render` and `weir mesh` on frames whose positions are NaN, infinite or absurdly far: both
// refuse the frame (exit 1) naming the file, the particle, the field and the value, instead of
// drawing only the legend or blaming the particle spacing.
#include <gtest/gtest.h>

#include <string>

#include "cli/cli_test_support.h"

namespace weir {
namespace {

using namespace cli_testing;

class BadFrames : public Cli {
   protected:
    // Runs the tiny scene to two CSV frames, then sets particle 5's `column` of frame 1 to
    // `value` (CSV: one header line, then one particle per line).
    void writeFramesWith(int column, const std::string& value) {
        writeFile("tiny.json", kTinyDrawScene);
        const RunResult run =
            weir("run tiny.json --backend cpu --quiet --frames 1 --format csv --out frames");
        ASSERT_EQ(run.exitCode, 0) << run.output;
        const fs::path frame = dir_ / "frames" / "frame_00001.csv";
        std::string text = fileText(frame);
        std::size_t line = 0;
        for (int k = 0; k < 1 + 5; ++k) {
            line = text.find('\n', line) + 1;
        }
        std::size_t start = line;
        for (int c = 0; c < column; ++c) {
            start = text.find(',', start) + 1;
        }
        const std::size_t end = text.find_first_of(",\n", start);
        text.replace(start, end - start, value);
        writeFile("frames/frame_00001.csv", text);
    }
};

TEST_F(BadFrames, MeshRefusesNonFiniteAndAbsurdPositions) {
    const struct {
        int column;
        const char* value;
        const char* expected;
    } cases[] = {{0, "nan", "particle 5 of 144 has x = nan"},
                 {1, "inf", "particle 5 of 144 has y = inf"},
                 {2, "3e38", "particle 5 of 144 has z = 3e+38"},
                 {0, "-2e7", "particle 5 of 144 has x = -2e+07 (more than 1e6 times"}};
    for (const auto& c : cases) {
        SCOPED_TRACE(c.value);
        fs::remove_all(dir_ / "frames");
        writeFramesWith(c.column, c.value);
        for (const std::string args : {"mesh frames --frame 1", "mesh frames"}) {
            const RunResult mesh = weir(args);
            EXPECT_EQ(mesh.exitCode, 1) << args << "\n" << mesh.output;
            EXPECT_TRUE(contains(mesh.output, "frame_00001.csv"));
            EXPECT_TRUE(contains(mesh.output, c.expected));
            EXPECT_EQ(mesh.output.find("error: cannot estimate the particle spacing"),
                      std::string::npos)
                << mesh.output;
        }
    }
}

TEST_F(BadFrames, RenderRefusesNonFiniteAndAbsurdPositions) {
#if !defined(WEIR_HAS_RENDER)
    GTEST_SKIP() << "weir is built without rendering";
#endif
    for (const char* value : {"nan", "-inf", "3e38"}) {
        SCOPED_TRACE(value);
        fs::remove_all(dir_ / "frames");
        writeFramesWith(1, value);
        for (const std::string args : {"render frames --frame 1", "render frames"}) {
            const RunResult render = weir(args);
            EXPECT_EQ(render.exitCode, 1) << args << "\n" << render.output;
            EXPECT_TRUE(contains(render.output, "frame_00001.csv"));
            EXPECT_TRUE(contains(render.output, "particle 5 of 144 has y = "));
            EXPECT_FALSE(fs::exists(dir_ / "frames" / "images" / "frame_00001.png"));
        }
    }
}

}  // namespace
}  // namespace weir
