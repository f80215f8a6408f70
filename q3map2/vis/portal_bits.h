// Rows of bits, one row per portal (or cluster), stored in one block of 64-bit words.
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace q3::vis {

inline size_t wordsForBits(size_t bits) { return (bits + 63) / 64; }
inline bool testBit(const uint64_t* row, size_t i) { return (row[i >> 6] >> (i & 63)) & 1u; }
inline void setBit(uint64_t* row, size_t i) { row[i >> 6] |= uint64_t{1} << (i & 63); }
inline size_t countBits(const uint64_t* row, size_t words) {
    size_t n = 0;
    for (size_t w = 0; w < words; ++w) n += static_cast<size_t>(std::popcount(row[w]));
    return n;
}

class BitMatrix {
public:
    BitMatrix() = default;
    BitMatrix(size_t rows, size_t bits) : rows_(rows), words_(wordsForBits(bits)), data_(rows * words_, 0) {}

    uint64_t* row(size_t r) { return data_.data() + r * words_; }
    const uint64_t* row(size_t r) const { return data_.data() + r * words_; }
    size_t rows() const { return rows_; }
    size_t words() const { return words_; }

private:
    size_t rows_ = 0;
    size_t words_ = 0;
    std::vector<uint64_t> data_;
};

}  // namespace q3::vis
