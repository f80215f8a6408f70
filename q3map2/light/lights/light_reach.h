// Which lights of a list may reach a box: lightReachesBounds for every light, without testing
// every light's sphere. Each light's envelope box (grown by a unit, which covers the rounding of
// its corners) is kept in flat arrays that one pass over them tests a box against; only the lights
// whose box meets it take the exact test. The answer is lightReachesBounds's, in light order.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "lights.h"

namespace q3::light {

class LightReach {
public:
    LightReach() = default;
    // `envelopes[i]` is lightEnvelope of lights[i] (one per light); both must outlive this index.
    LightReach(std::span<const Light> lights, std::span<const float> envelopes);

    // The indices of the lights that reach `bounds`, ascending, written to `out`.
    void reaching(const Bounds& bounds, std::vector<uint32_t>& out) const;

private:
    std::span<const Light> lights_;
    std::span<const float> envelopes_;
    std::vector<float> lo_[3], hi_[3];  // envelope boxes; unbounded lights span everything
};

}  // namespace q3::light
