// The sequence q3map2's Random() draws from: the GNU C library's rand() (its additive feedback
// generator of 31 words, TYPE_3), which q3map2 seeds once with srand(0), the same as seed 1.
// q3map2 shares that one sequence among the sun and light jitter made while it creates its lights
// and the nudges of the grid points that start in solid. With -threads 1 it draws in a fixed
// order, which drawing from this class in the same order reproduces.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

namespace q3::light {

class CLibraryRandom {
public:
    static constexpr int32_t kMax = 2147483647;  // RAND_MAX

    explicit CLibraryRandom(uint32_t seed = 1) {
        // Seed 0 is taken as 1; the other words follow by the minimal standard generator
        // (16807 x mod 2^31 - 1, Schrage's method), then 310 outputs are discarded.
        int32_t word = seed == 0 ? 1 : static_cast<int32_t>(seed);
        words_[0] = static_cast<uint32_t>(word);
        for (size_t i = 1; i < words_.size(); ++i) {
            const int32_t hi = word / 127773;
            const int32_t lo = word % 127773;
            word = 16807 * lo - 2836 * hi;
            if (word < 0) word += kMax;
            words_[i] = static_cast<uint32_t>(word);
        }
        front_ = kSeparation;
        rear_ = 0;
        for (int i = 0; i < 10 * kWords; ++i) next();
    }

    // rand(): uniform in [0, RAND_MAX].
    int32_t next() {
        words_[front_] += words_[rear_];
        const int32_t result = static_cast<int32_t>(words_[front_] >> 1);
        front_ = front_ + 1 == kWords ? 0 : front_ + 1;
        rear_ = rear_ + 1 == kWords ? 0 : rear_ + 1;
        return result;
    }

    // q3map2's Random(): rand() as a float times the float 1 / RAND_MAX, in [0, 1].
    float unit() { return static_cast<float>(next()) * (1.0f / static_cast<float>(kMax)); }

    // As many next() calls; long runs jump ahead (the words evolve linearly, modulo 2^32).
    void discard(uint64_t count);

private:
    static constexpr int kWords = 31;
    static constexpr int kSeparation = 3;
    std::array<uint32_t, kWords> words_{};
    int front_ = 0;
    int rear_ = 0;
};

}  // namespace q3::light
