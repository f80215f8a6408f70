// Shader-driven lights: q3map_surfacelight surfaces chopped into area lights (with their
// backsplash), autosprite point lights, and the suns and sky domes of sky shaders.
#include <algorithm>
#include <cmath>
#include <limits>
#include <span>

#include "lights.h"
#include "winding_ops.h"

namespace q3::light {
namespace {

constexpr float kFormFactorValueScale = 3;
constexpr float kDefaultLightSubdivide = 999;
constexpr float kClipEpsilon = 0.1f;

using Winding = std::vector<Vec3>;

struct AreaLightContext {
    const LightingShader& shader;
    const LightScales& scales;
    Vec3 normal;  // average vertex normal of the emitting triangle
    float subdivide;
    std::vector<Light>& out;
};

void emitAreaLight(const AreaLightContext& ctx, const Winding& w) {
    const Bounds bounds = windingBounds(w);
    for (int axis = 0; axis < 3; ++axis) {
        if (bounds.maxs[axis] - bounds.mins[axis] > ctx.subdivide) {
            const float dist = (bounds.maxs[axis] + bounds.mins[axis]) * 0.5f;
            Winding front, back;
            clipWindingAxial(w, axis, dist, kClipEpsilon, front, back);
            if (front.size() >= 3) emitAreaLight(ctx, front);
            if (back.size() >= 3) emitAreaLight(ctx, back);
            return;
        }
    }
    const float area = windingArea(w);
    if (area < 1.0f || area > 20000000.0f) return;

    const LightingShader& si = ctx.shader;
    Light light;
    light.type = LightType::Area;
    light.winding = w;
    light.emitter = emitterBounds(light.winding);
    light.falloffTolerance = ctx.scales.falloffTolerance;
    light.fast = ctx.scales.fast;
    light.photons = si.surfaceLight * area * ctx.scales.areaScale;
    light.add = si.surfaceLight * kFormFactorValueScale * ctx.scales.areaScale;
    light.color = si.color;
    light.style = ctx.scales.noStyles ? 0 : si.lightStyle;
    light.normal = ctx.normal;
    light.origin = bounds.center() + ctx.normal;  // nudged off the plane
    light.planeDist = dot(light.origin, light.normal);
    light.twoSided = si.fog || si.twoSided;
    light.filterRadius = si.lightFilterRadius;

    constexpr float kDefaultBacksplashFraction = 0.05f;
    const float fraction =
        si.backsplashSet ? si.backsplashFraction : kDefaultBacksplashFraction * ctx.scales.backsplashFractionScale;
    const float splashDistance = si.backsplashSet ? si.backsplashDistance : ctx.scales.backsplashDistance;
    ctx.out.push_back(light);

    if (fraction > 0 && !si.sky) {
        // q3map2 2.5.17n's backsplash: the emitter's own polygon, reversed to face back at the wall
        // it sits on, moved `backsplashDistance` out along the normal, one-sided, with 7 x `fraction`
        // of its photons and form-factor strength. (Older q3map2 made it a point light with
        // `fraction` of the photons: against 2.5.17n that left oacmpdm1's lightmaps at 0.84 of its
        // total, and the ceilings around its light fixtures at a quarter.)
        constexpr float kBacksplashGain = 7.0f;
        Light splash = light;
        splash.photons = light.photons * kBacksplashGain * fraction;
        splash.add = light.add * kBacksplashGain * fraction;
        splash.winding.clear();
        for (size_t i = w.size(); i-- > 0;) splash.winding.push_back(w[i] + ctx.normal * splashDistance);
        splash.emitter = emitterBounds(splash.winding);
        splash.origin = light.origin + ctx.normal * splashDistance;
        splash.normal = -ctx.normal;
        splash.planeDist = dot(splash.origin, splash.normal);
        splash.twoSided = false;
        ctx.out.push_back(splash);
    }
}

}  // namespace

const uint8_t* LightImage::texel(float s, float t) const {
    if (width <= 0 || height <= 0 || !std::isfinite(s) || !std::isfinite(t)) return nullptr;
    // Nearest texel with q3map2's rounding (RadSampleImage): int(size * coord + 0.5), repeated.
    auto wrap = [](float v, int size) {
        long i = static_cast<long>(std::floor(static_cast<double>(v) * size + 0.5)) % size;
        return static_cast<int>(i < 0 ? i + size : i);
    };
    const int x = wrap(s, width);
    const int y = wrap(t, height);
    return &rgba[(static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)) * 4];
}

Vec3 LightImage::averageColor() const {
    if (width <= 0 || height <= 0) return {1, 1, 1};
    double sum[3] = {0, 0, 0};
    const size_t count = static_cast<size_t>(width) * static_cast<size_t>(height);
    for (size_t i = 0; i < count; ++i)
        for (int c = 0; c < 3; ++c) sum[c] += rgba[i * 4 + static_cast<size_t>(c)];
    const double scale = 1.0 / (255.0 * static_cast<double>(count));
    return {static_cast<float>(sum[0] * scale), static_cast<float>(sum[1] * scale), static_cast<float>(sum[2] * scale)};
}

namespace {

// One emitting polygon of `g` (corner indexes into its vertexes): its normal is the sum of the
// corners' vertex normals, or the polygon's own (Quake winding order) when those cancel or are
// missing; a polygon with neither emits nothing.
void emitPolygon(std::vector<Light>& out, const EmitterGeometry& g, std::span<const size_t> corners,
                 const LightingShader& shader, const LightScales& scales, float subdivide) {
    const bool withNormals = g.normals.size() == g.xyz.size();
    Winding w;
    Vec3 normal;
    for (size_t c : corners) {
        w.push_back(g.xyz[c]);
        if (withNormals) normal = normal + g.normals[c];
    }
    if (length(normal) <= 0) normal = cross(w[2] - w[0], w[1] - w[0]);
    if (length(normal) <= 0) return;
    AreaLightContext ctx{shader, scales, normalize(normal), subdivide, out};
    emitAreaLight(ctx, w);
}

// q3map2 RadLightForPatch: each quad of the lighting mesh emits as one four-corner winding, its
// corners starting at alternating ones ((x + y) & 1) as the mesh's diagonals do. q3map2 means to
// split non-planar quads into triangles, but its planarity test measures a corner that defines the
// plane, and a quad whose first corners coincide (patches with a collapsed edge) gives a NaN plane
// that passes too: every quad goes whole. Measured against the binary: 126 area lights (not 252)
// on oacmpdm6's curved white_glowing_500 emitters, 416 on oacmpdm1's collapsed-edge fixtures.
void appendPatchAreaLights(std::vector<Light>& out, const EmitterGeometry& g, const LightingShader& shader,
                           const LightScales& scales, float subdivide) {
    const int w = g.meshWidth, h = g.meshHeight;
    for (int y = 0; y + 1 < h; ++y)
        for (int x = 0; x + 1 < w; ++x) {
            const size_t around[5] = {size_t(x + y * w), size_t(x + (y + 1) * w), size_t(x + 1 + (y + 1) * w),
                                      size_t(x + 1 + y * w), size_t(x + y * w)};
            const size_t r = size_t((x + y) & 1);
            emitPolygon(out, g, std::span<const size_t>(around + r, 4), shader, scales, subdivide);
        }
}

}  // namespace

void appendAreaLights(std::vector<Light>& out, const EmitterGeometry& g, const LightingShader& shader,
                      const LightScales& scales) {
    if (shader.surfaceLight <= 0) return;
    const float subdivide = shader.lightSubdivide > 0 ? shader.lightSubdivide : kDefaultLightSubdivide;
    if (g.meshWidth > 1 && g.meshHeight > 1 && g.xyz.size() == size_t(g.meshWidth) * size_t(g.meshHeight)) {
        appendPatchAreaLights(out, g, shader, scales, subdivide);
        return;
    }
    for (size_t i = 0; i + 2 < g.triangles.size(); i += 3) {
        const size_t triangle[3] = {g.triangles[i], g.triangles[i + 1], g.triangles[i + 2]};
        emitPolygon(out, g, triangle, shader, scales, subdivide);
    }
}

std::vector<Light> createShaderLights(const bsp::Bsp& bsp, const std::vector<LightingShader>& shaders,
                                      const std::vector<int>& skyIndices, bool noShaderSun,
                                      const LightScales& scales, CLibraryRandom& random,
                                      const std::function<EmitterGeometry(int surfaceNum)>& geometryOf) {
    std::vector<Light> out;
    std::vector<bool> skyDone(shaders.size(), false);
    for (size_t i = 0; i < bsp.surfaces.size(); ++i) {
        const bsp::Surface& surface = bsp.surfaces[i];
        if (surface.shaderNum < 0 || static_cast<size_t>(surface.shaderNum) >= shaders.size()) continue;
        const size_t shaderNum = static_cast<size_t>(surface.shaderNum);
        const LightingShader& si = shaders[shaderNum];

        // Suns and sky domes are created once per shader, when its first surface is met.
        if (!skyDone[shaderNum]) {
            skyDone[shaderNum] = true;
            const int skyIndex = shaderNum < skyIndices.size() ? skyIndices[shaderNum] : -1;
            if (!noShaderSun)
                for (size_t k = 0; k < si.suns.size(); ++k)
                    appendSunLights(out, si.suns[k], skyIndex, scales, random);
            for (const SkyLightDirective& sky : si.skyLights)
                appendSkyLights(out, sky, si.color, skyIndex, si.lightStyle, si.lightFilterRadius, scales, &si.skyBox);
        }

        if (si.surfaceLight <= 0) continue;
        if (surface.surfaceType != bsp::MST_PLANAR && surface.surfaceType != bsp::MST_TRIANGLE_SOUP &&
            surface.surfaceType != bsp::MST_PATCH)
            continue;
        EmitterGeometry g = geometryOf(static_cast<int>(i));
        if (si.autosprite) {
            Bounds b;
            for (const Vec3& p : g.xyz) b.add(p);
            if (b.empty()) continue;
            Light light;
            light.type = LightType::Point;
            light.photons = si.surfaceLight * scales.pointScale;
            light.origin = b.center();
            light.color = si.color;
            light.falloffTolerance = scales.falloffTolerance;
            light.fast = scales.fast || scales.fastPoint;
            light.style = scales.noStyles ? 0 : si.lightStyle;
            out.push_back(light);
            continue;
        }
        appendAreaLights(out, g, si, scales);
    }
    return out;
}

}  // namespace q3::light
