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
