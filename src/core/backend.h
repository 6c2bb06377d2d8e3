// Which machine runs the step: all CPU cores (OpenMP) or an NVIDIA GPU (CUDA).
#pragma once

#include <cstddef>
#include <string>

namespace weir {

enum class Backend { Cpu, Cuda };

// Parses "cpu", "cuda" or "auto" (auto: CUDA when a GPU is present, else CPU).
Backend parseBackend(const std::string& name);
const char* backendName(Backend backend);

// True when this binary has the CUDA backend and a CUDA device is visible.
bool cudaDeviceAvailable();
// Free memory of this process's CUDA device in bytes; 0 without CUDA or a device.
std::size_t cudaFreeMemoryBytes();
// Makes GPU (rankOnHost mod GPUs) this process's CUDA device, one GPU per rank of a distributed
// run; returns its ordinal, or -1 without CUDA or GPUs. Call before any CUDA work.
int selectCudaDevice(int rankOnHost);
// This process's CUDA device ordinal, -1 without CUDA.
int currentCudaDevice();
// Human-readable description of the device of a backend ("NVIDIA H100 80GB HBM3, 132 SMs, ...").
std::string describeBackend(Backend backend);

}  // namespace weir
