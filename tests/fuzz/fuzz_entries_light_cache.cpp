// The light cache under fuzzing: any BSP image loads or is refused with one line (and then keeps
// nothing); a loaded map answers queries at its lights, its origin and far away with at most four
// local lights, strongest first, each what worldLightArriving gives and never one the grid holds.
#include <cmath>

#include "fuzz_entries.h"
#include "light_cache.h"

namespace q3::fuzz {
namespace {

void checkQuery(const sh::LightCache& cache, const std::array<float, 3>& p) {
    const sh::LightCacheResult r = cache.query(p.data());
    if (r.localCount < 0 || r.localCount > sh::kMaxLocalLights) throw PropertyViolation("local light count out of range");
    float previous = INFINITY;
    for (int i = 0; i < r.localCount; ++i) {
        const sh::LocalLight& local = r.local[i];
        if (local.index >= cache.lights().size()) throw PropertyViolation("a local light index past the records");
        const sh::WorldLight& light = cache.lights()[local.index];
        if (light.flags & sh::kWorldLightInShGrid) throw PropertyViolation("a light of the SH grid returned as local");
        if (local.arriving != sh::worldLightArriving(light, p)) throw PropertyViolation("local light not as evaluated");
        const float strength = std::fabs(sh::luminance(local.arriving));
        if (strength > previous) throw PropertyViolation("local lights not strongest first");
        previous = strength;
    }
    if (r.leaf >= 0 && size_t(r.leaf) >= cache.collision().leafs.size()) throw PropertyViolation("leaf out of range");
}

}  // namespace

void fuzzLightCache(std::span<const uint8_t> input, const FuzzContext&) {
    sh::LightCache cache;
    const std::string error = cache.loadFromBsp(input.data(), input.size(), "fuzz.bsp");
    if (!error.empty()) {
        if (!error.starts_with("fuzz.bsp: ") || error.find('\n') != std::string::npos)
            throw PropertyViolation("a refused map without a one-line error: " + error);
        if (!cache.lights().empty() || !cache.collision().nodes.empty())
            throw PropertyViolation("a refused map left data behind");
        return;
    }
    checkQuery(cache, {0, 0, 0});
    checkQuery(cache, {1e5f, -1e5f, 3e4f});
    const size_t lights = std::min<size_t>(cache.lights().size(), 16);
    for (size_t i = 0; i < lights; ++i) {
        const auto& o = cache.lights()[i].origin;
        checkQuery(cache, {o[0] + 24, o[1] - 8, o[2] - 40});
    }
}

}  // namespace q3::fuzz
