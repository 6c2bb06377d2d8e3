// On a GPU: CUB's sort of 64-bit cell ids orders like std::stable_sort, and the grid past 1024
// cells per axis (64-bit ids) gives the CPU grid's order and tables.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "core/backend.h"
#include "core/exec_cpu.h"
#include "core/exec_cuda.cuh"
#include "grid/grid_test_support.h"
#include "grid/neighbour_grid.h"

namespace weir {
namespace {

using testing::Cloud;

template <class T>
std::vector<T> copyToHost(CudaExec& exec, const T* device, std::size_t n) {
    exec.synchronize();
    std::vector<T> host(n);
    if (n > 0) {
        WEIR_CUDA_CHECK(cudaMemcpy(host.data(), device, n * sizeof(T), cudaMemcpyDeviceToHost));
    }
    return host;
}

TEST(CudaRadixSort, WideKeysSortLikeStableSort) {
    if (!cudaDeviceAvailable()) {
        GTEST_SKIP() << "no CUDA device visible: the CUDA sort runs on GPU machines only";
    }
    std::mt19937_64 rng(5);
    const int n = 200000;
    for (int keyBits : {63, 45}) {
        std::vector<WideCellKey> pool(900), keys(n);
        for (WideCellKey& k : pool) {
            k = rng() >> (64 - keyBits);
        }
        std::vector<Index> values(n);
        for (int i = 0; i < n; ++i) {
            keys[i] = pool[rng() % pool.size()];
            values[i] = i;
        }
        CudaExec exec;
        DeviceBuffer<WideCellKey> keysIn, keysOut(n);
        DeviceBuffer<Index> valuesIn, valuesOut(n);
        exec.upload(keysIn, keys.data(), n);
        exec.upload(valuesIn, values.data(), n);
        exec.sortPairs(keysIn.data(), keysOut.data(), valuesIn.data(), valuesOut.data(), n,
                       keyBits);
        const auto sortedKeys = copyToHost(exec, keysOut.data(), n);
        const auto sortedValues = copyToHost(exec, valuesOut.data(), n);
        const auto expected = testing::stableSorted(keys);
        for (int i = 0; i < n; ++i) {
            ASSERT_EQ(sortedKeys[i], expected[i].first) << keyBits << " bits, at " << i;
            ASSERT_EQ(sortedValues[i], expected[i].second) << keyBits << " bits, at " << i;
        }
    }
}

TEST(CudaNeighbourGrid, WideGridMatchesTheCpuGrid) {
    if (!cudaDeviceAvailable()) {
        GTEST_SKIP() << "no CUDA device visible: the CUDA grid runs on GPU machines only";
    }
    for (int longAxis = 0; longAxis < 3; ++longAxis) {
        const Real h = Real(0.002), length = 1250 * h, width = 4 * h;
        Cloud cloud = testing::clumpsAlong(longAxis, length, width, h, 29 + unsigned(longAxis));
        Vec3d boxMax(width, width, width);
        boxMax[longAxis] = length;
        const GridSpec spec = makeGridSpec({0, 0, 0}, boxMax, h);
        const std::vector<Real4> pos = cloud.packed();
        const Index n = Index(pos.size());

        CpuExec cpuExec;
        NeighbourGrid<CpuExec> cpu(spec);
        cpu.build(cpuExec, pos.data(), n);
        CudaExec exec;
        DeviceBuffer<Real4> devicePos;
        exec.upload(devicePos, pos.data(), pos.size());
        NeighbourGrid<CudaExec> gpu(spec);
        ASSERT_EQ(gpu.cellIdBits(), 64);
        gpu.build(exec, devicePos.data(), n);

        // Stable sorts of the same ids: the same order and the same tables, entry for entry.
        const auto& cpuTables = *cpu.keyed<WideCellKey>();
        const auto& gpuTables = *gpu.keyed<WideCellKey>();
        const Index cells = cpu.numCells();
        ASSERT_EQ(gpu.numCells(), cells) << "long axis " << longAxis;
        auto same = [&](const auto* onGpu, const auto* onCpu, std::size_t count, const char* what) {
            const auto fromGpu = copyToHost(exec, onGpu, count);
            for (std::size_t i = 0; i < count; ++i) {
                ASSERT_EQ(fromGpu[i], onCpu[i]) << what << " " << i << ", long axis " << longAxis;
            }
        };
        same(gpu.permutation(), cpu.permutation(), std::size_t(n), "permutation");
        same(gpuTables.cellKeys().data(), cpuTables.cellKeys().data(), cells, "cell id");
        same(gpuTables.cellStart().data(), cpuTables.cellStart().data(), cells, "cell start");
        same(gpuTables.cellCount().data(), cpuTables.cellCount().data(), cells, "cell count");
        same(gpuTables.particleCell().data(), cpuTables.particleCell().data(), std::size_t(n),
             "particle cell");
        same(gpuTables.neighbourTable().data(), cpuTables.neighbourTable().data(),
             std::size_t(cells) * kNeighbourCells, "neighbour entry");
    }
}

}  // namespace
}  // namespace weir
