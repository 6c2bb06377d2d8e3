// Helpers shared by the frame writers and readers: raw binary output, number text, file input.
#pragma once

#include <algorithm>
#include <array>
#include <charconv>
#include <cstddef>
#include <ostream>
#include <string>
#include <type_traits>
#include <vector>

#include "core/config.h"

namespace weir {

// Writes count values valueAt(0..count-1) as raw bytes of T through a bounded buffer, so
// interleaving SoA arrays needs no full-size copy.
template <class T, class ValueAt>
void writeSequence(std::ostream& out, std::size_t count, ValueAt valueAt) {
    std::array<T, 4096> buffer;
    for (std::size_t start = 0; start < count; start += buffer.size()) {
        const std::size_t chunk = std::min(buffer.size(), count - start);
        for (std::size_t j = 0; j < chunk; ++j) {
            buffer[j] = T(valueAt(start + j));
        }
        out.write(reinterpret_cast<const char*>(buffer.data()), std::streamsize(chunk * sizeof(T)));
    }
}

// Writes arrays[0][0], arrays[1][0], ..., arrays[0][1], ...: n tuples of arrays.size() values.
// A chunk of tuples at a time, one array at a time (a division and a remainder per value made
// the VTU writer 5x slower than dd: bench/NOTES.md F3); a single array of T goes out as it is.
template <class T>
void writeInterleaved(std::ostream& out, const std::vector<const std::vector<Real>*>& arrays,
                      std::size_t n) {
    const std::size_t k = arrays.size();
    if constexpr (std::is_same_v<T, Real>) {
        if (k == 1) {
            out.write(reinterpret_cast<const char*>(arrays[0]->data()),
                      std::streamsize(n * sizeof(T)));
            return;
        }
    }
    constexpr std::size_t kTuples = 4096;
    std::vector<T> buffer(kTuples * k);
    for (std::size_t start = 0; start < n; start += kTuples) {
        const std::size_t rows = std::min(kTuples, n - start);
        for (std::size_t c = 0; c < k; ++c) {
            const Real* from = arrays[c]->data() + start;
            T* to = buffer.data() + c;
            for (std::size_t j = 0; j < rows; ++j) {
                to[j * k] = T(from[j]);
            }
        }
        out.write(reinterpret_cast<const char*>(buffer.data()),
                  std::streamsize(rows * k * sizeof(T)));
    }
}

// The shortest text that reads back to exactly the same value (locale independent).
template <class T>
std::string numberText(T value) {
    std::array<char, 64> text;
    const auto result = std::to_chars(text.data(), text.data() + text.size(), value);
    return std::string(text.data(), result.ptr);
}

// Parses all of text as a number; false if it is not one.
template <class T>
bool parseNumber(std::string_view text, T& value) {
    const auto result = std::from_chars(text.data(), text.data() + text.size(), value);
    return result.ec == std::errc() && result.ptr == text.data() + text.size();
}

// The whole file as bytes; throws IoError naming the path and the OS reason.
std::string readFileBytes(const std::string& path);

}  // namespace weir
