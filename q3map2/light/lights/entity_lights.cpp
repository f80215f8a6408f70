// Light entities -> Light records: q3map2's model (CreateEntityLights) and the controlled model of
// specs/light-models.md.
#include <algorithm>
#include <cmath>

#include "entity_keys.h"
#include "lights.h"
#include "light_text.h"
#include "log.h"

namespace q3::light {
namespace {

constexpr int kMaxStyle = 254;  // 255 marks an unused style slot in the engine

bool isLightClass(std::string_view classname, bool* junior) {
    *junior = classname == "lightJunior";
    return *junior || classname.starts_with("light");
}

// Largest component becomes 1 (q3map2's ColorNormalize); black stays black.
Vec3 normalizeColor(Vec3 c) {
    float m = maxComponent(c);
    return m > 0 ? c / m : Vec3{};
}

const bsp::Entity* findTarget(const std::vector<bsp::Entity>& entities, const std::string& name) {
    for (const bsp::Entity& e : entities) {
        const std::string* tn = e.find("targetname");
        if (tn && *tn == name) return &e;
    }
    return nullptr;
}

constexpr std::string_view kControlledKeys[] = {"brightness",        "dot_product_weight", "falloff_start_dist",
                                                "falloff_end_dist",  "falloff_curvature",  "angle_hotspot",
                                                "angle_penumbra",    "spherical_ambient"};

bool usesControlledModel(const bsp::Entity& e) {
    return std::any_of(std::begin(kControlledKeys), std::end(kControlledKeys),
                       [&](std::string_view k) { return e.find(k) != nullptr; });
}

// Reads one controlled-model key, clamping it into [lo, hi] with a warning naming entity and key.
float readClamped(const bsp::Entity& e, std::string_view key, float fallback, float lo, float hi, int entityNum,
                  Log& log) {
    std::optional<float> v = floatKey(e, {key});
    if (!v) return fallback;
    float value = *v;
    if (!std::isfinite(value)) value = fallback;
    float clamped = std::clamp(value, lo, hi);
    if (clamped != value)
        log.warning(strCat("entity ", entityNum, ": key \"", key, "\" value ", value, " is out of range [", lo, ", ", hi, "], clamped to ", clamped));
    return clamped;
}

ControlledParams readControlledParams(const bsp::Entity& e, int entityNum, Log& log) {
    constexpr float kHuge = 1e30f;
    ControlledParams p;
    p.brightness = readClamped(e, "brightness", 1, -1, 1, entityNum, log);
    p.dotProductWeight = readClamped(e, "dot_product_weight", 0.5f, 0, 1, entityNum, log);
    p.falloffStart = readClamped(e, "falloff_start_dist", 0, 0, kHuge, entityNum, log);
    p.falloffEnd = readClamped(e, "falloff_end_dist", 300, 0, kHuge, entityNum, log);
    if (p.falloffEnd < p.falloffStart) {
        log.warning(strCat("entity ", entityNum, ": key \"falloff_end_dist\" ", p.falloffEnd, " is below falloff_start_dist, raised to ", p.falloffStart));
        p.falloffEnd = p.falloffStart;
    }
    p.falloffCurvature = readClamped(e, "falloff_curvature", 0.5f, 0, 1, entityNum, log);
    p.angleHotspot = readClamped(e, "angle_hotspot", 45, 0, 180, entityNum, log);
    p.anglePenumbra = readClamped(e, "angle_penumbra", 60, 0, 180, entityNum, log);
    if (p.anglePenumbra < p.angleHotspot) {
        log.warning(strCat("entity ", entityNum, ": key \"angle_penumbra\" ", p.anglePenumbra, " is below angle_hotspot, raised to ", p.angleHotspot));
        p.anglePenumbra = p.angleHotspot;
    }
    p.sphericalAmbient = readClamped(e, "spherical_ambient", 0, 0, 1, entityNum, log);
    return p;
}

Light makeControlledLight(const bsp::Entity& e, int entityNum, const std::vector<bsp::Entity>& targets,
                          bool junior, int style, Log& log) {
    Light light;
    light.entityNum = entityNum;
    light.controlled = readControlledParams(e, entityNum, log);
    light.origin = vecKey(e, {"origin"}).value_or(Vec3{});
    light.style = style;
    light.affectsSurfaces = !junior;
    light.affectsGrid = junior || !(intKey(e, {"spawnflags"}).value_or(0) & 16);
    for (std::string_view legacy : {"light", "_light", "radius", "_fade", "fade"})
        if (e.find(legacy))
            log.debug(strCat("entity ", entityNum, ": key \"", legacy, "\" ignored by a controlled-model light"));

    Vec3 color{1, 1, 1};
    if (std::optional<Vec3> c = vecKey(e, {"_color"})) {
        color = vmax(*c, Vec3{});
        float m = maxComponent(color);
        if (m <= 0) {
            log.warning(strCat("entity ", entityNum, ": key \"_color\" is black, using 1 1 1"));
            color = {1, 1, 1};
        } else if (m != 1) {
            log.warning(strCat("entity ", entityNum, ": key \"_color\" normalised so that its largest component is 1"));
            color = color / m;
        }
    }
    light.color = color;
    light.filterRadius = std::max(0.f, floatKey(e, {"_filterradius", "_filteradius", "_filter"}).value_or(0));

    const bsp::Entity* target = nullptr;
    if (const std::string* t = e.find("target")) target = findTarget(targets, *t);
    if (target) {
        Vec3 axis = vecKey(*target, {"origin"}).value_or(Vec3{}) - light.origin;
        light.normal = length(axis) > 0 ? normalize(axis) : Vec3{0, 0, -1};
        light.type = boolKey(e, {"_sun"}) ? LightType::Sun : LightType::Spot;
    } else if (boolKey(e, {"_sun"})) {
        log.warning(strCat("entity ", entityNum, ": sun light has no target, shining straight down"));
        light.normal = {0, 0, -1};
        light.type = LightType::Sun;
    } else {
        light.type = LightType::Point;
    }
    if (light.type == LightType::Sun) light.normal = -light.normal;  // suns store the direction towards the sun
    return light;
}

}  // namespace

WorldLighting readWorldLighting(const bsp::Entity& ws) {
    WorldLighting w;
    // q3map2 scales the ambient and minimum lights by the worldspawn _color as written: unlike a
    // light entity's colour it is not normalised (oacmpdm10's "0.87 0.87 0.5" with ambient 2 gives
    // 1.74 1.74 1.0, stored as 1 1 1, not 2 2 1).
    Vec3 color = vecKey(ws, {"_color"}).value_or(Vec3{1, 1, 1});
    if (length(color) == 0) color = {1, 1, 1};
    w.ambient = color * floatKey(ws, {"_ambient", "ambient"}).value_or(0);
    float minLight = floatKey(ws, {"_minlight"}).value_or(0);
    w.minLight = color * minLight;
    w.minVertexLight = color * floatKey(ws, {"_minvertexlight"}).value_or(minLight);
    w.minGridLight = color * floatKey(ws, {"_mingridlight"}).value_or(minLight);
    w.maxLight = std::clamp(floatKey(ws, {"_maxlight"}).value_or(255), 0.f, 255.f);
    w.noShaderSun = boolKey(ws, {"_noshadersun"});
    w.keepLights = boolKey(ws, {"_keepLights"});
    return w;
}

std::vector<Light> createEntityLights(const std::vector<bsp::Entity>& entities,
                                      const std::vector<bsp::Entity>& targets, const LightScales& scales,
                                      Log& log, const std::string& fileName, CLibraryRandom& random) {
    std::vector<Light> out;
    for (size_t i = 0; i < entities.size(); ++i) {
        const bsp::Entity& e = entities[i];
        bool junior = false;
        if (!isLightClass(e.classname(), &junior)) continue;
        const int entityNum = static_cast<int>(i);

        int style = intKey(e, {"_style", "style"}).value_or(0);
        if (style < 0 || style > kMaxStyle)
            throw CompileError(strCat(fileName, ": entity ", entityNum, ": invalid light style ", style));
        if (scales.noStyles) style = 0;

        if (usesControlledModel(e)) {
            out.push_back(makeControlledLight(e, entityNum, targets, junior, style, log));
            continue;
        }

        Light light;
        light.entityNum = entityNum;
        light.style = style;
        const int spawnflags = intKey(e, {"spawnflags"}).value_or(0);
        if (!scales.wolfLight) {
            light.linear = false;
            light.angleAttenuation = true;
            if (spawnflags & 1) {
                light.linear = true;
                light.angleAttenuation = false;
            }
            if (spawnflags & 2) light.angleAttenuation = false;
        } else {
            light.linear = true;
            light.angleAttenuation = false;
            if (spawnflags & 1) {
                light.linear = false;
                light.angleAttenuation = true;
            }
            if (spawnflags & 2) light.angleAttenuation = true;
        }
        if (spawnflags & 16) light.affectsGrid = false;
        if (junior) {
            light.affectsGrid = true;
            light.affectsSurfaces = false;
        }
        const bool unnormalized = (spawnflags & 32) != 0;

        light.fade = 1;
        if (light.linear) {
            light.fade = floatKey(e, {"fade"}).value_or(0);
            if (light.fade == 0) light.fade = 1;
        }
        light.angleScale = floatKey(e, {"_anglescale"}).value_or(0);
        if (light.angleScale != 0) light.angleAttenuation = true;

        light.origin = vecKey(e, {"origin"}).value_or(Vec3{});

        float intensity = floatKey(e, {"_light", "light"}).value_or(300);
        if (intensity == 0) intensity = 300;
        if (std::optional<float> scale = floatKey(e, {"scale"}); scale && *scale != 0) intensity *= *scale;

        const float deviance = std::max(0.f, floatKey(e, {"_deviance", "_deviation", "_jitter"}).value_or(0));
        const int numSamples = std::max(1, intKey(e, {"_samples"}).value_or(1));
        intensity /= static_cast<float>(numSamples);

        light.filterRadius = std::max(0.f, floatKey(e, {"_filterradius", "_filteradius", "_filter"}).value_or(0));
        if (std::optional<Vec3> c = vecKey(e, {"_color"}))
            light.color = unnormalized ? *c : normalizeColor(*c);
        light.extraDist = floatKey(e, {"_extradist"}).value_or(scales.extraDist);
        light.photons = intensity;
        light.type = LightType::Point;
        light.falloffTolerance = scales.falloffTolerance / static_cast<float>(numSamples);

        bool isPoint = true;
        if (const std::string* targetName = e.find("target")) {
            const bsp::Entity* target = findTarget(targets, *targetName);
            if (!target) {
                log.warning(strCat(fileName, ": light at (", static_cast<int>(light.origin.x), " ", static_cast<int>(light.origin.y), " ", static_cast<int>(light.origin.z), ") has missing target \"", *targetName, "\""));
            } else {
                isPoint = false;
                Vec3 axis = vecKey(*target, {"origin"}).value_or(Vec3{}) - light.origin;
                float dist = length(axis);
                light.normal = dist > 0 ? axis / dist : Vec3{};
                float radius = floatKey(e, {"radius"}).value_or(0);
                if (radius == 0) radius = 64;
                if (dist == 0) dist = 64;
                light.radiusByDist = (radius + 16) / dist;
                light.type = LightType::Spot;
                light.linear = false;  // spotlights are always inverse-square and angle attenuated
                light.angleAttenuation = true;
                light.fade = 1;

                if (boolKey(e, {"_sun"})) {
                    SunDirective sun;
                    sun.direction = -light.normal;
                    sun.color = light.color;
                    sun.intensity = intensity;  // already divided by the sample count (q3map2 quirk kept)
                    sun.devianceDeg = deviance;
                    sun.samples = numSamples;
                    sun.style = style;
                    sun.filterRadius = light.filterRadius;
                    appendSunLights(out, sun, -1, scales, random);
                    for (size_t k = out.size() - static_cast<size_t>(numSamples); k < out.size(); ++k)
                        out[k].entityNum = entityNum;
                    continue;
                }
                light.photons *= scales.spotScale;
            }
        }
        if (isPoint) light.photons *= scales.pointScale;
        light.fast = scales.fast || scales.fastPoint;

        // Jittered copies, three draws each (x, y, z), even with no deviance.
        out.push_back(light);
        for (int j = 1; j < numSamples; ++j) {
            Light copy = light;
            copy.origin.x += (random.unit() * 2 - 1) * deviance;
            copy.origin.y += (random.unit() * 2 - 1) * deviance;
            copy.origin.z += (random.unit() * 2 - 1) * deviance;
            out.push_back(copy);
        }
    }
    return out;
}

}  // namespace q3::light
