// The sequence glibc's rand() yields when never seeded (seed 1, the additive feedback generator
// of degree 31). q3map2 draws its -maxarea retries from rand(); an owned generator gives the
// same numbers without global state.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

namespace q3::bspstage {

class LibcRandom {
public:
    explicit LibcRandom(uint32_t seed = 1) {
        std::array<int32_t, 34> r{};
        r[0] = int32_t(seed);
        for (int i = 1; i < 31; ++i) {
            // 16807 * r mod (2^31 - 1), kept positive.
            int64_t v = (16807LL * r[std::size_t(i - 1)]) % 2147483647LL;
            if (v < 0) v += 2147483647LL;
            r[std::size_t(i)] = int32_t(v);
        }
        for (int i = 31; i < 34; ++i) r[std::size_t(i)] = r[std::size_t(i - 31)];
        for (int i = 0; i < 34; ++i) state_[std::size_t(i)] = uint32_t(r[std::size_t(i)]);
        position_ = 34;
        for (int i = 34; i < 344; ++i) step();  // glibc discards the first 310 outputs
    }

    // The next value in [0, 2^31).
    int next() { return int(step() >> 1); }

private:
    // r[i] = r[i - 31] + r[i - 3] (mod 2^32), over a ring of the last 34 values.
    uint32_t step() {
        const uint32_t v = state_[(position_ - 31) % 34] + state_[(position_ - 3) % 34];
        state_[position_ % 34] = v;
        ++position_;
        return v;
    }

    std::array<uint32_t, 34> state_{};
    uint64_t position_ = 0;
};

}  // namespace q3::bspstage
