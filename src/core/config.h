// Build-wide basics: the real type, the host/device annotation, index types.
#pragma once

#include <cstdint>

#if defined(__CUDACC__)
#define WEIR_HD __host__ __device__
#define WEIR_DEVICE_CODE 1
#else
#define WEIR_HD
#endif

namespace weir {

#if defined(WEIR_DOUBLE)
using Real = double;
#else
using Real = float;
#endif

// Particle and cell indices. 32 bits cover two billion particles.
using Index = std::int32_t;
// Cell ids as in paper §6.2: 2 unused bits, then Y, Z, X at 10 bits each.
using CellKey = std::uint32_t;
// Cell ids of grids past 1024 cells on an axis: the same order at 21 bits each.
using WideCellKey = std::uint64_t;

}  // namespace weir
