// The WORLDLIGHTS lump of `-light -worldlights` (docs/world-lights-format.md): the map's point, spot
// and sun lights as records a runtime evaluates to the direct light the SH grid holds for them.
#pragma once

#include <optional>
#include <span>
#include <vector>

#include "lights.h"
#include "world_lights.h"

namespace q3 {
class Log;
}

namespace q3::light {

struct LightContext;

// What, beside the light itself, shapes the record of a light.
struct WorldLightSettings {
    float gridScale = 1;     // -gridscale: the SH grid's values are scaled by it
    bool shGrid = false;     // an SH grid is written in this run
    bool sunOnly = false;    // -sunonly: only suns reach the grids
    bool forceFast = false;  // -fast / -faster / -fastgrid: every light ends at its envelope in the grids
    bool outOfShGrid = false;  // -shnoworldlights: the SH grid leaves the listed lights' direct light out
};

struct LightOptions;
WorldLightSettings worldLightSettings(const LightOptions& options);

// The record of one light; nullopt for lights a record cannot stand for (area lights, the suns of a
// sky dome, which are sky ambient) and for lights that add nothing to the grids (spawnflags 16, no
// positive intensity, empty envelope).
std::optional<sh::WorldLight> worldLightRecord(const Light& light, const WorldLightSettings& settings);

// Whether the SH grid leaves out the direct light of `light` (it is listed, with -shnoworldlights).
bool keptOutOfShGrid(const Light& light, const WorldLightSettings& settings);

// Records of every light that has one, in light order.
std::vector<sh::WorldLight> worldLightRecords(std::span<const Light> lights, const WorldLightSettings& settings);

// With -worldlights: sets the BSPX lump WORLDLIGHTS of ctx.bsp from ctx.lights (replacing an older
// one in its place). Without it: removes a lump an earlier run left, which no longer matches.
void attachWorldLights(LightContext& ctx, Log& log);

}  // namespace q3::light
