// Light records of the WORLDLIGHTS lump (see world_lights_export.h).
#include "world_lights_export.h"

#include <cmath>

#include "bspfile.h"
#include "light_context.h"
#include "log.h"
#include "light_text.h"

namespace q3::light {
namespace {

constexpr float kMinDistance = 16.0f;       // q3map2 clamps light distances to this
constexpr float kSpotFadeWidth = 32.0f;     // q3map2 spot cones fade over their last 32 units
constexpr float kLinearScale = 1.0f / 8000.0f;
constexpr float kLargestRadius = 1.0e6f;    // the format's bound on distances

std::array<float, 3> toArray(Vec3 v) { return {v.x, v.y, v.z}; }

// Controlled model: brightness and colour as the value's scale, falloff, cone and incidence constants.
sh::WorldLight controlledRecord(const Light& light, const ControlledParams& p, float gridScale) {
    sh::WorldLight r;
    r.intensity = toArray(light.color * (p.brightness * gridScale));
    if (light.type == LightType::Sun) {
        r.falloff = sh::WorldLightFalloff::Parallel;
        return r;  // suns force an incidence weight of 1
    }
    r.falloff = sh::WorldLightFalloff::Controlled;
    r.falloffConstants = {p.falloffStart, p.falloffEnd, p.falloffCurvature, 0};
    if (light.type == LightType::Spot) r.cone = {p.angleHotspot * 0.5f, p.anglePenumbra * 0.5f, p.sphericalAmbient, 0};
    r.incidenceWeight = p.dotProductWeight;
    r.radius = p.falloffEnd;
    return r;
}

// q3map2 model; nullopt when the light adds nothing to a grid point.
std::optional<sh::WorldLight> q3map2Record(const Light& light, const WorldLightSettings& settings) {
    if (!(light.photons > 0)) return std::nullopt;  // the grids drop lights whose value is not positive
    sh::WorldLight r;
    if (light.type == LightType::Sun) {
        r.falloff = sh::WorldLightFalloff::Parallel;
        r.intensity = toArray(light.color * (light.photons / 255.0f * settings.gridScale));
        return r;
    }
    // The value before the colour: photons / D^2, or photons / 8000 * (1 - D * rate) when linear.
    const float scale = light.linear ? light.photons * kLinearScale : light.photons;
    r.falloff = light.linear ? sh::WorldLightFalloff::Linear : sh::WorldLightFalloff::InverseSquare;
    r.intensity = toArray(light.color * (scale / 255.0f * settings.gridScale));
    const bool fast = light.fast || settings.forceFast;
    const float cutoff = fast ? std::max(0.f, light.falloffTolerance / scale) : 0.f;
    r.falloffConstants = {kMinDistance, light.extraDist, cutoff, light.linear ? light.fade / scale : 0.f};
    if (light.type == LightType::Spot) r.cone = {light.radiusByDist, kSpotFadeWidth, 0, 0};
    const float envelope = lightEnvelope(light, settings.forceFast);
    if (std::isfinite(envelope)) {
        if (!(envelope > 0)) return std::nullopt;
        if (envelope <= kLargestRadius) r.radius = envelope;
    }
    return r;
}

}  // namespace

WorldLightSettings worldLightSettings(const LightOptions& options) {
    WorldLightSettings settings;
    settings.gridScale = options.gridScale;
    settings.shGrid = options.sh && !options.noGrid;
    settings.sunOnly = options.sunOnly;
    settings.forceFast = options.fast || options.faster || options.fastGrid;
    settings.outOfShGrid = options.shNoWorldLights;
    return settings;
}

std::optional<sh::WorldLight> worldLightRecord(const Light& light, const WorldLightSettings& settings) {
    if (light.type == LightType::Area || light.skyDome || !light.affectsGrid) return std::nullopt;
    std::optional<sh::WorldLight> record = light.controlled
                                               ? std::optional(controlledRecord(light, *light.controlled, settings.gridScale))
                                               : q3map2Record(light, settings);
    if (!record) return std::nullopt;
    sh::WorldLight& r = *record;
    const bool sun = light.type == LightType::Sun;
    r.type = sun ? sh::WorldLightType::Sun
                 : light.type == LightType::Spot ? sh::WorldLightType::Spot : sh::WorldLightType::Point;
    r.style = light.style;
    r.cluster = sun ? -1 : light.cluster;
    if (!sun) r.origin = toArray(light.origin);
    if (sun || light.type == LightType::Spot) r.direction = toArray(light.normal);
    // The SH grid holds style 0 only; -sunonly keeps every other light out of it.
    const bool inGrid = settings.shGrid && !settings.outOfShGrid && light.style == 0 && (sun || !settings.sunOnly);
    r.flags = inGrid ? sh::kWorldLightInShGrid : 0u;
    if (!sh::checkWorldLight(r).empty()) return std::nullopt;  // values no map light has (e.g. beyond 1e6 units)
    return record;
}

bool keptOutOfShGrid(const Light& light, const WorldLightSettings& settings) {
    return settings.outOfShGrid && worldLightRecord(light, settings).has_value();
}

std::vector<sh::WorldLight> worldLightRecords(std::span<const Light> lights, const WorldLightSettings& settings) {
    std::vector<sh::WorldLight> out;
    for (const Light& light : lights)
        if (std::optional<sh::WorldLight> r = worldLightRecord(light, settings)) out.push_back(*r);
    return out;
}

void attachWorldLights(LightContext& ctx, Log& log) {
    if (!ctx.options.worldLights) {
        if (ctx.bsp.removeBspx(sh::kWorldLightsLumpName)) log.info("removed the WORLDLIGHTS lump of an earlier run");
        return;
    }
    const WorldLightSettings settings = worldLightSettings(ctx.options);
    const std::vector<sh::WorldLight> records = worldLightRecords(ctx.lights, settings);
    // Area lights are never listed; the other lights that affect the grid should all be.
    size_t points = 0, spots = 0, suns = 0, areas = 0, domes = 0, eligible = 0;
    for (const Light& light : ctx.lights) {
        areas += light.type == LightType::Area;
        domes += light.skyDome;
        eligible += light.type != LightType::Area && !light.skyDome && light.affectsGrid;
    }
    for (const sh::WorldLight& r : records) {
        points += r.type == sh::WorldLightType::Point;
        spots += r.type == sh::WorldLightType::Spot;
        suns += r.type == sh::WorldLightType::Sun;
    }
    // Lights the format could hold but that got no record: they reach no point, or a value lies
    // outside what a record may carry (said once, so that a missing light is never silent).
    if (eligible > records.size())
        log.warning(strCat("WORLDLIGHTS: ", eligible - records.size(),
                           " lights not listed: they reach no point or carry values a record cannot hold"));
    std::vector<uint8_t> lump = sh::encodeWorldLights(records);
    log.info(strCat("WORLDLIGHTS: ", records.size(), " lights (", points, " point, ", spots, " spot, ", suns,
                    " sun), ", lump.size(), " bytes; ", areas, " area lights and ", domes, " sky dome suns not listed"));
    ctx.bsp.setBspx(sh::kWorldLightsLumpName, std::move(lump));
}

}  // namespace q3::light
