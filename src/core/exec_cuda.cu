// CUDA primitives: CUB radix sort and scan with persistent scratch, event timing, device info.
#include <omp.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <cub/device/device_radix_sort.cuh>
#include <cub/device/device_reduce.cuh>
#include <cub/device/device_scan.cuh>
#include <cuda/functional>
#include <mutex>
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
    if (loopStream_ != nullptr) {
        cudaStreamDestroy(loopStream_);
    }
}

namespace {

// The last kernel of a conditional WHILE node's body: loop again while the flag is clear.
__global__ void setLoopCondition(cudaGraphConditionalHandle handle, const int* flag) {
    cudaGraphSetConditional(handle, *flag == 0 ? 1u : 0u);
}

}  // namespace

bool CudaExec::capturing() const {
    cudaStreamCaptureStatus status = cudaStreamCaptureStatusNone;
    WEIR_CUDA_CHECK(cudaStreamIsCapturing(stream_, &status));
    return status == cudaStreamCaptureStatusActive;
}

bool CudaExec::readFlag(const int* flag) {
    int value = 0;
    copyAndWait(&value, flag, sizeof(int), cudaMemcpyDeviceToHost);
    return value != 0;
}

cudaGraphConditionalHandle CudaExec::beginLoopBody() {
    WEIR_REQUIRE(outerStream_ == nullptr, "a device loop inside another one's capture");
    cudaStreamCaptureStatus status = cudaStreamCaptureStatusNone;
    cudaGraph_t graph = nullptr;
    const cudaGraphNode_t* dependencies = nullptr;
    const cudaGraphEdgeData* edges = nullptr;
    std::size_t count = 0;
    WEIR_CUDA_CHECK(
        cudaStreamGetCaptureInfo(stream_, &status, nullptr, &graph, &dependencies, &edges, &count));
    cudaGraphConditionalHandle handle{};
    // Default 1 at every launch of the graph: the body runs at least once, then its last kernel
    // decides.
    WEIR_CUDA_CHECK(
        cudaGraphConditionalHandleCreate(&handle, graph, 1, cudaGraphCondAssignDefault));
    cudaGraphNodeParams params{};
    params.type = cudaGraphNodeTypeConditional;
    params.conditional.handle = handle;
    params.conditional.type = cudaGraphCondTypeWhile;
    params.conditional.size = 1;
    cudaGraphNode_t node = nullptr;
    // Full dependencies on what came before (no programmatic edge into a conditional node).
    WEIR_CUDA_CHECK(cudaGraphAddNode(&node, graph, dependencies, nullptr, count, &params));
    WEIR_CUDA_CHECK(cudaStreamUpdateCaptureDependencies(stream_, &node, nullptr, 1,
                                                        cudaStreamSetCaptureDependencies));
    if (loopStream_ == nullptr) {
        WEIR_CUDA_CHECK(cudaStreamCreateWithFlags(&loopStream_, cudaStreamNonBlocking));
    }
    WEIR_CUDA_CHECK(cudaStreamBeginCaptureToGraph(loopStream_, params.conditional.phGraph_out[0],
                                                  nullptr, nullptr, 0,
                                                  cudaStreamCaptureModeThreadLocal));
    outerStream_ = stream_;
    stream_ = loopStream_;
    return handle;
}

void CudaExec::endLoopBody(cudaGraphConditionalHandle handle, const int* flag) {
    setLoopCondition<<<1, 1, 0, stream_>>>(handle, flag);
    WEIR_CUDA_CHECK(cudaGetLastError());
    cudaGraph_t body = nullptr;
    stream_ = outerStream_;
    outerStream_ = nullptr;
    WEIR_CUDA_CHECK(cudaStreamEndCapture(loopStream_, &body));  // the node's own graph
}

void CudaExec::abandonLoopBody() {
    cudaGraph_t body = nullptr;
    cudaStreamEndCapture(loopStream_, &body);
    stream_ = outerStream_;
    outerStream_ = nullptr;
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

namespace {

// Copies of at least kStagedCopyBytes go through the staging chunks.
constexpr std::size_t kStagingChunkBytes = std::size_t(32) << 20;
constexpr std::size_t kStagedCopyBytes = std::size_t(4) << 20;

// Two pinned chunks and their events, allocated on first use on one device and kept for the
// process (freed by the driver at exit: a static destructor could run after the CUDA runtime's
// own teardown). One staged copy at a time.
struct StagingChunks {
    std::mutex mutex;
    bool tried = false;
    int device = -1;
    void* chunk[2] = {nullptr, nullptr};
    cudaEvent_t done[2] = {nullptr, nullptr};

    // Whether the chunks exist for the current device (a failed allocation leaves them out, and
    // copies go direct).
    bool readyFor(int currentDevice) {
        if (!tried) {
            tried = true;
            device = currentDevice;
            for (int k = 0; k < 2; ++k) {
                if (cudaHostAlloc(&chunk[k], kStagingChunkBytes, cudaHostAllocPortable) !=
                        cudaSuccess ||
                    cudaEventCreateWithFlags(&done[k], cudaEventDisableTiming) != cudaSuccess) {
                    cudaGetLastError();  // the failure is handled: direct copies
                    chunk[0] = chunk[1] = nullptr;
                    return false;
                }
            }
        }
        return chunk[0] != nullptr && chunk[1] != nullptr && device == currentDevice;
    }
};

StagingChunks& stagingChunks() {
    static StagingChunks* chunks = new StagingChunks;  // never destroyed, see above
    return *chunks;
}

// memcpy on all cores, a megabyte or more per thread.
void copyOnCores(void* dst, const void* src, std::size_t bytes) {
    const int parts = int(std::max<std::size_t>(
        1, std::min<std::size_t>(std::size_t(omp_get_max_threads()), bytes >> 20)));
#pragma omp parallel for num_threads(parts) schedule(static)
    for (int part = 0; part < parts; ++part) {
        const std::size_t begin = bytes * std::size_t(part) / std::size_t(parts);
        const std::size_t end = bytes * std::size_t(part + 1) / std::size_t(parts);
        std::memcpy(static_cast<char*>(dst) + begin, static_cast<const char*>(src) + begin,
                    end - begin);
    }
}

// The staging chunks, locked, for a copy of `bytes`: an empty lock where the copy goes direct
// (under kStagedCopyBytes, or no chunks for the current device).
std::unique_lock<std::mutex> lockStagingFor(std::size_t bytes) {
    if (bytes < kStagedCopyBytes) {
        return {};
    }
    int device = 0;
    WEIR_CUDA_CHECK(cudaGetDevice(&device));
    StagingChunks& staging = stagingChunks();
    std::unique_lock<std::mutex> lock(staging.mutex);
    if (!staging.readyFor(device)) {
        return {};
    }
    return lock;
}

}  // namespace

void CudaExec::copyToDevice(void* deviceDst, const void* hostSrc, std::size_t bytes) {
    if (bytes == 0) {
        return;
    }
    const std::unique_lock<std::mutex> staged = lockStagingFor(bytes);
    StagingChunks& staging = stagingChunks();
    if (!staged.owns_lock()) {
        copyAndWait(deviceDst, hostSrc, bytes, cudaMemcpyHostToDevice);
        return;
    }
    for (std::size_t offset = 0, k = 0; offset < bytes; offset += kStagingChunkBytes, ++k) {
        const std::size_t slot = k & 1;
        const std::size_t length = std::min(kStagingChunkBytes, bytes - offset);
        // The DMA that last read this chunk is over before the host writes it again.
        WEIR_CUDA_CHECK(cudaEventSynchronize(staging.done[slot]));
        copyOnCores(staging.chunk[slot], static_cast<const char*>(hostSrc) + offset, length);
        WEIR_CUDA_CHECK(cudaMemcpyAsync(static_cast<char*>(deviceDst) + offset, staging.chunk[slot],
                                        length, cudaMemcpyHostToDevice, stream_));
        WEIR_CUDA_CHECK(cudaEventRecord(staging.done[slot], stream_));
    }
    WEIR_CUDA_CHECK(cudaStreamSynchronize(stream_));
}

void CudaExec::copyToHost(void* hostDst, const void* deviceSrc, std::size_t bytes) {
    if (bytes == 0) {
        return;
    }
    const std::unique_lock<std::mutex> staged = lockStagingFor(bytes);
    StagingChunks& staging = stagingChunks();
    if (!staged.owns_lock()) {
        copyAndWait(hostDst, deviceSrc, bytes, cudaMemcpyDeviceToHost);
        return;
    }
    const std::size_t chunks = (bytes + kStagingChunkBytes - 1) / kStagingChunkBytes;
    const auto startChunk = [&](std::size_t k) {
        const std::size_t offset = k * kStagingChunkBytes;
        const std::size_t length = std::min(kStagingChunkBytes, bytes - offset);
        WEIR_CUDA_CHECK(cudaMemcpyAsync(staging.chunk[k & 1],
                                        static_cast<const char*>(deviceSrc) + offset, length,
                                        cudaMemcpyDeviceToHost, stream_));
        WEIR_CUDA_CHECK(cudaEventRecord(staging.done[k & 1], stream_));
    };
    startChunk(0);
    for (std::size_t k = 0; k < chunks; ++k) {
        // The next chunk's DMA runs while the host copies this one out (its slot's last host
        // copy finished in the iteration before).
        if (k + 1 < chunks) {
            startChunk(k + 1);
        }
        WEIR_CUDA_CHECK(cudaEventSynchronize(staging.done[k & 1]));
        const std::size_t offset = k * kStagingChunkBytes;
        copyOnCores(static_cast<char*>(hostDst) + offset, staging.chunk[k & 1],
                    std::min(kStagingChunkBytes, bytes - offset));
    }
}

void CudaExec::copyAndWait(void* dst, const void* src, std::size_t bytes, cudaMemcpyKind kind) {
    WEIR_CUDA_CHECK(cudaMemcpyAsync(dst, src, bytes, kind, stream_));
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
