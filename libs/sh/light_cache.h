// Engine-side light cache for moving models, after Source's: loaded once from a BSP image (the SH
// grid, the WORLDLIGHTS records, the BSP tree, opaque brushes and visibility), it answers "how is
// this point lit" with the grid's probe plus the strongest few lights that reach the point, which
// the engine shades per vertex or pixel with evaluateWorldLight (or its GLSL twin). See
// docs/lightcache.md. No dependencies, no exceptions besides std::bad_alloc.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "bsp_collision.h"
#include "sh_grid_runtime.h"
#include "world_lights.h"

namespace q3::sh {

constexpr int kMaxLocalLights = 4;
// Sun rays are traced this far towards the sun: beyond the +-65536 world of the BSP format.
constexpr float kSunTraceDistance = 131072.0f;

struct LocalLight {
    uint32_t index = 0;                // record index in the WORLDLIGHTS lump (LightCache::lights())
    std::array<float, 3> arriving{};   // worldLightArriving at the query position
};

struct LightCacheResult {
    // The grid sample plus, as directional light, every reachable light that is neither in the
    // grid already nor among the local lights. Coefficient-major, like GridPointSH.
    GridPointSH probe{};
    int localCount = 0;
    LocalLight local[kMaxLocalLights];  // strongest first
    int32_t leaf = -1;
    int32_t cluster = -1;
    uint32_t projectedCount = 0;  // lights added to the probe
    uint32_t occludedCount = 0;   // lights traced and found blocked, dropped
};

class LightCache {
public:
    // Loads a BSP image held in memory (copied as needed, not kept). Returns an empty string or one
    // line prefixed with `name`. A map without a WORLDLIGHTS lump loads with no lights (queries
    // return the grid sample), a map without any grid with a zero probe.
    std::string loadFromBsp(const uint8_t* bsp, size_t size, const std::string& name = "");

    const GridRuntime& grid() const { return grid_; }
    const BspCollision& collision() const { return world_; }
    const std::vector<WorldLight>& lights() const { return lights_; }

    // The lighting of a point: see docs/lightcache.md for the selection. maxLocal (0..4) is how
    // many lights the caller shades itself; the others reaching the point go into the probe.
    LightCacheResult query(const float position[3], int maxLocal = kMaxLocalLights) const;

    // Whether the segment from `position` to the light is free of opaque brushes (suns: the ray
    // towards the sun leaves the world or enters a sky brush first).
    bool reaches(const WorldLight& light, const float position[3]) const;

private:
    GridRuntime grid_;
    BspCollision world_;
    std::vector<WorldLight> lights_;
};

// Rec. 709 luminance: the strength by which lights are ranked.
float luminance(const std::array<float, 3>& rgb);

}  // namespace q3::sh
