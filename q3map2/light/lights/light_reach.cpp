#include "light_reach.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace q3::light {

LightReach::LightReach(std::span<const Light> lights, std::span<const float> envelopes)
    : lights_(lights), envelopes_(envelopes) {
    if (envelopes.size() != lights.size()) throw std::logic_error("LightReach: one envelope per light expected");
    constexpr float kInf = std::numeric_limits<float>::infinity();
    for (int k = 0; k < 3; ++k) {
        lo_[k].resize(lights.size());
        hi_[k].resize(lights.size());
    }
    for (size_t i = 0; i < lights.size(); ++i) {
        const Light& light = lights[i];
        const float envelope = envelopes[i];
        const bool unbounded = light.type == LightType::Sun || !std::isfinite(envelope) || !std::isfinite(light.origin.x) ||
                               !std::isfinite(light.origin.y) || !std::isfinite(light.origin.z);
        for (int k = 0; k < 3; ++k) {
            lo_[k][i] = unbounded ? -kInf : light.origin[k] - envelope - 1.0f;
            hi_[k][i] = unbounded ? kInf : light.origin[k] + envelope + 1.0f;
        }
    }
}

void LightReach::reaching(const Bounds& bounds, std::vector<uint32_t>& out) const {
    out.clear();
    const size_t n = lights_.size();
    const float* lx = lo_[0].data(), *ly = lo_[1].data(), *lz = lo_[2].data();
    const float* hx = hi_[0].data(), *hy = hi_[1].data(), *hz = hi_[2].data();
    // Boxes a block at a time into flags (a loop the compiler runs several lights at a time),
    // then the exact test for the lights whose box meets the bounds.
    constexpr size_t kBlock = 256;
    uint8_t meets[kBlock];
    for (size_t first = 0; first < n; first += kBlock) {
        const size_t count = std::min(kBlock, n - first);
        for (size_t j = 0; j < count; ++j) {
            const size_t i = first + j;
            meets[j] = uint8_t((lx[i] <= bounds.maxs.x) & (hx[i] >= bounds.mins.x) & (ly[i] <= bounds.maxs.y) &
                               (hy[i] >= bounds.mins.y) & (lz[i] <= bounds.maxs.z) & (hz[i] >= bounds.mins.z));
        }
        for (size_t j = 0; j < count; ++j)
            if (meets[j] && lightReachesBounds(lights_[first + j], bounds, envelopes_[first + j]))
                out.push_back(uint32_t(first + j));
    }
}

}  // namespace q3::light
