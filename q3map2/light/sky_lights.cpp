// Suns (q3map_sun, q3map_sunExt, entity _sun), sky domes (q3map_skyLight) and the sky index that
// lets each sun light only through the sky surfaces of its own shader.
#include <algorithm>
#include <cmath>

#include "light_random.h"
#include "lights.h"
#include "light_text.h"
#include "log.h"

namespace q3::light {
namespace {

constexpr float kSunDistance = 65536.0f * 8.0f;  // MAX_WORLD_COORD * 8
constexpr int kMaxSkies = 32;

Vec3 directionForSpherical(double azimuth, double elevation) {
    return {static_cast<float>(std::cos(azimuth) * std::cos(elevation)),
            static_cast<float>(std::sin(azimuth) * std::cos(elevation)), static_cast<float>(std::sin(elevation))};
}

}  // namespace

void appendSunLights(std::vector<Light>& out, const SunDirective& sun, int skyIndex, const LightScales& scales,
                     uint32_t seed) {
    const int samples = std::max(1, sun.samples);
    const float photons = sun.intensity / static_cast<float>(samples);
    const double deviance = degToRad(sun.devianceDeg);
    const Vec3 base = normalize(sun.direction);
    const double baseAzimuth = std::atan2(base.y, base.x);
    const double baseElevation = std::atan2(base.z, std::sqrt(base.x * base.x + base.y * base.y));
    SplitMix rng(seed);

    for (int i = 0; i < samples; ++i) {
        Vec3 direction = base;
        if (i > 0 && deviance > 0) {
            // Rejection sampling inside a disc of radius `deviance` in (azimuth, elevation) space.
            double da, de;
            do {
                da = (rng.unit() * 2.0 - 1.0) * deviance;
                de = (rng.unit() * 2.0 - 1.0) * deviance;
            } while (da * da + de * de > deviance * deviance);
            direction = directionForSpherical(baseAzimuth + da, baseElevation + de);
        }
        Light light;
        light.type = LightType::Sun;
        light.origin = direction * kSunDistance;
        light.normal = direction;
        light.color = sun.color;
        light.photons = photons * scales.skyScale;
        light.falloffTolerance = scales.falloffTolerance;
        light.filterRadius = sun.filterRadius / static_cast<float>(samples);
        light.style = scales.noStyles ? 0 : sun.style;
        light.skyIndex = scales.oneSky ? -1 : skyIndex;
        out.push_back(light);
    }
}

void appendSkyLights(std::vector<Light>& out, const SkyLightDirective& sky, Vec3 color, int skyIndex, int style,
                     float filterRadius, const LightScales& scales) {
    if (sky.value <= 0 || sky.iterations < 2 || sky.horizonMin > sky.horizonMax) return;

    const bool doBottom = sky.horizonMin == -90;
    const bool doTop = sky.horizonMax == 90;
    const int angleSteps = (sky.iterations - 1) * 4;
    const float eleStep = 90.0f / static_cast<float>(sky.iterations);
    const float elevationStep = degToRad(eleStep);
    const float angleStep = degToRad(360.0f / static_cast<float>(angleSteps));
    const float eleMin = doBottom ? -90 + eleStep * 1.5f : sky.horizonMin + eleStep * 0.5f;
    const float eleMax = doTop ? 90 - eleStep * 1.5f : sky.horizonMax - eleStep * 0.5f;
    const int elevationSteps = static_cast<int>(std::lround(1 + std::max(0.f, (eleMax - eleMin) / eleStep)));
    const int numSuns = angleSteps * elevationSteps + (doBottom ? 1 : 0) + (doTop ? 1 : 0);

    SunDirective sun;
    sun.color = color;
    sun.samples = 1;
    sun.style = style;
    sun.filterRadius = filterRadius;
    sun.intensity = sky.value / static_cast<float>(numSuns) *
                    static_cast<float>(std::max(0.25, (sky.horizonMax - sky.horizonMin) / 90.0));

    float elevation = degToRad(std::min(eleMin, sky.horizonMax));
    float angle = 0;
    for (int i = 0; i < elevationSteps; ++i) {
        for (int j = 0; j < angleSteps; ++j) {
            sun.direction = directionForSpherical(angle, elevation);
            appendSunLights(out, sun, skyIndex, scales, 0);
            angle += angleStep;
        }
        elevation += elevationStep;
        angle += angleStep / static_cast<float>(elevationSteps);  // stagger the rings
    }
    if (doBottom) {
        sun.direction = {0, 0, -1};
        appendSunLights(out, sun, skyIndex, scales, 0);
    }
    if (doTop) {
        sun.direction = {0, 0, 1};
        appendSunLights(out, sun, skyIndex, scales, 0);
    }
}

std::vector<int> assignSkyIndices(const bsp::Bsp& bsp, const std::vector<LightingShader>& shaders, bool noShaderSun,
                                  bool oneSky, Log& log) {
    std::vector<int> index(shaders.size(), -1);
    if (oneSky) return index;
    int next = 0;
    bool warned = false;
    for (const bsp::Surface& s : bsp.surfaces) {
        if (s.shaderNum < 0 || static_cast<size_t>(s.shaderNum) >= shaders.size()) continue;
        const LightingShader& sh = shaders[static_cast<size_t>(s.shaderNum)];
        bool emits = (!sh.suns.empty() && !noShaderSun) || !sh.skyLights.empty();
        if (!emits || index[static_cast<size_t>(s.shaderNum)] >= 0) continue;
        if (next == kMaxSkies) {
            if (!warned) log.warning(strCat("more than ", kMaxSkies, " sky shaders emit light; ", sh.name, " lights through every sky"));
            warned = true;
            continue;
        }
        index[static_cast<size_t>(s.shaderNum)] = next++;
    }
    return index;
}

}  // namespace q3::light
