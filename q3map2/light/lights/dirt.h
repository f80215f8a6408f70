// Dirt mapping (q3map2 -dirty): ambient occlusion that darkens luxels by how close the geometry
// around them is. Each sample casts 48 rays in a cone of 88 degrees around its normal plus one along
// it; each ray that meets a surface within `depth` adds 1 - distance/depth, and
//   dirt = 1 - min(1, min(1, (sum / 49)^gain) * scale)
// multiplies the luxel. Rays that reach sky do not darken (q3map2's ordered mode counted them; see
// NetRadiant-custom issue 101). The factors of a raw lightmap are smoothed over 3x3 neighbours.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "bsp_tree.h"
#include "hit_scene.h"
#include "light_contribution.h"
#include "light_options.h"
#include "lightmap_filter.h"

namespace q3::light {

struct DirtSettings {
    int mode = 0;         // 0 ordered cone, 1 random directions in the same cone
    float depth = 128;    // ray length
    float scale = 1;
    float gain = 1;       // exponent
    bool debug = false;   // -dirtdebug: the luxel becomes dirt * 255 grey
};

DirtSettings dirtSettingsFromOptions(const LightOptions& options);

// The 48 ordered cone directions around +z (16 azimuths x 3 elevations within 88 degrees).
const std::vector<Vec3>& dirtConeDirections();

// q3map2's DEFAULT_INHIBIT_RADIUS: dirt rays of luxels and vertexes pass surfaces this close.
constexpr float kDirtInhibitRadius = 1.5f;

// Triangles whose whole back, half a unit behind them (Quake 3 triangles wind clockwise seen from
// the front), lies in structural solid. A dirt ray that meets one from the front enters that solid
// just past it, where the BSP walk already stops it, so the rays the walk finds open need not test
// them (but for grazing or ending within that half unit, which changes nothing measurable).
SolidBackedTest dirtSolidBacked(const BspTree& tree);

// Dirt factor (0 black .. 1 untouched) of one sample. `seed` drives the random directions of mode 1
// (the same seed always gives the same directions); surfaces closer than `ignoreNear` do not count.
// With `tree`, a ray that enters structural solid is stopped where it enters, even within
// `ignoreNear` and behind nearer surfaces (q3map2 tests the BSP's solid leaves before surfaces).
// `skyNear` false says that no sky triangle's box (HitScene::skyTriangleBoxes) lies within the
// depth plus kDirtSkyReach of `origin`, so that no ray needs to look for sky before its solid.
float dirtForSample(Vec3 origin, Vec3 normal, const HitScene& scene, const DirtSettings& settings, uint64_t seed,
                    float ignoreNear = kDirtInhibitRadius, const BspTree* tree = nullptr, bool skyNear = true);
// How far beyond the dirt depth a ray still looks for a sky face in front of the solid it enters.
constexpr float kDirtSkyReach = 2.0f;

// Seed of a sample's random directions, from its position (independent of thread scheduling).
uint64_t dirtSeed(Vec3 origin);

// Dirt of every luxel of a raw lightmap (width x height, row-major `points`; nullopt = unmapped,
// which gets 0). `noDirty` (q3map_noDirty) gives 1 everywhere. Then each mapped luxel takes the mean
// of itself and its mapped 3x3 neighbours with dirt > 0, as q3map2's smoothing. With a non-empty
// `wanted` (one byte per luxel), luxels it leaves unmarked are taken as 1 before smoothing, so only
// marked luxels whose neighbours are all marked keep their true factor (dirtWantedLuxels marks so
// that this covers every luxel the factors can change).
std::vector<float> dirtForLightmap(const std::vector<std::optional<SamplePoint>>& points, int width, int height,
                                   const HitScene& scene, const DirtSettings& settings, bool noDirty,
                                   const BspTree* tree = nullptr, std::span<const uint8_t> wanted = {});

// The luxels whose dirt can change `image`: those within one luxel (the smoothing's reach) of a
// luxel that is not black. Dirt multiplies, so a black luxel stays black whatever its factor.
std::vector<uint8_t> dirtWantedLuxels(const LuxelImage& image);

// Multiplies every luxel by its dirt (or, with settings.debug, replaces it by dirt * 255 grey).
void applyDirt(LuxelImage& image, const std::vector<float>& dirt, bool debug);

}  // namespace q3::light
