// Counts on the command line, written as people write them: 20000, 20k, 5M, 1e9, 1.5k. Used by
// every count option (--particles, --frames, --sizes, --steps, ...), each with its own range.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>

namespace weir {

// The most particles one run holds: particle indices are 32-bit.
constexpr std::int64_t kMaxParticles = 2147483647;
constexpr const char* kParticleLimitText =
    "the most particles one run holds, as its indices are 32-bit";

// `text` as a whole count in [min, max]: digits with an optional fraction and exponent, then an
// optional k (10^3), M (10^6) or G/B (10^9). Throws std::invalid_argument naming the option, the
// value and what is allowed (`maxMeaning` says why max is the limit, e.g. "the most particles one
// run holds").
std::int64_t parseCount(const std::string& text, const std::string& option, std::int64_t min,
                        std::int64_t max, const std::string& maxMeaning = "");

// The same as a CLI11 transform: rewrites the option's text to the plain integer, or fails with
// the message (CLI11 puts the option's name in front).
CLI::Validator countOption(std::int64_t min, std::int64_t max, const std::string& maxMeaning = "");

}  // namespace weir
