// Step 1-2 of the grid build, shared by both cell tables: a cell key per particle and a stable
// radix sort of (key, particle index) pairs. The caller reorders particle data by permutation().
#pragma once

#include <cstddef>

#include "core/config.h"

namespace weir {

// Grows a buffer to at least n elements, with headroom so that it rarely reallocates.
template <class Buffer>
void ensureCapacity(Buffer& buffer, std::size_t n) {
    if (buffer.size() < n) {
        buffer.resize(n + n / 4 + 16);
    }
}

// Key: the cell id type, CellKey (the paper's 32 bits) or WideCellKey.
template <class Exec, class Key = CellKey>
class CellSort {
   public:
    template <class T>
    using Buffer = typename Exec::template Buffer<T>;

    // Sizes the buffers for n particles; the caller then fills keys()[0, n).
    void prepare(Index n) {
        // The particle count does not change between steps: exact sizes, no headroom.
        for (auto* b : {&keys_, &sortedKeys_}) {
            b->resize(std::size_t(n));
        }
        for (auto* b : {&order_, &sortedOrder_}) {
            b->resize(std::size_t(n));
        }
        n_ = n;
    }
    Key* keys() { return keys_.data(); }

    // Sorts (key, index) by the low keyBits bits of the key, stably.
    void sort(Exec& exec, int keyBits) {
        Index* order = order_.data();
        exec.forEach(n_, [=] WEIR_HD(Index i) { order[i] = i; });
        exec.sortPairs(keys_.data(), sortedKeys_.data(), order_.data(), sortedOrder_.data(), n_,
                       keyBits);
    }

    const Key* sortedKeys() const { return sortedKeys_.data(); }
    // permutation()[i] is the old index of the particle that is i-th in cell order.
    const Index* permutation() const { return sortedOrder_.data(); }
    const Buffer<Key>& sortedKeyBuffer() const { return sortedKeys_; }
    Index count() const { return n_; }
    std::size_t bytesHeld() const {
        return (keys_.size() + sortedKeys_.size()) * sizeof(Key) +
               (order_.size() + sortedOrder_.size()) * sizeof(Index);
    }

   private:
    Index n_ = 0;
    Buffer<Key> keys_, sortedKeys_;
    Buffer<Index> order_, sortedOrder_;
};

// Bits needed for keys in [0, count).
inline int bitsFor(std::uint64_t count) {
    int bits = 1;
    while (bits < 32 && (std::uint64_t(1) << bits) < count) {
        ++bits;
    }
    return bits;
}

}  // namespace weir
