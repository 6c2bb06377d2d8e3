// Backend names and detection of a usable CUDA device.
#include "core/backend.h"

#include <stdexcept>

#include "core/exec_cpu.h"

namespace weir {

#if defined(WEIR_HAS_CUDA)
bool probeCudaDevice(std::string* description);  // core/exec_cuda.cu
int useCudaDeviceOf(int rankOnHost);             // core/exec_cuda.cu
int currentCudaDeviceOrdinal();                  // core/exec_cuda.cu
std::size_t cudaDeviceFreeBytes();               // core/exec_cuda.cu
#endif

int currentCudaDevice() {
#if defined(WEIR_HAS_CUDA)
    return currentCudaDeviceOrdinal();
#else
    return -1;
#endif
}

int selectCudaDevice(int rankOnHost) {
#if defined(WEIR_HAS_CUDA)
    return useCudaDeviceOf(rankOnHost);
#else
    (void)rankOnHost;
    return -1;
#endif
}

Backend parseBackend(const std::string& name) {
    if (name == "cpu") {
        return Backend::Cpu;
    }
    if (name == "cuda") {
        return Backend::Cuda;
    }
    if (name == "auto") {
        return cudaDeviceAvailable() ? Backend::Cuda : Backend::Cpu;
    }
    throw std::invalid_argument("unknown backend '" + name + "': allowed are auto, cuda, cpu");
}

const char* backendName(Backend backend) { return backend == Backend::Cuda ? "cuda" : "cpu"; }

bool cudaDeviceAvailable() {
#if defined(WEIR_HAS_CUDA)
    static const bool available = probeCudaDevice(nullptr);
    return available;
#else
    return false;
#endif
}

std::size_t cudaFreeMemoryBytes() {
#if defined(WEIR_HAS_CUDA)
    return cudaDeviceAvailable() ? cudaDeviceFreeBytes() : 0;
#else
    return 0;
#endif
}

std::string describeBackend(Backend backend) {
    if (backend == Backend::Cpu) {
        return CpuExec().deviceName();
    }
#if defined(WEIR_HAS_CUDA)
    std::string description;
    if (probeCudaDevice(&description)) {
        return description;
    }
    return "no CUDA device visible";
#else
    return "this weir was built without CUDA";
#endif
}

}  // namespace weir
