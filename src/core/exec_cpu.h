// The CPU backend's primitives: parallelFor over OpenMP, radix sort, scan, host buffers.
#pragma once

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <string>
#include <vector>

#include "core/config.h"
#include "core/stage_timer.h"
#include "core/team.h"

namespace weir {

// Host memory of n elements; same interface as DeviceBuffer.
template <class T>
class HostBuffer {
   public:
    HostBuffer() = default;
    explicit HostBuffer(std::size_t n) : data_(n) {}
    void resize(std::size_t n) { data_.resize(n); }  // keeps the contents, as DeviceBuffer's
    std::size_t size() const { return data_.size(); }
    std::size_t capacity() const { return data_.capacity(); }
    T* data() { return data_.data(); }
    const T* data() const { return data_.data(); }
    void swap(HostBuffer& other) noexcept { data_.swap(other.data_); }

   private:
    std::vector<T> data_;
};

class CpuExec {
   public:
    template <class T>
    using Buffer = HostBuffer<T>;
    static constexpr bool isDevice = false;
    struct Graph {};  // the CPU runs steps directly

    // Runs f(i) for i in [0, n) on all cores.
    template <class F>
    void forEach(Index n, F f) const {
#pragma omp parallel for schedule(static)
        for (Index i = 0; i < n; ++i) {
            f(i);
        }
    }

    // Runs f(i, team) for i in [0, n): on the CPU every team is one thread.
    template <int TeamSize, class F>
    void forEachTeam(Index n, F f) const {
        static_assert(TeamSize == 1, "CPU threads work alone");
        forEach(n, [&](Index i) { f(i, Team<1>{}); });
    }

    // Stable sort of (key, value) pairs by the low keyBits bits of the key (LSD radix sort).
    void sortPairs(const CellKey* keysIn, CellKey* keysOut, const Index* valuesIn, Index* valuesOut,
                   Index n, int keyBits);
    void sortPairs(const WideCellKey* keysIn, WideCellKey* keysOut, const Index* valuesIn,
                   Index* valuesOut, Index n, int keyBits);
    // out[i] = in[0] + ... + in[i]; in and out may alias.
    void inclusiveScan(const Index* in, Index* out, Index n);
    void inclusiveScan(const std::int64_t* in, std::int64_t* out, Index n);
    // data[i] = max(data[0], ..., data[i]), in place.
    void inclusiveMaxScan(Index* data, Index n);
    // *out = in[0] + ... + in[n - 1] (0 for n = 0) and *out = max(in[0], ..., in[n - 1]) (the
    // lowest value for n = 0), out in this backend's memory: the device keeps the result, so an
    // iterative solver tests convergence with no host round trip (graph-capturable on CUDA).
    void sum(const float* in, Index n, float* out);
    void sum(const double* in, Index n, double* out);
    void max(const float* in, Index n, float* out);
    void max(const double* in, Index n, double* out);

    template <class T>
    void upload(Buffer<T>& dst, const T* src, std::size_t n) const {
        dst.resize(n);
        std::copy(src, src + n, dst.data());
    }
    template <class T>
    void download(const Buffer<T>& src, T* dst, std::size_t n) const {
        std::copy(src.data(), src.data() + n, dst);
    }
    template <class T>
    void uploadAt(Buffer<T>& dst, std::size_t offset, const T* src, std::size_t n) const {
        std::copy(src, src + n, dst.data() + offset);
    }
    template <class T>
    void downloadFrom(const Buffer<T>& src, std::size_t offset, T* dst, std::size_t n) const {
        std::copy(src.data() + offset, src.data() + offset + n, dst);
    }
    template <class T>
    void uploadAtAsync(Buffer<T>& dst, std::size_t offset, const T* src, std::size_t n) const {
        uploadAt(dst, offset, src, n);
    }
    template <class T>
    void downloadFromAsync(const Buffer<T>& src, std::size_t offset, T* dst, std::size_t n) const {
        downloadFrom(src, offset, dst, n);
    }
    template <class T>
    T readOne(const Buffer<T>& src, std::size_t index) const {
        return src.data()[index];
    }
    template <class T>
    void writeOne(Buffer<T>& dst, std::size_t index, const T& value) const {
        dst.data()[index] = value;
    }
    void synchronize() const {}

    // Runs body() until *flag (set by body's own work) is non-zero, at most maxRounds times.
    // firstCheck: rounds before the flag is first read (the GPU's reads cost a round trip each;
    // here they are free, so every round is checked).
    template <class Body>
    void repeatUntilSet(const int* flag, int maxRounds, int /*firstCheck*/, Body&& body) const {
        for (int round = 0; round < maxRounds; ++round) {
            body();
            if (*flag != 0) {
                return;
            }
        }
    }

    // Stage timing: the CPU is synchronous, so a steady clock around the stage is exact.
    void stageBegin(const char* stage);
    void stageEnd(const char* stage);
    void collectTimes(StageTimes& into);
    bool timing = false;

    std::string deviceName() const;
    std::int64_t residentThreads() const { return omp_get_max_threads(); }
    std::size_t freeMemoryBytes() const;

   private:
    std::vector<CellKey> sortKeysScratch_;
    std::vector<WideCellKey> sortWideKeysScratch_;
    std::vector<Index> sortValuesScratch_;
    std::vector<std::size_t> histogram_;
    std::chrono::steady_clock::time_point stageStart_;
    std::vector<std::pair<std::string, double>> pending_;
};

}  // namespace weir
