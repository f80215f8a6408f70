// The light cache's C interface: thin wrappers that catch everything so no exception crosses into C.
#include "light_cache_c.h"

#include <cstring>

#include "c_api_support.h"
#include "light_cache.h"
#include "world_lights_glsl.h"

struct q3sh_lightcache {
    q3::sh::LightCache cache;
};

extern "C" {

q3sh_lightcache* q3sh_lightcache_load(const unsigned char* bsp, size_t size, char* error, size_t errorSize) {
    return q3::sh::capi::loadHandle<q3sh_lightcache>(
        bsp, size, error, errorSize, "the light cache",
        [](q3sh_lightcache& h, const unsigned char* b, size_t n) { return h.cache.loadFromBsp(b, n); });
}

void q3sh_lightcache_free(q3sh_lightcache* cache) { delete cache; }

unsigned q3sh_lightcache_light_count(const q3sh_lightcache* cache) {
    return cache != nullptr ? unsigned(cache->cache.lights().size()) : 0u;
}

void q3sh_lightcache_query(const q3sh_lightcache* cache, const float position[3], int maxLocal,
                           q3sh_lightcache_result* out) {
    if (out == nullptr) return;
    std::memset(out, 0, sizeof *out);
    out->cluster = -1;
    if (cache == nullptr || position == nullptr) return;
    try {
        const q3::sh::LightCacheResult r = cache->cache.query(position, maxLocal);
        std::memcpy(out->coeffs, r.probe.coeffs, sizeof out->coeffs);
        out->localCount = r.localCount;
        for (int i = 0; i < r.localCount; ++i) {
            out->local[i].index = r.local[i].index;
            std::memcpy(out->local[i].arriving, r.local[i].arriving.data(), sizeof out->local[i].arriving);
            const q3::sh::WorldLightGpu gpu = q3::sh::packWorldLightGpu(cache->cache.lights()[r.local[i].index]);
            static_assert(sizeof gpu == sizeof out->local[i].gpu);
            std::memcpy(out->local[i].gpu, &gpu, sizeof gpu);
        }
        out->cluster = r.cluster;
        out->projectedCount = r.projectedCount;
        out->occludedCount = r.occludedCount;
    } catch (...) {  // only bad_alloc can escape the query: answer with no light rather than abort
        std::memset(out, 0, sizeof *out);
        out->cluster = -1;
    }
}

void q3sh_lightcache_eval_light(const q3sh_lightcache* cache, unsigned index, const float point[3],
                                const float normal[3], float rgb[3]) {
    if (rgb == nullptr) return;
    rgb[0] = rgb[1] = rgb[2] = 0;
    if (cache == nullptr || point == nullptr || normal == nullptr || index >= cache->cache.lights().size()) return;
    const std::array<float, 3> e = q3::sh::evaluateWorldLight(cache->cache.lights()[index], {point[0], point[1], point[2]},
                                                              {normal[0], normal[1], normal[2]});
    std::copy(e.begin(), e.end(), rgb);
}

}  // extern "C"
