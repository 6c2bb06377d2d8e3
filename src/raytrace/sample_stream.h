// The path tracer's random numbers: each number is a hash of (pixel, sample, draw)
// (core/counter_random.h), so the CPU and CUDA draw the same numbers for a pixel whatever order the
// work runs in, and an image is the same from run to run.
#pragma once

#include <cstdint>

#include "core/counter_random.h"

namespace weir {

// The numbers of one path: the n-th call of next() is a pure function of (pixel, sample, n).
class SampleStream : public CounterStream {
   public:
    WEIR_HD SampleStream(std::uint32_t pixel, std::uint32_t sample)
        : CounterStream(mixBits(pixel * 0x9e3779b9U ^ mixBits(sample + 0x632be5abU))) {}
};

}  // namespace weir
