// CUDA primitives: CUB radix sort and scan with persistent scratch, event timing, device info.
#include <cstdlib>
#include <cub/device/device_radix_sort.cuh>
#include <cub/device/device_reduce.cuh>
#include <cub/device/device_scan.cuh>
#include <cuda/functional>
#include <sstream>
#include <string>

#include "core/exec_cuda.cuh"

namespace weir {

CudaExec::CudaExec() {
    WEIR_CUDA_CHECK(cudaStreamCreateWithFlags(&stream_, cudaStreamNonBlocking));
    int device = 0, major = 0;
    WEIR_CUDA_CHECK(cudaGetDevice(&device));
    WEIR_CUDA_CHECK(cudaDeviceGetAttribute(&major, cudaDevAttrComputeCapabilityMajor, device));
    WEIR_CUDA_CHECK(
        cudaDeviceGetAttribute(&multiprocessors_, cudaDevAttrMultiProcessorCount, device));
    const char* pdl = std::getenv("WEIR_PDL");
    programmaticLaunch = major >= 9 && !(pdl != nullptr && std::string(pdl) == "0");
}

CudaExec::~CudaExec() {
    for (cudaEvent_t e : eventPool_) {
        cudaEventDestroy(e);
    }
    if (stream_ != nullptr) {
        cudaStreamDestroy(stream_);
    }
}

namespace {

// CUB's stable radix sort of (key, value) pairs on the low keyBits bits, with scratch kept in
// `temp` between calls.
template <class Key>
void cubSortPairs(DeviceBuffer<unsigned char>& temp, cudaStream_t stream, const Key* keysIn,
                  Key* keysOut, const Index* valuesIn, Index* valuesOut, Index n, int keyBits) {
    std::size_t bytes = 0;
    WEIR_CUDA_CHECK(cub::DeviceRadixSort::SortPairs(nullptr, bytes, keysIn, keysOut, valuesIn,
                                                    valuesOut, n, 0, keyBits, stream));
    if (temp.size() < bytes) {
        temp.resize(bytes);
    }
    bytes = temp.size();
    WEIR_CUDA_CHECK(cub::DeviceRadixSort::SortPairs(temp.data(), bytes, keysIn, keysOut, valuesIn,
                                                    valuesOut, n, 0, keyBits, stream));
}

}  // namespace

void CudaExec::sortPairs(const CellKey* keysIn, CellKey* keysOut, const Index* valuesIn,
                         Index* valuesOut, Index n, int keyBits) {
    cubSortPairs(sortTemp_, stream_, keysIn, keysOut, valuesIn, valuesOut, n, keyBits);
}

// The 64-bit cell ids of grids past 1024 cells per axis: only keyBits bits, so fewer passes.
void CudaExec::sortPairs(const WideCellKey* keysIn, WideCellKey* keysOut, const Index* valuesIn,
                         Index* valuesOut, Index n, int keyBits) {
    cubSortPairs(sortTemp_, stream_, keysIn, keysOut, valuesIn, valuesOut, n, keyBits);
}

template <class T>
void CudaExec::deviceInclusiveScan(const T* in, T* out, Index n) {
    std::size_t bytes = 0;
    WEIR_CUDA_CHECK(cub::DeviceScan::InclusiveSum(nullptr, bytes, in, out, n, stream_));
    if (scanTemp_.size() < bytes) {
        scanTemp_.resize(bytes);
    }
    bytes = scanTemp_.size();
    WEIR_CUDA_CHECK(cub::DeviceScan::InclusiveSum(scanTemp_.data(), bytes, in, out, n, stream_));
}

void CudaExec::inclusiveScan(const Index* in, Index* out, Index n) {
    deviceInclusiveScan(in, out, n);
}

void CudaExec::inclusiveScan(const std::int64_t* in, std::int64_t* out, Index n) {
    deviceInclusiveScan(in, out, n);
}

unsigned char* CudaExec::reduceScratch(std::size_t bytes) {
    if (reduceTemp_.size() < bytes) {
        cudaStreamCaptureStatus capturing = cudaStreamCaptureStatusNone;
        WEIR_CUDA_CHECK(cudaStreamIsCapturing(stream_, &capturing));
        WEIR_REQUIRE(
            capturing == cudaStreamCaptureStatusNone,
            "a reduction of a new size inside a graph capture (" << bytes << " bytes of scratch)");
        reduceTemp_.resize(bytes);
    }
    return reduceTemp_.data();
}

namespace {

template <class T>
void cubSum(CudaExec& exec, const T* in, Index n, T* out, cudaStream_t stream,
            unsigned char* (CudaExec::*scratch)(std::size_t)) {
    std::size_t bytes = 0;
    WEIR_CUDA_CHECK(cub::DeviceReduce::Sum(nullptr, bytes, in, out, n, stream));
    unsigned char* temp = (exec.*scratch)(bytes);
    WEIR_CUDA_CHECK(cub::DeviceReduce::Sum(temp, bytes, in, out, n, stream));
}

template <class T>
void cubMax(CudaExec& exec, const T* in, Index n, T* out, cudaStream_t stream,
            unsigned char* (CudaExec::*scratch)(std::size_t)) {
    std::size_t bytes = 0;
    WEIR_CUDA_CHECK(cub::DeviceReduce::Max(nullptr, bytes, in, out, n, stream));
    unsigned char* temp = (exec.*scratch)(bytes);
    WEIR_CUDA_CHECK(cub::DeviceReduce::Max(temp, bytes, in, out, n, stream));
}

}  // namespace

void CudaExec::inclusiveMaxScan(Index* data, Index n) {
    std::size_t bytes = 0;
    WEIR_CUDA_CHECK(
        cub::DeviceScan::InclusiveScan(nullptr, bytes, data, data, cuda::maximum<>{}, n, stream_));
    if (scanTemp_.size() < bytes) {
        scanTemp_.resize(bytes);
    }
    bytes = scanTemp_.size();
    WEIR_CUDA_CHECK(cub::DeviceScan::InclusiveScan(scanTemp_.data(), bytes, data, data,
                                                   cuda::maximum<>{}, n, stream_));
}

void CudaExec::download1(void* dst, const void* src, std::size_t bytes) {
    WEIR_CUDA_CHECK(cudaMemcpyAsync(dst, src, bytes, cudaMemcpyDeviceToHost, stream_));
    WEIR_CUDA_CHECK(cudaStreamSynchronize(stream_));
}

cudaEvent_t CudaExec::takeEvent() {
    if (eventsUsed_ == eventPool_.size()) {
        cudaEvent_t e;
        WEIR_CUDA_CHECK(cudaEventCreate(&e));
        eventPool_.push_back(e);
    }
    return eventPool_[eventsUsed_++];
}

void CudaExec::stageBegin(const char*) {
    if (timing) {
        openEvent_ = takeEvent();
        WEIR_CUDA_CHECK(cudaEventRecord(openEvent_, stream_));
    }
}

void CudaExec::stageEnd(const char* stage) {
    if (timing) {
        cudaEvent_t end = takeEvent();
        WEIR_CUDA_CHECK(cudaEventRecord(end, stream_));
        pending_.push_back({stage, {openEvent_, end}});
    }
}

void CudaExec::collectTimes(StageTimes& into) {
    if (!pending_.empty()) {
        WEIR_CUDA_CHECK(cudaEventSynchronize(pending_.back().second.second));
    }
    for (auto& [stage, events] : pending_) {
        float ms = 0;
        WEIR_CUDA_CHECK(cudaEventElapsedTime(&ms, events.first, events.second));
        into.add(stage, ms);
    }
    pending_.clear();
    eventsUsed_ = 0;
}

std::string CudaExec::deviceName() const {
    int device = 0;
    WEIR_CUDA_CHECK(cudaGetDevice(&device));
    cudaDeviceProp prop;
    WEIR_CUDA_CHECK(cudaGetDeviceProperties(&prop, device));
    int driver = 0;
    cudaDriverGetVersion(&driver);
    std::ostringstream s;
    s << prop.name << ", " << prop.multiProcessorCount << " SMs, " << (prop.totalGlobalMem >> 20)
      << " MiB, compute " << prop.major << "." << prop.minor << ", driver CUDA " << driver / 1000
      << "." << (driver % 1000) / 10;
    return s.str();
}

std::size_t CudaExec::freeMemoryBytes() const {
    std::size_t freeBytes = 0, totalBytes = 0;
    WEIR_CUDA_CHECK(cudaMemGetInfo(&freeBytes, &totalBytes));
    return freeBytes;
}

// The current device's free memory, without making an executor (no streams or pools).
std::size_t cudaDeviceFreeBytes() {
    std::size_t freeBytes = 0, totalBytes = 0;
    WEIR_CUDA_CHECK(cudaMemGetInfo(&freeBytes, &totalBytes));
    return freeBytes;
}

bool probeCudaDevice(std::string* description) {
    int count = 0;
    if (cudaGetDeviceCount(&count) != cudaSuccess || count == 0) {
        cudaGetLastError();  // clear the sticky "no device" error
        return false;
    }
    if (description != nullptr) {
        CudaExec exec;
        *description = exec.deviceName();
    }
    return true;
}

int currentCudaDeviceOrdinal() {
    int ordinal = -1;
    if (cudaGetDevice(&ordinal) != cudaSuccess) {
        cudaGetLastError();
        return -1;
    }
    return ordinal;
}

int useCudaDeviceOf(int rankOnHost) {
    int count = 0;
    if (cudaGetDeviceCount(&count) != cudaSuccess || count == 0) {
        cudaGetLastError();
        return -1;
    }
    const int ordinal = rankOnHost % count;
    WEIR_CUDA_CHECK(cudaSetDevice(ordinal));
    return ordinal;
}

void CudaExec::sum(const float* in, Index n, float* out) {
    cubSum(*this, in, n, out, stream_, &CudaExec::reduceScratch);
}
void CudaExec::sum(const double* in, Index n, double* out) {
    cubSum(*this, in, n, out, stream_, &CudaExec::reduceScratch);
}
void CudaExec::max(const float* in, Index n, float* out) {
    cubMax(*this, in, n, out, stream_, &CudaExec::reduceScratch);
}
void CudaExec::max(const double* in, Index n, double* out) {
    cubMax(*this, in, n, out, stream_, &CudaExec::reduceScratch);
}

}  // namespace weir
