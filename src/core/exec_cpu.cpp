// CPU primitives: a parallel LSD radix sort (paper §6.2) and a prefix sum.
#include "core/exec_cpu.h"

#include <unistd.h>

#include <fstream>
#include <limits>
#include <sstream>

namespace weir {

namespace {

// LSD radix sort of (key, value) pairs on the low keyBits bits, 8 bits a pass, stable.
template <class Key>
void radixSortPairs(const Key* keysIn, Key* keysOut, const Index* valuesIn, Index* valuesOut,
                    Index n, int keyBits, std::vector<Key>& keysScratch,
                    std::vector<Index>& valuesScratch, std::vector<std::size_t>& histogram) {
    constexpr int kDigitBits = 8;
    constexpr int kBuckets = 1 << kDigitBits;
    const int passes = std::max(1, (keyBits + kDigitBits - 1) / kDigitBits);
    keysScratch.resize(n);
    valuesScratch.resize(n);
    // Ping-pong so that the last pass lands in the output arrays.
    Key* keyBuf[2] = {keysOut, keysScratch.data()};
    Index* valBuf[2] = {valuesOut, valuesScratch.data()};
    int dst = passes % 2 == 0 ? 1 : 0;  // buffer the first pass writes into
    const Key* srcKeys = keysIn;
    const Index* srcValues = valuesIn;
    const int threads = omp_get_max_threads();
    histogram.assign(std::size_t(threads) * kBuckets, 0);
    for (int pass = 0; pass < passes; ++pass) {
        const int shift = pass * kDigitBits;
        Key* outKeys = keyBuf[dst];
        Index* outValues = valBuf[dst];
#pragma omp parallel num_threads(threads)
        {
            const int t = omp_get_thread_num();
            const int nt = omp_get_num_threads();
            const Index begin = Index(std::int64_t(n) * t / nt);
            const Index end = Index(std::int64_t(n) * (t + 1) / nt);
            std::size_t* hist = &histogram[std::size_t(t) * kBuckets];
            std::fill(hist, hist + kBuckets, 0);
            for (Index i = begin; i < end; ++i) {
                ++hist[(srcKeys[i] >> shift) & (kBuckets - 1)];
            }
#pragma omp barrier
#pragma omp single
            {
                // Offsets ordered by (digit, thread): keeps the sort stable.
                std::size_t sum = 0;
                for (int d = 0; d < kBuckets; ++d) {
                    for (int tt = 0; tt < nt; ++tt) {
                        std::size_t c = histogram[std::size_t(tt) * kBuckets + d];
                        histogram[std::size_t(tt) * kBuckets + d] = sum;
                        sum += c;
                    }
                }
            }
            for (Index i = begin; i < end; ++i) {
                std::size_t at = hist[(srcKeys[i] >> shift) & (kBuckets - 1)]++;
                outKeys[at] = srcKeys[i];
                outValues[at] = srcValues[i];
            }
        }
        srcKeys = outKeys;
        srcValues = outValues;
        dst ^= 1;
    }
}

}  // namespace

void CpuExec::sortPairs(const CellKey* keysIn, CellKey* keysOut, const Index* valuesIn,
                        Index* valuesOut, Index n, int keyBits) {
    radixSortPairs(keysIn, keysOut, valuesIn, valuesOut, n, keyBits, sortKeysScratch_,
                   sortValuesScratch_, histogram_);
}

void CpuExec::sortPairs(const WideCellKey* keysIn, WideCellKey* keysOut, const Index* valuesIn,
                        Index* valuesOut, Index n, int keyBits) {
    radixSortPairs(keysIn, keysOut, valuesIn, valuesOut, n, keyBits, sortWideKeysScratch_,
                   sortValuesScratch_, histogram_);
}

namespace {

template <class T>
void serialInclusiveScan(const T* in, T* out, Index n) {
    T sum = 0;
    for (Index i = 0; i < n; ++i) {
        sum += in[i];
        out[i] = sum;
    }
}

}  // namespace

void CpuExec::inclusiveScan(const Index* in, Index* out, Index n) {
    serialInclusiveScan(in, out, n);
}

void CpuExec::inclusiveScan(const std::int64_t* in, std::int64_t* out, Index n) {
    serialInclusiveScan(in, out, n);
}

void CpuExec::inclusiveMaxScan(Index* data, Index n) {
    for (Index i = 1; i < n; ++i) {
        data[i] = std::max(data[i], data[i - 1]);
    }
}

namespace {

template <class T>
void sumOnCores(const T* in, Index n, T* out) {
    double total = 0;  // float sums in double: the CPU's answer is the accurate one
#pragma omp parallel for schedule(static) reduction(+ : total)
    for (Index i = 0; i < n; ++i) {
        total += double(in[i]);
    }
    *out = T(total);
}

template <class T>
void maxOnCores(const T* in, Index n, T* out) {
    T best = std::numeric_limits<T>::lowest();
#pragma omp parallel for schedule(static) reduction(max : best)
    for (Index i = 0; i < n; ++i) {
        best = in[i] > best ? in[i] : best;
    }
    *out = best;
}

}  // namespace

void CpuExec::sum(const float* in, Index n, float* out) { sumOnCores(in, n, out); }
void CpuExec::sum(const double* in, Index n, double* out) { sumOnCores(in, n, out); }
void CpuExec::max(const float* in, Index n, float* out) { maxOnCores(in, n, out); }
void CpuExec::max(const double* in, Index n, double* out) { maxOnCores(in, n, out); }

void CpuExec::stageBegin(const char*) {
    if (timing) {
        stageStart_ = std::chrono::steady_clock::now();
    }
}

void CpuExec::stageEnd(const char* stage) {
    if (timing) {
        auto ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() -
                                                            stageStart_)
                      .count();
        pending_.emplace_back(stage, ms);
    }
}

void CpuExec::collectTimes(StageTimes& into) {
    for (auto& [stage, ms] : pending_) {
        into.add(stage, ms);
    }
    pending_.clear();
}

std::string CpuExec::deviceName() const {
    std::string model = "CPU";
    std::ifstream cpuinfo("/proc/cpuinfo");
    for (std::string line; std::getline(cpuinfo, line);) {
        if (line.rfind("model name", 0) == 0) {
            model = line.substr(line.find(':') + 2);
            break;
        }
    }
    std::ostringstream s;
    s << model << ", " << omp_get_max_threads() << " OpenMP threads";
    return s.str();
}

std::size_t CpuExec::freeMemoryBytes() const {
    // MemAvailable counts reclaimable page cache, unlike sysconf's free pages.
    std::ifstream meminfo("/proc/meminfo");
    for (std::string key; meminfo >> key;) {
        std::size_t kib = 0;
        meminfo >> kib;
        if (key == "MemAvailable:") {
            return kib * 1024;
        }
        meminfo.ignore(256, '\n');
    }
    return std::size_t(sysconf(_SC_AVPHYS_PAGES)) * std::size_t(sysconf(_SC_PAGESIZE));
}

}  // namespace weir
