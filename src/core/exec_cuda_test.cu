// On a GPU: CUB's reductions land in device memory and replay inside a CUDA graph, so an
// iterative solver can test convergence with no host round trip.
#include <gtest/gtest.h>

#include <vector>

#include "core/backend.h"
#include "core/exec_cuda.cuh"

namespace weir {
namespace {

// data[i] += 1 on the device (a free function: CUDA lambdas cannot live in a test's body).
void addOne(CudaExec& exec, float* data, Index n) {
    exec.forEach(n, [=] __device__(Index i) { data[i] += 1.0f; });
}

// A loop whose body counts its rounds and sets the flag at the round `limit` holds (a solver's
// sweeps until converged, in miniature): the flag and the count cleared first.
void countToLimit(CudaExec& exec, int* count, int* flag, const int* limit, int maxRounds) {
    exec.forEach(1, [=] __device__(Index) {
        *count = 0;
        *flag = 0;
    });
    exec.repeatUntilSet(flag, maxRounds, 0, [&] {
        exec.forEach(1, [=] __device__(Index) {
            if (*flag == 0) {
                *count += 1;
                *flag = *count >= *limit ? 1 : 0;
            }
        });
    });
}

TEST(CudaLoops, RunUntilTheFlagIsSetDirectlyAndInsideAReplayedGraph) {
    if (!cudaDeviceAvailable()) {
        GTEST_SKIP() << "no CUDA device visible: CUDA loops run on GPU machines only";
    }
    CudaExec exec;
    DeviceBuffer<int> state(3);  // count, flag, limit
    int* count = state.data();
    int* flag = count + 1;
    int* limit = count + 2;
    // Run directly: the host polls every second round, the body does nothing once the flag is
    // set, so the count stops at the limit; at most maxRounds rounds if it is never reached.
    exec.writeOne(state, 2, 7);
    countToLimit(exec, count, flag, limit, 100);
    EXPECT_EQ(exec.readOne(state, 0), 7);
    EXPECT_EQ(exec.readOne(state, 1), 1);
    exec.writeOne(state, 2, 1000);
    countToLimit(exec, count, flag, limit, 5);
    EXPECT_EQ(exec.readOne(state, 0), 5);
    EXPECT_EQ(exec.readOne(state, 1), 0);

    // Captured: nothing runs; each replay loops on the device until the flag, whatever the limit
    // is when it runs (the number of rounds is decided on the device, not at capture).
    CudaGraph graph;
    exec.capture(graph, [&] { countToLimit(exec, count, flag, limit, 100); });
    exec.writeOne(state, 2, 13);
    exec.launch(graph);
    exec.synchronize();
    EXPECT_EQ(exec.readOne(state, 0), 13);
    EXPECT_EQ(exec.readOne(state, 1), 1);
    exec.writeOne(state, 2, 3);
    exec.launch(graph);
    exec.synchronize();
    EXPECT_EQ(exec.readOne(state, 0), 3);
    // A limit of one: the body runs once (the node's condition starts true at every launch).
    exec.writeOne(state, 2, 1);
    exec.launch(graph);
    exec.synchronize();
    EXPECT_EQ(exec.readOne(state, 0), 1);
}

TEST(CudaReductions, SumAndMaxStayOnTheDeviceAndReplayInAGraph) {
    if (!cudaDeviceAvailable()) {
        GTEST_SKIP() << "no CUDA device visible: CUDA reductions run on GPU machines only";
    }
    CudaExec exec;
    const Index n = 1 << 20;
    std::vector<float> host(static_cast<std::size_t>(n));
    for (Index i = 0; i < n; ++i) {
        host[std::size_t(i)] = float(i % 5);
    }
    // Integers with every partial sum under 2^24: exact in float whatever the order.
    double expected = 0;
    for (float v : host) {
        expected += v;
    }
    DeviceBuffer<float> values, results(2);
    exec.upload(values, host.data(), host.size());
    exec.sum(values.data(), n, results.data());
    exec.max(values.data(), n, results.data() + 1);
    EXPECT_EQ(double(exec.readOne(results, 0)), expected);
    EXPECT_EQ(exec.readOne(results, 1), 4.0f);

    // Captured, nothing runs; replayed, the device sees the values as they are then.
    float* data = values.data();
    float* out = results.data();
    CudaGraph graph;
    exec.capture(graph, [&] {
        addOne(exec, data, n);
        exec.sum(data, n, out);
        exec.max(data, n, out + 1);
    });
    exec.launch(graph);
    exec.launch(graph);
    exec.synchronize();
    EXPECT_EQ(double(exec.readOne(results, 0)), expected + 2.0 * n);
    EXPECT_EQ(exec.readOne(results, 1), 6.0f);
}

}  // namespace
}  // namespace weir
