// A small fixed-seed generator (SplitMix64) for the jitter of light samples: the same seed always
// gives the same sequence on every platform, so light lists are reproducible.
#pragma once

#include <cstdint>

namespace q3::light {

struct SplitMix {
    uint64_t state;
    explicit SplitMix(uint64_t seed) : state(seed) {}

    uint64_t next() {
        uint64_t z = (state += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    // Uniform in [0, 1).
    float unit() { return static_cast<float>(next() >> 40) * (1.0f / 16777216.0f); }
};

}  // namespace q3::light
