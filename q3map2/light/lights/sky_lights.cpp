// Suns (q3map_sun, q3map_sunExt, entity _sun), sky domes (q3map_skyLight) and the sky index that
// lets each sun light only through the sky surfaces of its own shader.
#include <algorithm>
#include <cmath>

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

// One direction of the sky box with the colour seen along it, cosine-weighted over its texel block.
struct SkyProbe {
    Vec3 color;
    Vec3 normal;
};

// Turns a direction of the +x (rt) face into the direction of face `face` (lf, rt, ft, bk, up, dn).
Vec3 faceDirection(int face, Vec3 d) {
    switch (face) {
        case 0: return {-d.x, -d.y, d.z};  // lf: -x
        case 1: return d;                  // rt: +x
        case 2: return {d.y, -d.x, d.z};   // ft: -y
        case 3: return {-d.y, d.x, d.z};   // bk: +y
        case 4: return {-d.z, d.y, d.x};   // up: +z
        default: return {d.z, d.y, -d.x};  // dn: -z
    }
}

std::vector<SkyProbe> skyProbes(const SkyBoxImages& box) {
    constexpr int kRes = 64;  // probes per face side
    std::vector<SkyProbe> probes;
    for (const LightImage* img : box)
        if (!img || img->width <= 0 || img->height <= 0) return probes;
    probes.reserve(static_cast<size_t>(6 * kRes * kRes));
    for (int face = 0; face < 6; ++face) {
        const LightImage& img = *box[static_cast<size_t>(face)];
        for (int u = 0; u < kRes; ++u)
            for (int v = 0; v < kRes; ++v) {
                const Vec3 normal = normalize(Vec3{1, 1 - u * 2.0f / kRes, 1 - v * 2.0f / kRes});
                const int x0 = img.width * u / kRes, x1 = std::max(x0 + 1, img.width * (u + 1) / kRes);
                const int y0 = img.height * v / kRes, y1 = std::max(y0 + 1, img.height * (v + 1) / kRes);
                Vec3 sum;
                for (int x = x0; x < x1; ++x)
                    for (int y = y0; y < y1; ++y) {
                        const uint8_t* p = &img.rgba[(static_cast<size_t>(y) * static_cast<size_t>(img.width) +
                                                      static_cast<size_t>(x)) * 4];
                        sum += Vec3{static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2])};
                    }
                const Vec3 mean = sum / static_cast<float>((x1 - x0) * (y1 - y0));
                probes.push_back({mean * (normal.x / 255.0f), faceDirection(face, normal)});
            }
    }
    return probes;
}

Vec3 sampleProbes(const std::vector<SkyProbe>& probes, Vec3 direction, Vec3 limit) {
    Vec3 color;
    double weight = 0;
    for (const SkyProbe& p : probes) {
        const float d = dot(p.normal, direction);
        if (d > 0 && dot(p.normal, limit) >= 0) {
            color += p.color * d;
            weight += d;
        }
    }
    return weight != 0 ? color / static_cast<float>(weight) : color;
}

}  // namespace

void appendSunLights(std::vector<Light>& out, const SunDirective& sun, int skyIndex, const LightScales& scales,
                     CLibraryRandom& random) {
    const int samples = std::max(1, sun.samples);
    const float photons = sun.intensity / static_cast<float>(samples);
    const float deviance = sun.devianceDeg / 180.0f * static_cast<float>(kPiD);
    const Vec3 base = normalize(sun.direction);
    const double baseAzimuth = std::atan2(base.y, base.x);
    const double baseElevation = std::atan2(base.z, std::sqrt(base.x * base.x + base.y * base.y));

    for (int i = 0; i < samples; ++i) {
        Vec3 direction = base;
        if (i > 0) {
            // Rejection sampling inside a disc of radius `deviance` in (azimuth, elevation) space,
            // in floats as q3map2; a pair is drawn even when there is no deviance.
            float da, de;
            do {
                da = (random.unit() * 2.0f - 1.0f) * deviance;
                de = (random.unit() * 2.0f - 1.0f) * deviance;
            } while (da * da + de * de > deviance * deviance);
            if (deviance > 0) direction = directionForSpherical(baseAzimuth + da, baseElevation + de);
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
                     float filterRadius, const LightScales& scales, const SkyBoxImages* skyBox) {
    if (sky.value <= 0 || sky.iterations < 2 || sky.horizonMin > sky.horizonMax) return;
    const std::vector<SkyProbe> probes = sky.sampleColor && skyBox ? skyProbes(*skyBox) : std::vector<SkyProbe>{};
    const Vec3 limit = sky.horizonMin >= 0 ? Vec3{0, 0, 1} : sky.horizonMax <= 0 ? Vec3{0, 0, -1} : Vec3{};
    const size_t first = out.size();

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
    CLibraryRandom unused;  // suns of one sample draw nothing
    sun.style = style;
    sun.filterRadius = filterRadius;
    sun.intensity = sky.value / static_cast<float>(numSuns) *
                    static_cast<float>(std::max(0.25, (sky.horizonMax - sky.horizonMin) / 90.0));

    float elevation = degToRad(std::min(eleMin, sky.horizonMax));
    float angle = 0;
    for (int i = 0; i < elevationSteps; ++i) {
        for (int j = 0; j < angleSteps; ++j) {
            sun.direction = directionForSpherical(angle, elevation);
            appendSunLights(out, sun, skyIndex, scales, unused);
            angle += angleStep;
        }
        elevation += elevationStep;
        angle += angleStep / static_cast<float>(elevationSteps);  // stagger the rings
    }
    if (doBottom) {
        sun.direction = {0, 0, -1};
        appendSunLights(out, sun, skyIndex, scales, unused);
    }
    if (doTop) {
        sun.direction = {0, 0, 1};
        appendSunLights(out, sun, skyIndex, scales, unused);
    }
    for (size_t i = first; i < out.size(); ++i) out[i].skyDome = true;
    if (!probes.empty()) {
        float brightest = 0;
        for (size_t i = first; i < out.size(); ++i) {
            out[i].color = sampleProbes(probes, out[i].normal, limit);
            brightest = std::max(brightest, maxComponent(out[i].color));
        }
        if (brightest > 0)
            for (size_t i = first; i < out.size(); ++i) out[i].color = out[i].color / brightest;
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
