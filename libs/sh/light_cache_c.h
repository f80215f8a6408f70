/* C interface of the light cache (light_cache.h, docs/lightcache.md). No function throws or
 * aborts: failures return NULL / zeros and a one-line message. Coefficients are 27 floats,
 * coefficient-major (coeffs[3*i + channel]) like sh_grid_runtime_c.h. */
#ifndef Q3SH_LIGHT_CACHE_C_H
#define Q3SH_LIGHT_CACHE_C_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

#define Q3SH_MAX_LOCAL_LIGHTS 4

typedef struct q3sh_lightcache q3sh_lightcache;

typedef struct q3sh_local_light {
    unsigned index;     /* record index in the WORLDLIGHTS lump */
    float arriving[3];  /* light arriving at the query position, before the incidence term */
    /* The record packed for docs/glsl/world_lights.glsl: five vec4 (originRadius,
     * intensityFalloff, directionWeight, falloffConstants, coneType). */
    float gpu[20];
} q3sh_local_light;

typedef struct q3sh_lightcache_result {
    float coeffs[27]; /* grid sample plus the reachable lights that are not local, as SH */
    int localCount;   /* 0..4, strongest first */
    q3sh_local_light local[Q3SH_MAX_LOCAL_LIGHTS];
    int cluster;                 /* cluster of the query position, -1 outside the map or in solid */
    unsigned projectedCount;     /* lights added to coeffs */
    unsigned occludedCount;      /* lights traced, found blocked and dropped */
} q3sh_lightcache_result;

/* Loads the SH grid, the WORLDLIGHTS lump and the BSP tree, brushes and visibility of a BSP image
 * in memory (copied; `bsp` may be freed afterwards). On failure returns NULL and, when
 * errorSize > 0, writes a NUL-terminated one-line message to `error`. */
q3sh_lightcache* q3sh_lightcache_load(const unsigned char* bsp, size_t size, char* error, size_t errorSize);
void q3sh_lightcache_free(q3sh_lightcache* cache);

/* Number of WORLDLIGHTS records loaded. */
unsigned q3sh_lightcache_light_count(const q3sh_lightcache* cache);

/* The lighting of a point: maxLocal (0..4) lights to shade directly, the rest in the SH probe.
 * A NULL cache or position gives zeros and no lights. */
void q3sh_lightcache_query(const q3sh_lightcache* cache, const float position[3], int maxLocal,
                           q3sh_lightcache_result* out);

/* Irradiance of record `index` at a point on a surface with unit normal (no occlusion), what
 * worldLightIrradiance computes in GLSL. An index out of range gives zeros. */
void q3sh_lightcache_eval_light(const q3sh_lightcache* cache, unsigned index, const float point[3],
                                const float normal[3], float rgb[3]);

#ifdef __cplusplus
}
#endif

#endif
