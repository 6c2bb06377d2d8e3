// Counter-based random numbers: the n-th number of a stream is a hash of (the stream's key, n), so
// the numbers do not depend on the order the work runs in, on the thread count or on the backend
// (the CPU and CUDA draw the same), and a result is the same from run to run. The path tracer keys
// a stream by (pixel, sample) (raytrace/sample_stream.h), the whitewater by (frame, particle).
#pragma once

#include <cstdint>

#include "core/config.h"

namespace weir {

// A 32-bit integer hash with good avalanche (Chris Wellons' "lowbias32", bias 0.17).
WEIR_HD inline std::uint32_t mixBits(std::uint32_t x) {
    x ^= x >> 16;
    x *= 0x7feb352dU;
    x ^= x >> 15;
    x *= 0x846ca68bU;
    x ^= x >> 16;
    return x;
}

// The numbers of one stream: the n-th call of next() is a pure function of (key, n).
class CounterStream {
   public:
    WEIR_HD explicit CounterStream(std::uint32_t key) : key_(key) {}

    // Uniform in [0, 1): 24 random bits, exact in a float.
    WEIR_HD float next() {
        const std::uint32_t bits = mixBits(key_ ^ mixBits(draw_ * 0x85ebca6bU + 0x27d4eb2fU));
        ++draw_;
        return float(bits >> 8) * (1.0f / 16777216.0f);
    }

   private:
    std::uint32_t key_;
    std::uint32_t draw_ = 0;
};

}  // namespace weir
