// The CUDA backend's primitives: a generic one-thread-per-element kernel, CUB sort and scan,
// device buffers, and CUDA-event stage timing.
#pragma once

#include <cuda_runtime.h>

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "core/check.h"
#include "core/config.h"
#include "core/stage_timer.h"
#include "core/team.h"

namespace weir {

// Owning device memory, move-only. resize() reallocates only to grow past the capacity, and then
// does not keep the contents; within the capacity it keeps them (a distributed run's particle
// count changes every step: no allocation per step).
template <class T>
class DeviceBuffer {
   public:
    DeviceBuffer() = default;
    explicit DeviceBuffer(std::size_t n) { resize(n); }
    DeviceBuffer(const DeviceBuffer&) = delete;
    DeviceBuffer& operator=(const DeviceBuffer&) = delete;
    DeviceBuffer(DeviceBuffer&& o) noexcept { swap(o); }
    DeviceBuffer& operator=(DeviceBuffer&& o) noexcept {
        swap(o);
        return *this;
    }
    ~DeviceBuffer() { release(); }

    void resize(std::size_t n) {
        if (n > capacity_) {
            release();
            WEIR_CUDA_CHECK(cudaMalloc(&data_, n * sizeof(T)));
            capacity_ = n;
        }
        size_ = n;
    }
    std::size_t size() const { return size_; }
    std::size_t capacity() const { return capacity_; }
    T* data() { return data_; }
    const T* data() const { return data_; }
    void swap(DeviceBuffer& o) noexcept {
        std::swap(data_, o.data_);
        std::swap(size_, o.size_);
        std::swap(capacity_, o.capacity_);
    }

   private:
    void release() {
        if (data_ != nullptr) {
            cudaFree(data_);
        }
        data_ = nullptr;
        size_ = 0;
        capacity_ = 0;
    }
    T* data_ = nullptr;
    std::size_t size_ = 0;
    std::size_t capacity_ = 0;
};

// At least 6 blocks of 256 threads per SM, so registers are capped at 40: the density and force
// loops, issue-bound, then run at 75% occupancy instead of 62% (bench/NOTES.md: 2-4% faster).
//
// Launched with programmatic dependent launch (CudaExec::programmaticLaunch), a kernel's blocks
// may start while the kernel before it finishes: each first waits until that kernel's work is
// complete and visible (griddepcontrol.wait, a no-op without the launch attribute), then lets
// the next kernel start launching in turn. The launch latency between the small kernels of a
// step overlaps the tail of the one before.
template <class F>
__global__ void __launch_bounds__(256, 6) forEachKernel(Index n, F f) {
#if defined(__CUDA_ARCH__) && __CUDA_ARCH__ >= 900
    asm volatile("griddepcontrol.wait;" ::: "memory");
    asm volatile("griddepcontrol.launch_dependents;");
#endif
    Index i = Index(blockIdx.x) * Index(blockDim.x) + Index(threadIdx.x);
    if (i < n) {
        f(i);
    }
}

// An instantiated CUDA graph, move-only.
class CudaGraph {
   public:
    CudaGraph() = default;
    CudaGraph(const CudaGraph&) = delete;
    CudaGraph& operator=(const CudaGraph&) = delete;
    ~CudaGraph() {
        if (exec_ != nullptr) {
            cudaGraphExecDestroy(exec_);
        }
    }
    bool ready() const { return exec_ != nullptr; }
    cudaGraphExec_t get() const { return exec_; }
    void reset(cudaGraphExec_t e) {
        if (exec_ != nullptr) {
            cudaGraphExecDestroy(exec_);
        }
        exec_ = e;
    }

   private:
    cudaGraphExec_t exec_ = nullptr;
};

class CudaExec {
   public:
    using Graph = CudaGraph;
    template <class T>
    using Buffer = DeviceBuffer<T>;
    static constexpr bool isDevice = true;
    static constexpr int kBlockSize = 256;

    CudaExec();
    ~CudaExec();
    CudaExec(const CudaExec&) = delete;
    CudaExec& operator=(const CudaExec&) = delete;

    // Runs f(i) for i in [0, n), one CUDA thread each, on this backend's stream.
    template <class F>
    void forEach(Index n, F f) const {
        if (n <= 0) {
            return;
        }
        unsigned blocks = unsigned((std::int64_t(n) + kBlockSize - 1) / kBlockSize);
        if (programmaticLaunch) {
            cudaLaunchConfig_t config{};
            config.gridDim = dim3(blocks);
            config.blockDim = dim3(kBlockSize);
            config.dynamicSmemBytes = 0;
            config.stream = stream_;
            cudaLaunchAttribute attribute{};
            attribute.id = cudaLaunchAttributeProgrammaticStreamSerialization;
            attribute.val.programmaticStreamSerializationAllowed = 1;
            config.attrs = &attribute;
            config.numAttrs = 1;
            WEIR_CUDA_CHECK(cudaLaunchKernelEx(&config, forEachKernel<F>, n, f));
        } else {
            forEachKernel<<<blocks, kBlockSize, 0, stream_>>>(n, f);
        }
        WEIR_CUDA_CHECK(cudaGetLastError());
#ifndef NDEBUG
        cudaStreamCaptureStatus capturing = cudaStreamCaptureStatusNone;
        WEIR_CUDA_CHECK(cudaStreamIsCapturing(stream_, &capturing));
        if (capturing == cudaStreamCaptureStatusNone) {
            WEIR_CUDA_CHECK(cudaStreamSynchronize(stream_));
        }
#endif
    }

    // Runs f(i, team) for i in [0, n) with a team of TeamSize adjacent lanes per i (core/team.h).
    template <int TeamSize, class F>
    void forEachTeam(Index n, F f) const {
        WEIR_REQUIRE(std::int64_t(n) * TeamSize < (std::int64_t(1) << 31),
                     "a team launch of " << n << " x " << TeamSize << " threads");
        forEach(n * TeamSize,
                [=] __device__(Index t) { f(t / TeamSize, Team<TeamSize>{int(t % TeamSize)}); });
    }

    // Stable (key, value) radix sort on the low keyBits bits, by CUB.
    void sortPairs(const CellKey* keysIn, CellKey* keysOut, const Index* valuesIn, Index* valuesOut,
                   Index n, int keyBits);
    void sortPairs(const WideCellKey* keysIn, WideCellKey* keysOut, const Index* valuesIn,
                   Index* valuesOut, Index n, int keyBits);
    // Inclusive prefix sum by CUB; in and out may alias.
    void inclusiveScan(const Index* in, Index* out, Index n);
    void inclusiveScan(const std::int64_t* in, std::int64_t* out, Index n);
    // data[i] = max(data[0], ..., data[i]), in place, by CUB.
    void inclusiveMaxScan(Index* data, Index n);
    // *out = the sum and the maximum of in[0, n) by CUB, out in device memory: no host round
    // trip, capturable in a graph (once a call of that size has sized the scratch outside one).
    void sum(const float* in, Index n, float* out);
    void sum(const double* in, Index n, double* out);
    void max(const float* in, Index n, float* out);
    void max(const double* in, Index n, double* out);

    // Copies between host memory and a buffer, waiting for them (copyToDevice, copyToHost).
    template <class T>
    void upload(Buffer<T>& dst, const T* src, std::size_t n) {
        dst.resize(n);
        copyToDevice(dst.data(), src, n * sizeof(T));
    }
    template <class T>
    void download(const Buffer<T>& src, T* dst, std::size_t n) {
        copyToHost(dst, src.data(), n * sizeof(T));
    }
    // n elements between the host and a buffer from element `offset` on (the buffer keeps its
    // size).
    template <class T>
    void uploadAt(Buffer<T>& dst, std::size_t offset, const T* src, std::size_t n) {
        copyToDevice(dst.data() + offset, src, n * sizeof(T));
    }
    template <class T>
    void downloadFrom(const Buffer<T>& src, std::size_t offset, T* dst, std::size_t n) {
        copyToHost(dst, src.data() + offset, n * sizeof(T));
    }
    // Blocking copies from (to) pageable host memory: large ones go through two pinned staging
    // chunks shared by the process, the host's copy of one chunk (on all cores) overlapping the
    // DMA of the other, since a pageable cudaMemcpy runs at a few GB/s.
    void copyToDevice(void* deviceDst, const void* hostSrc, std::size_t bytes);
    void copyToHost(void* hostDst, const void* deviceSrc, std::size_t bytes);
    // The same without waiting: the copy is done once synchronize() returns (the host memory
    // must stay put until then). A distributed step queues several and waits once.
    template <class T>
    void uploadAtAsync(Buffer<T>& dst, std::size_t offset, const T* src, std::size_t n) {
        if (n > 0) {
            WEIR_CUDA_CHECK(cudaMemcpyAsync(dst.data() + offset, src, n * sizeof(T),
                                            cudaMemcpyHostToDevice, stream_));
        }
    }
    template <class T>
    void downloadFromAsync(const Buffer<T>& src, std::size_t offset, T* dst, std::size_t n) {
        if (n > 0) {
            WEIR_CUDA_CHECK(cudaMemcpyAsync(dst, src.data() + offset, n * sizeof(T),
                                            cudaMemcpyDeviceToHost, stream_));
        }
    }
    template <class T>
    T readOne(const Buffer<T>& src, std::size_t index) {
        T value;
        copyToHost(&value, src.data() + index, sizeof(T));
        return value;
    }
    template <class T>
    void writeOne(Buffer<T>& dst, std::size_t index, const T& value) {
        WEIR_CUDA_CHECK(cudaMemcpyAsync(dst.data() + index, &value, sizeof(T),
                                        cudaMemcpyHostToDevice, stream_));
        WEIR_CUDA_CHECK(cudaStreamSynchronize(stream_));
    }
    void synchronize() { WEIR_CUDA_CHECK(cudaStreamSynchronize(stream_)); }

    // Runs body() until the device int *flag (set by body's own kernels) is non-zero, at most
    // maxRounds times; body's kernels must do nothing once it is set. Run directly, the host
    // reads the flag after round firstCheck and every second round from there (a round trip
    // each). Inside a graph capture the loop becomes a conditional WHILE node (CUDA 12.4): body is
    // recorded once into the node's graph, which ends by setting the node's condition from *flag
    // on the device, so a replayed graph loops with no host round trip. Body's kernels are then
    // launched without programmatic dependent launch.
    template <class Body>
    void repeatUntilSet(const int* flag, int maxRounds, int firstCheck, Body&& body) {
        if (!capturing()) {
            for (int round = 0; round < maxRounds; ++round) {
                body();
                if (round >= firstCheck && (round - firstCheck) % 2 == 0 && readFlag(flag)) {
                    return;
                }
            }
            return;
        }
        const cudaGraphConditionalHandle handle = beginLoopBody();
        const bool programmatic = programmaticLaunch;
        programmaticLaunch = false;
        try {
            body();
        } catch (...) {
            programmaticLaunch = programmatic;
            abandonLoopBody();
            throw;
        }
        programmaticLaunch = programmatic;
        endLoopBody(handle, flag);
    }

    // Records everything body() queues on this backend's stream into graph (nothing runs).
    template <class Body>
    void capture(Graph& graph, Body&& body) {
        WEIR_CUDA_CHECK(cudaStreamBeginCapture(stream_, cudaStreamCaptureModeThreadLocal));
        try {
            body();
        } catch (...) {
            cudaGraph_t broken = nullptr;
            cudaStreamEndCapture(stream_, &broken);
            if (broken != nullptr) {
                cudaGraphDestroy(broken);
            }
            throw;
        }
        cudaGraph_t recorded = nullptr;
        WEIR_CUDA_CHECK(cudaStreamEndCapture(stream_, &recorded));
        cudaGraphExec_t instance = nullptr;
        cudaError_t status = cudaGraphInstantiate(&instance, recorded, 0);
        cudaGraphDestroy(recorded);
        WEIR_CUDA_CHECK(status);
        graph.reset(instance);
    }
    void launch(const Graph& graph) { WEIR_CUDA_CHECK(cudaGraphLaunch(graph.get(), stream_)); }

    // Programmatic dependent launch of forEach kernels (see forEachKernel) on Hopper and later
    // (bench/NOTES.md #11); WEIR_PDL=0 turns it off.
    bool programmaticLaunch = false;

    void stageBegin(const char* stage);
    void stageEnd(const char* stage);
    // Waits for the recorded events and moves their times into `into`.
    void collectTimes(StageTimes& into);
    bool timing = false;

    std::string deviceName() const;
    // Threads the GPU keeps resident at forEachKernel's occupancy (6 blocks of 256 per SM).
    std::int64_t residentThreads() const { return std::int64_t(multiprocessors_) * 6 * kBlockSize; }
    std::size_t freeMemoryBytes() const;
    cudaStream_t stream() const { return stream_; }

   private:
    // Whether this backend's stream is recording a graph.
    bool capturing() const;
    // *flag, read back (a round trip).
    bool readFlag(const int* flag);
    // repeatUntilSet inside a capture: adds the WHILE node after what was recorded so far and
    // records on a second stream into its body until endLoopBody, which adds the kernel that
    // sets the condition and returns to the outer capture.
    cudaGraphConditionalHandle beginLoopBody();
    void endLoopBody(cudaGraphConditionalHandle handle, const int* flag);
    void abandonLoopBody();

    // One cudaMemcpyAsync on the stream, then waits for it.
    void copyAndWait(void* dst, const void* src, std::size_t bytes, cudaMemcpyKind kind);
    cudaEvent_t takeEvent();
    template <class T>
    void deviceInclusiveScan(const T* in, T* out, Index n);

    cudaStream_t stream_ = nullptr;
    cudaStream_t outerStream_ = nullptr;  // the capturing stream while a loop body is recorded
    cudaStream_t loopStream_ = nullptr;   // where loop bodies are recorded
    int multiprocessors_ = 1;
    // Scratch of CUB's reductions of `bytes`, grown outside graph capture only.
    unsigned char* reduceScratch(std::size_t bytes);

    DeviceBuffer<unsigned char> sortTemp_, scanTemp_, reduceTemp_;
    std::vector<cudaEvent_t> eventPool_;
    std::size_t eventsUsed_ = 0;
    cudaEvent_t openEvent_ = nullptr;
    std::vector<std::pair<std::string, std::pair<cudaEvent_t, cudaEvent_t>>> pending_;
};

}  // namespace weir
