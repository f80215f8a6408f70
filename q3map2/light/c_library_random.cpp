// Jumping ahead in the C library sequence (see c_library_random.h).
#include "c_library_random.h"

#include <algorithm>
#include <vector>

namespace q3::light {
namespace {

constexpr int kWords = 31;
constexpr int kPowers = 48;  // jumps up to 2^48 - 1 values
using Matrix = std::array<std::array<uint32_t, kWords>, kWords>;
using Words = std::array<uint32_t, kWords>;

// The words oldest first: word j is the one written 31 - j steps ago. One step drops the oldest
// and appends the sum of it and the word written 3 steps ago (index 28).
Matrix oneStep() {
    Matrix m{};
    for (int j = 0; j + 1 < kWords; ++j) m[j][j + 1] = 1;
    m[kWords - 1][0] = 1;
    m[kWords - 1][kWords - 3] += 1;
    return m;
}

Matrix product(const Matrix& a, const Matrix& b) {
    Matrix out{};
    for (int i = 0; i < kWords; ++i)
        for (int k = 0; k < kWords; ++k) {
            const uint32_t aik = a[i][k];
            if (aik == 0) continue;
            for (int j = 0; j < kWords; ++j) out[i][j] += aik * b[k][j];
        }
    return out;
}

// The step matrix raised to 2^p for every p, made once.
const std::vector<Matrix>& stepPowers() {
    static const std::vector<Matrix> powers = [] {
        std::vector<Matrix> out{oneStep()};
        while (out.size() < kPowers) out.push_back(product(out.back(), out.back()));
        return out;
    }();
    return powers;
}

Words apply(const Matrix& m, const Words& v) {
    Words out{};
    for (int i = 0; i < kWords; ++i) {
        uint32_t sum = 0;
        for (int j = 0; j < kWords; ++j) sum += m[i][j] * v[j];
        out[i] = sum;
    }
    return out;
}

}  // namespace

void CLibraryRandom::discard(uint64_t count) {
    // A jump costs a 31 x 31 matrix product per set bit of the count, each as much as stepping
    // a few hundred values: shorter runs are cheaper stepped.
    constexpr uint64_t kStepUpTo = 4096;
    if (count < uint64_t(kWords)) {
        for (uint64_t i = 0; i < count; ++i) next();
        return;
    }
    if (count <= kStepUpTo || count >> kPowers) {
        // Stepped along a line instead of round the ring: value n is the sum of values n - 31 and
        // n - 3, the line starting with the ring's words oldest first and keeping its last 31
        // when it is full.
        constexpr size_t kLine = 512;
        std::array<uint32_t, kWords + kLine> line;
        for (int j = 0; j < kWords; ++j) line[size_t(j)] = words_[size_t((front_ + j) % kWords)];
        // The three newest values ride in registers: a vectorized loop would read each value two
        // steps after storing it, straddling two stores, which the store buffer cannot forward.
        static_assert(kSeparation == 3);
        for (uint64_t left = count; left > 0;) {
            const size_t n = size_t(std::min<uint64_t>(left, kLine));
            uint32_t a = line[kWords - 3], b = line[kWords - 2], c = line[kWords - 1];
            for (size_t k = 0; k < n; ++k) {
                const uint32_t value = line[k] + a;
                line[kWords + k] = value;
                a = b;
                b = c;
                c = value;
            }
            std::copy(line.begin() + ptrdiff_t(n), line.begin() + ptrdiff_t(n) + kWords, line.begin());
            left -= n;
        }
        std::copy(line.begin(), line.begin() + kWords, words_.begin());
        front_ = 0;
        rear_ = kWords - kSeparation;
        return;
    }
    Words v;
    for (int j = 0; j < kWords; ++j) v[j] = words_[size_t((front_ + j) % kWords)];
    const std::vector<Matrix>& powers = stepPowers();
    for (int p = 0; p < kPowers; ++p)
        if ((count >> p) & 1) v = apply(powers[size_t(p)], v);
    words_ = v;
    front_ = 0;
    rear_ = kWords - kSeparation;
}

}  // namespace q3::light
