// One lighting pass over one lightmapped surface: lay it out, light its super luxels with a list
// of lights (sub-samples at light/shadow edges, per-light box filter), split by light style, and
// average them into BSP luxels. The direct pass adds the world ambient, floodlight and dirt;
// radiosity passes light the same luxels with the emitters made from the previous pass.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "bspfile.h"
#include "light_contribution.h"
#include "light_reach.h"
#include "lightmap_filter.h"
#include "lightmap_layout.h"
#include "lights.h"
#include "vec3.h"

namespace q3::light {

class BspTree;
struct LightContext;
struct LightingEnv;
struct LuxelPasses;

constexpr int kMaxLightmapStyles = 4;  // MAX_LIGHTMAPS: style 0 and three others per raw lightmap

// The light of one style on a raw lightmap, in BSP luxels (linear, legacy units 0..255+).
struct LightmapLayer {
    int style = 0;
    std::vector<Vec3> color;
};

struct SurfacePass {
    std::span<const Light> lights;
    bool direct = true;   // the first pass: world ambient, floodlight and dirt
    bool deluxe = false;  // also sum the direction the style-0 light comes from
    // lightEnvelope of each light, asked once per pass instead of once per surface and light;
    // empty: computed where needed.
    std::span<const float> envelopes = {};
    // Which of `lights` reach a box (built from `envelopes`); null: every light is tested.
    const LightReach* reach = nullptr;
    // Keep the sample points in the result (SurfaceLight::samples), for the passes that follow.
    bool keepSamples = false;
};

// Where a raw lightmap's super luxels are sampled, as its first pass placed them: a later pass of
// the same lightmap lights the same points (its layout is SurfaceLight::layout).
struct LuxelSamples {
    std::vector<std::optional<SamplePoint>> points;  // per super luxel; nullopt: in solid or unmapped
    std::vector<Vec3> normals;                       // per super luxel
    std::vector<LuxelState> states;
};

struct SurfaceLight {
    bool ok = false;
    int surfaceNum = -1;
    RawLightmap layout;
    int width = 0, height = 0;          // BSP luxels
    std::vector<uint8_t> used;          // per BSP luxel: 0 = nothing reached it
    std::vector<LightmapLayer> layers;  // [0] is style 0; then styles in the order lights met them
    // -deluxe: per BSP luxel, the sum of the style-0 light directions weighted by brightness.
    std::vector<Vec3> directions;
    std::vector<Vec3> normals;          // per BSP luxel: mean luxel normal (deluxe fallback and frame)
    uint64_t luxelCount = 0;
    uint64_t styleLimitHits = 0;        // lights dropped: the surface already had four styles
    std::shared_ptr<const LuxelSamples> samples;  // with SurfacePass::keepSamples

    const LightmapLayer* layer(int style) const;
    LightmapLayer& layerFor(int style);  // creates the layer (zero light) when missing
};

// For every surface, the clusters of the leafs whose surface lists hold it and whose stored bounds
// touch the surface's bounds (vertexes moved by `offsets`, per surface) (sorted, unique).
std::vector<std::vector<int>> surfaceClusterLists(const bsp::Bsp& bsp, std::span<const Vec3> offsets);
// q3map2 ClusterForPointExtFilter on a point's cluster: kept when it is one of `clusters` or sees
// one of them (or when `clusters` is empty), else -1.
int clusterSeenBySurface(const BspTree& tree, int cluster, std::span<const int> clusters);

// The layout options of the stage (from -super, -samplescale, -lightmapsize, ...).
LayoutOptions layoutOptionsFor(const LightContext& ctx, Log& log);

// Lights one raw lightmap, the surfaces `surfaceNums` share (q3map2's SetupSurfaceLightmaps groups;
// one surface alone most often), for one pass. `passes` (floodlight, dirt) apply to the direct pass
// only.
// `previous`, when it holds the samples of an earlier pass of the same lightmap, spares the layout
// and the sample points.
SurfaceLight lightSurface(const LightContext& ctx, const LightingEnv& env, std::span<const int> surfaceNums,
                          const LayoutOptions& layoutOptions, const LuxelPasses* passes, const SurfacePass& pass,
                          const SurfaceLight* previous = nullptr);

}  // namespace q3::light
