/* Compiled as C: proves light_cache_c.h is a valid C header and the API is usable from C. */
#include "light_cache_c.h"

int q3sh_test_c_light_cache(const unsigned char* bsp, size_t size, const float position[3], unsigned* firstIndex,
                            char* error, size_t errorSize) {
    q3sh_lightcache_result result;
    q3sh_lightcache* cache = q3sh_lightcache_load(bsp, size, error, errorSize);
    if (cache == NULL) return -1;
    q3sh_lightcache_query(cache, position, Q3SH_MAX_LOCAL_LIGHTS, &result);
    if (result.localCount > 0) *firstIndex = result.local[0].index;
    q3sh_lightcache_free(cache);
    return result.localCount;
}
