// The CPU backend's reductions (sums and maxima into the backend's memory) and its loops.
#include <gtest/gtest.h>

#include <limits>
#include <vector>

#include "core/exec_cpu.h"

namespace weir {
namespace {

TEST(CpuReductions, SumAndMaxOfFloatsAndDoubles) {
    CpuExec exec;
    std::vector<float> f(100001);
    std::vector<double> d(f.size());
    for (std::size_t i = 0; i < f.size(); ++i) {
        f[i] = float(i % 17) - 8.0f;  // sums to a known integer; maximum 8 at i = 16, 33, ...
        d[i] = double(f[i]) * 0.5;
    }
    double expected = 0;
    for (float v : f) {
        expected += v;
    }
    float fs = 0, fm = 0;
    double ds = 0, dm = 0;
    exec.sum(f.data(), Index(f.size()), &fs);
    exec.max(f.data(), Index(f.size()), &fm);
    exec.sum(d.data(), Index(d.size()), &ds);
    exec.max(d.data(), Index(d.size()), &dm);
    EXPECT_EQ(double(fs), expected);
    EXPECT_EQ(fm, 8.0f);
    EXPECT_EQ(ds, 0.5 * expected);
    EXPECT_EQ(dm, 4.0);
}

TEST(CpuReductions, EmptyRangesGiveTheIdentity) {
    CpuExec exec;
    float s = 7, m = 7;
    exec.sum(static_cast<const float*>(nullptr), 0, &s);
    exec.max(static_cast<const float*>(nullptr), 0, &m);
    EXPECT_EQ(s, 0.0f);
    EXPECT_EQ(m, std::numeric_limits<float>::lowest());
}

// A solver's loop in miniature: the body sets the flag at its seventh round, and the loop stops
// there; a flag never set stops at maxRounds.
TEST(CpuLoops, RunUntilTheFlagIsSetOrTheRoundsRunOut) {
    CpuExec exec;
    int count = 0, flag = 0, limit = 7;
    auto body = [&] {
        exec.forEach(1, [&](Index) {
            if (flag == 0) {
                ++count;
                flag = count >= limit ? 1 : 0;
            }
        });
    };
    exec.repeatUntilSet(&flag, 100, 2, body);
    EXPECT_EQ(count, 7);
    count = 0;
    flag = 0;
    limit = 1000;
    exec.repeatUntilSet(&flag, 5, 2, body);
    EXPECT_EQ(count, 5);
    EXPECT_EQ(flag, 0);
}

}  // namespace
}  // namespace weir
