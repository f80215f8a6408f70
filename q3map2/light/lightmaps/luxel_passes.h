// The per-raw-lightmap passes that run after every light has been added to a lightmap's luxels and
// before the final neighbour fill, in q3map2's order: floodlight is added (the global one, then the
// surface shader's q3map_floodLight), then the dirt factor multiplies everything (q3map_noDirty
// surfaces keep their light). Prepared once per compile; applied to each raw lightmap read-only.
// A shader's q3map_floodLight lights its surfaces on its own; q3map2 computes it but adds it only
// when the global floodlight is on as well, which makes the directive look broken.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "dirt.h"
#include "floodlight.h"
#include "hit_scene.h"

namespace q3 {
class Log;
}

namespace q3::light {

struct LightContext;

struct LuxelPasses {
    std::unique_ptr<HitScene> scene;
    const BspTree* tree = nullptr;  // structural solid for dirt rays (null: no node tree)
    bool dirty = false;
    DirtSettings dirt;
    std::optional<FloodlightSettings> globalFlood;
    std::vector<uint8_t> noDirty;                              // per BSP shader: q3map_noDirty
    std::vector<std::optional<FloodlightSettings>> shaderFlood;  // per BSP shader: q3map_floodLight
};

// nullptr when neither dirt nor any floodlight (option, worldspawn key or shader) is in use.
// Builds the nearest-hit scene from ctx.surfaces. Throws CompileError on a malformed _floodlight.
std::unique_ptr<LuxelPasses> prepareLuxelPasses(const LightContext& ctx, Log& log);

// Floodlight then dirt on the super luxels of one raw lightmap (`points` as the image, nullopt =
// no sample point).
void applyLuxelPasses(const LuxelPasses& passes, int shaderNum, LuxelImage& image,
                      const std::vector<std::optional<SamplePoint>>& points);

}  // namespace q3::light
