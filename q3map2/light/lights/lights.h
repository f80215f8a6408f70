// The light list of the -light stage: every emitter of a map turned into one flat list of Light
// records (entity point/spot lights, suns, sky domes, surface area lights), plus the worldspawn
// lighting settings. Creation is deterministic: the same inputs always give the same list in the
// same order, including jittered copies (fixed-seed generator per entity).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "bspfile.h"
#include "c_library_random.h"
#include "vec3.h"

namespace q3 {
class Log;
}

namespace q3::light {

enum class LightType { Point, Spot, Sun, Area };

// The controlled model (specs/light-models.md): every value already clamped.
struct ControlledParams {
    float brightness = 1;
    float dotProductWeight = 0.5f;
    float falloffStart = 0;
    float falloffEnd = 300;
    float falloffCurvature = 0.5f;
    float angleHotspot = 45;   // full cone angle, degrees
    float anglePenumbra = 60;  // full cone angle, degrees
    float sphericalAmbient = 0;
};

// What the -fast test of an area light needs to know of its polygon without walking it: a sphere
// and a box around it, its area, and its plane when it is flat (see formFactorUpperBound).
struct EmitterBounds {
    Vec3 center;
    float radius = -1;  // < 0: unknown, no bound
    Bounds box;         // of the corners
    float area = 0;     // of the fan from the first corner (the polygon's, when it is flat)
    bool flat = false;
    Vec3 planeNormal;   // unit, when flat
    float flatness = 0; // largest distance of a corner from the plane through the centre
};

// The bounds of an emitter polygon (radius < 0 for fewer than three corners).
EmitterBounds emitterBounds(const std::vector<Vec3>& winding);

struct Light {
    LightType type = LightType::Point;
    int entityNum = -1;  // originating entity, -1 for shader lights

    Vec3 origin;
    Vec3 color{1, 1, 1};
    float photons = 0;  // point/spot: intensity * scale; sun: intensity * skyScale; area: value*area*areaScale

    // Spot: unit axis from the light towards its target. Sun: unit vector from the world towards
    // the sun. Area: unit emitter normal.
    Vec3 normal;
    float radiusByDist = 0;  // spot: (radius + 16) / distance to target

    bool linear = false;            // linear falloff (add = angle*photons/8000 - dist*fade)
    bool angleAttenuation = true;   // Lambert term on luxels
    float fade = 1;
    float angleScale = 0;           // _anglescale (0 = unused)
    float extraDist = 0;            // _extradist / -extradist
    float filterRadius = 0;         // _filterradius, world units
    float falloffTolerance = 1;      // -fast envelope threshold (divided by _samples)
    bool fast = false;               // use the falloff envelope (-fast, or fast point lights)

    bool affectsSurfaces = true;  // false for lightJunior
    bool affectsGrid = true;      // false with spawnflags 16
    int style = 0;

    // Area lights.
    std::vector<Vec3> winding;
    float add = 0;           // value * 3 * areaScale (form-factor scale)
    float planeDist = 0;     // dot(origin, normal)
    bool twoSided = false;
    EmitterBounds emitter;   // of `winding`: set with it

    // Suns: -1 lights through any sky, otherwise only sky surfaces of this sky index.
    int skyIndex = -1;
    // Suns: one of the many parallel lights of a q3map_skyLight dome (sky ambient), not a sun.
    bool skyDome = false;

    // Controlled model, when the entity has any of its keys.
    std::optional<ControlledParams> controlled;

    int cluster = -1;  // PVS cluster of the light, -1 = unknown (visible from everywhere)
};

// Scales and switches from the command line that shape the light list.
struct LightScales {
    float pointScale = 7500;      // -point / -spherical
    float spotScale = 7500;       // -spot
    float areaScale = 0.25f;      // -area
    float skyScale = 1;           // -sky
    float extraDist = 0;          // -extradist (default for _extradist)
    // -backsplash: scale of the default 5% fraction and the default distance, both used by shaders
    // without their own q3map_backsplash.
    float backsplashFractionScale = 1;
    float backsplashDistance = 23;
    float falloffTolerance = 1;
    bool fast = false;            // -fast: every light uses its envelope
    bool fastPoint = true;        // point/spot lights use the envelope (off with -nofastpoint)
    bool wolfLight = false;       // -wolf: linear falloff by default
    bool noStyles = false;        // -nostyles
    bool oneSky = false;          // -onesky: every sun lights through every sky
};

// A parallel sun as declared by q3map_sun / q3map_sunExt.
struct SunDirective {
    Vec3 color{1, 1, 1};     // normalised
    float intensity = 0;
    Vec3 direction{0, 0, 1};  // unit vector towards the sun
    float devianceDeg = 0;
    int samples = 1;
    int style = 0;
    float filterRadius = 0;  // world units, shared by the samples
};

// q3map_skyLight value iterations [horizonMin horizonMax].
struct SkyLightDirective {
    float value = 0;
    int iterations = 0;
    float horizonMin = 0;
    float horizonMax = 90;
    bool sampleColor = false;  // colour each sun from the sky box images (when they load)
};

// RGBA8 image used for light colours, alpha shadows and light filters.
struct LightImage {
    int width = 0;
    int height = 0;
    std::vector<uint8_t> rgba;  // width * height * 4, row 0 at the top

    // Nearest texel at texture coordinate (s, t), wrapped (repeat).
    const uint8_t* texel(float s, float t) const;
    // Average RGB in 0..1 over all texels.
    Vec3 averageColor() const;
};

// The six sky box images of a skyParms shader, in the order lf, rt, ft, bk, up, dn (null = missing).
using SkyBoxImages = std::array<const LightImage*, 6>;

// What the light stage needs to know about one BSP shader, resolved from the shader scripts.
struct LightingShader {
    std::string name;
    bool sky = false;
    bool translucent = false;  // surfaceparm trans
    bool nodraw = false;
    bool alphaShadow = false;
    bool lightFilter = false;
    bool twoSided = false;     // cull none / twosided
    bool fog = false;
    bool vertexLit = false;    // nolightmap / pointlight
    bool autosprite = false;

    std::vector<SunDirective> suns;
    std::vector<SkyLightDirective> skyLights;

    float surfaceLight = 0;     // q3map_surfacelight
    Vec3 color{1, 1, 1};        // emitted colour (lightRGB or light image average), normalised
    bool hasLightRGB = false;   // colour from q3map_lightRGB rather than the image
    float lightSubdivide = 0;   // 0 = default (999)
    int lightStyle = 0;
    float backsplashFraction = 0.05f;
    float backsplashDistance = 23;
    bool backsplashSet = false;  // q3map_backsplash written: its values win over -backsplash
    float lightFilterRadius = 0;
    float bounceScale = 1;      // q3map_bounceScale: fraction re-emitted by -bounce (0 = none)

    const LightImage* lightImage = nullptr;  // owned by the caller, outlives the scene
    SkyBoxImages skyBox{};                    // skyParms box images, for q3map_skyLight colours

    // How the surfaces of this shader receive light.
    int lightmapSampleSize = 0;        // q3map_lightmapSampleSize, 0 = not set
    int lightmapAxis = -1;             // q3map_lightmapAxis 0/1/2, -1 = chosen from the plane
    float lightmapSampleOffset = 1;    // q3map_lightmapSampleOffset
    float lightmapFilterRadius = 0;    // q3map_lightmapFilterRadius (this surface's lightmap)
    float lightmapBrightness = 1;      // q3map_lightmapBrightness
    float vertexScale = 1;             // q3map_vertexScale
    bool noVertexLight = false;        // q3map_noVertexLight
    bool forceSunlight = false;        // q3map_forceSunlight: vertex light gets sun without occlusion
};

// Worldspawn keys read by -light.
struct WorldLighting {
    Vec3 ambient;            // _ambient * _color
    Vec3 minLight;           // _minlight * _color
    Vec3 minVertexLight;     // _minvertexlight (default _minlight)
    Vec3 minGridLight;       // _mingridlight (default _minlight)
    float maxLight = 255;    // _maxlight
    bool noShaderSun = false;
    bool keepLights = false;
};

WorldLighting readWorldLighting(const bsp::Entity& worldspawn);

// Light entities (classname prefixed "light", and "lightJunior") of `entities`, in entity order.
// Spotlight targets are looked up among `targets` (normally the same list). Warnings and clamps
// of the controlled model go to `log`. Throws CompileError for an invalid light style. The jitter
// of lights with "_samples" draws from `random`, as q3map2's does from rand().
std::vector<Light> createEntityLights(const std::vector<bsp::Entity>& entities,
                                      const std::vector<bsp::Entity>& targets, const LightScales& scales,
                                      Log& log, const std::string& fileName, CLibraryRandom& random);

// Adds the `samples` sun lights of a sun (sample 0 exact, the others jittered within the deviance,
// each drawing pairs from `random` until the pair falls inside it, as q3map2's CreateSunLight).
void appendSunLights(std::vector<Light>& out, const SunDirective& sun, int skyIndex, const LightScales& scales,
                     CLibraryRandom& random);

// Adds the ring of suns that approximates q3map_skyLight. With sky.sampleColor and all six
// `skyBox` images, each sun takes the cosine-weighted colour of the box around its direction
// (limited to the dome's hemisphere), the set normalised so its brightest channel is 1.
void appendSkyLights(std::vector<Light>& out, const SkyLightDirective& sky, Vec3 color, int skyIndex, int style,
                     float filterRadius, const LightScales& scales, const SkyBoxImages* skyBox = nullptr);

// Geometry of one BSP surface as the light stage sees it (world coordinates).
struct EmitterGeometry {
    std::vector<Vec3> xyz;
    std::vector<Vec3> normals;
    std::vector<uint32_t> triangles;  // 3 indices per triangle
    int meshWidth = 0, meshHeight = 0;  // > 0: a patch mesh, xyz row-major, emitting by quads
};

// Area lights of one emitting triangle list, chopped at `subdivide` world units.
void appendAreaLights(std::vector<Light>& out, const EmitterGeometry& geometry, const LightingShader& shader,
                      const LightScales& scales);

// Sky index of every shader that emits sun or sky light (-1 for the others), in order of first use
// by a surface, at most 32 indices. Empty when `oneSky`.
std::vector<int> assignSkyIndices(const bsp::Bsp& bsp, const std::vector<LightingShader>& shaders, bool noShaderSun,
                                  bool oneSky, Log& log);

// Shader suns, sky domes and surface lights of every BSP surface. `geometryOf(i)` returns the
// geometry of surface i (patches tessellated by the caller). Sun jitter draws from `random`.
std::vector<Light> createShaderLights(const bsp::Bsp& bsp, const std::vector<LightingShader>& shaders,
                                      const std::vector<int>& skyIndices, bool noShaderSun,
                                      const LightScales& scales, CLibraryRandom& random,
                                      const std::function<EmitterGeometry(int surfaceNum)>& geometryOf);

// Fast-envelope radius of a light: beyond it the light adds at most falloffTolerance.
// Infinity for suns and for lights that do not use an envelope (`forceFast` makes every light use it).
// Inline: it is asked once per light and sample.
inline float lightEnvelope(const Light& light, bool forceFast = false) {
    constexpr float kInfinite = std::numeric_limits<float>::infinity();
    if (light.controlled) return light.type == LightType::Sun ? kInfinite : light.controlled->falloffEnd;
    if (!(light.fast || forceFast) || light.type == LightType::Sun || light.falloffTolerance <= 0) return kInfinite;
    switch (light.type) {
        case LightType::Point:
        case LightType::Spot:
            if (light.linear) return std::max(0.f, (light.photons / 8000.0f - light.falloffTolerance) / light.fade);
            return std::sqrt(std::max(0.f, light.photons) / light.falloffTolerance);
        case LightType::Area:
            // Beyond this distance the inverse-square estimate of the emitter is below tolerance.
            return std::sqrt(std::max(0.f, light.photons) / light.falloffTolerance) + 16.0f;
        default:
            return kInfinite;
    }
}

inline std::vector<float> lightEnvelopes(std::span<const Light> lights, bool forceFast) {
    std::vector<float> out;
    out.reserve(lights.size());
    for (const Light& light : lights) out.push_back(lightEnvelope(light, forceFast));
    return out;
}

// Whether any point of `bounds` lies inside the light's envelope (its lightEnvelope, which loops
// over many bounds compute once; suns and unbounded lights: always).
inline bool lightReachesBounds(const Light& light, const Bounds& bounds, float envelope) {
    if (light.type == LightType::Sun || !std::isfinite(envelope)) return true;
    const Vec3 nearest = vmin(vmax(light.origin, bounds.mins), bounds.maxs);
    return distance(nearest, light.origin) < envelope;
}

}  // namespace q3::light
