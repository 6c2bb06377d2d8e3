// Counter-based random numbers for Monte Carlo: each number is a hash of (pixel, sample, draw), so
// the CPU and CUDA draw the same numbers for a pixel whatever order the work runs in, and an image
// is the same from run to run.
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

// The numbers of one path: the n-th call of next() is a pure function of (pixel, sample, n).
class SampleStream {
   public:
    WEIR_HD SampleStream(std::uint32_t pixel, std::uint32_t sample)
        : key_(mixBits(pixel * 0x9e3779b9U ^ mixBits(sample + 0x632be5abU))) {}

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
