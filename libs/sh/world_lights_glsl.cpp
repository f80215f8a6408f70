// The GLSL twin of world_lights_eval.cpp. The text keeps to what GLSL and C++ share (no swizzles,
// no out parameters, no GLSL-only built-ins) so the tests can compile it as C++ and compare it with
// evaluateWorldLight point by point.
#include "world_lights_glsl.h"

#include <cstdio>
#include <cstring>

namespace q3::sh {
namespace {

std::string floatLiteral(float v) {
    char text[48];
    std::snprintf(text, sizeof text, "%.9g", double(v));
    std::string out = text;
    if (out.find_first_of(".e") == std::string::npos) out += ".0";
    return out;
}

std::string intConstant(const char* name, uint32_t value) {
    return std::string("const int ") + name + " = " + std::to_string(value) + ";\n";
}

std::string floatConstant(const char* name, float value) {
    return std::string("const float ") + name + " = " + floatLiteral(value) + ";\n";
}

void copy4(float out[4], float x, float y, float z, float w) {
    out[0] = x;
    out[1] = y;
    out[2] = z;
    out[3] = w;
}

// Everything after the constants; plain text, the formulas of world-lights-format.md.
constexpr const char* kFunctions = R"(
struct WorldLightGpu {
    vec4 originRadius;
    vec4 intensityFalloff;
    vec4 directionWeight;
    vec4 falloffConstants;
    vec4 coneType;
};

vec3 wlXyz(vec4 v) { return vec3(v.x, v.y, v.z); }

int wlType(WorldLightGpu l) { return int(l.coneType.w + 0.5); }
int wlFalloff(WorldLightGpu l) { return int(l.intensityFalloff.w + 0.5); }

// The controlled model: linear and inverse-square parts blended by the curvature.
float wlControlledFalloff(float d, float start, float end, float curvature)
{
    if (d <= start) return 1.0;
    if (d >= end) return 0.0;
    float lin = 1.0 - (d - start) / (end - start);
    float s = max(start, WL_CONTROLLED_SQUARE_START);
    float see = (s * s) / (end * end);
    float isq = lin;
    if (see < 1.0) isq = ((s * s) / (d * d) - see) / (1.0 - see);
    isq = clamp(isq, 0.0, 1.0);
    return (1.0 - curvature) * lin + curvature * isq;
}

// The controlled spot cone: 1 inside the inner half angle, linear down to 0 at the outer one,
// lifted by the spherical ambient fraction.
float wlControlledCone(float cosAngle, float inner, float outer, float ambient)
{
    float angle = acos(clamp(cosAngle, -1.0, 1.0)) * WL_DEGREES_PER_RADIAN;
    float cone = 0.0;
    if (angle <= inner) cone = 1.0;
    else if (angle >= outer) cone = 0.0;
    else cone = 1.0 - (angle - inner) / (outer - inner);
    return ambient + (1.0 - ambient) * cone;
}

// q3map2's spot cone: a radius growing along the axis, faded over its last `fade` units.
float wlQ3map2Spot(WorldLightGpu l, vec3 p)
{
    vec3 origin = wlXyz(l.originRadius);
    vec3 axis = wlXyz(l.directionWeight);
    float along = -dot(origin - p, axis);
    if (along < 0.0) return 0.0;
    vec3 onAxis = origin + axis * along;
    float radiusAtDist = l.coneType.x * along;
    float fromAxis = length(p - onAxis);
    if (fromAxis >= radiusAtDist) return 0.0;
    float fade = l.coneType.y;
    if (fromAxis > radiusAtDist - fade) return max(0.0, (radiusAtDist - fromAxis) / fade);
    return 1.0;
}

// Distance falloff times cone of a point or spot light at distance d, lit from towardsLight.
float wlPointFactor(WorldLightGpu l, vec3 p, float d, vec3 towardsLight)
{
    if (l.originRadius.w > 0.0 && d > l.originRadius.w) return 0.0;
    bool spot = wlType(l) == WL_TYPE_SPOT;
    vec4 c = l.falloffConstants;
    if (wlFalloff(l) == WL_FALLOFF_CONTROLLED) {
        float falloff = wlControlledFalloff(d, c.x, c.y, c.z);
        if (falloff <= 0.0) return 0.0;
        float cone = 1.0;
        if (spot) cone = wlControlledCone(-dot(towardsLight, wlXyz(l.directionWeight)), l.coneType.x, l.coneType.y, l.coneType.z);
        if (cone <= 0.0) return 0.0;
        return falloff * cone;
    }
    float clamped = max(c.x, sqrt(d * d + c.y * c.y));
    float factor = 1.0 / (clamped * clamped);
    if (wlFalloff(l) == WL_FALLOFF_LINEAR) factor = max(0.0, 1.0 - clamped * c.w);
    if (spot) factor = factor * wlQ3map2Spot(l, p);
    if (factor <= c.z) return 0.0;
    return factor;
}

// Irradiance of one record at point p on a surface of unit normal n (evaluateWorldLight).
vec3 worldLightIrradiance(WorldLightGpu l, vec3 p, vec3 n)
{
    vec3 towardsLight = wlXyz(l.directionWeight);
    float factor = 1.0;
    if (wlType(l) != WL_TYPE_SUN) {
        vec3 toLight = wlXyz(l.originRadius) - p;
        float d = length(toLight);
        towardsLight = vec3(0.0);
        if (d > 0.0) towardsLight = toLight / d;
        else if (wlFalloff(l) == WL_FALLOFF_CONTROLLED) towardsLight = vec3(0.0, 0.0, 1.0);
        factor = wlPointFactor(l, p, d, towardsLight);
    }
    if (factor == 0.0) return vec3(0.0);
    float cosine = dot(n, towardsLight);
    if (cosine <= 0.0) return vec3(0.0);
    float w = l.directionWeight.w;
    return wlXyz(l.intensityFalloff) * (factor * ((1.0 - w) + w * cosine));
}

// The light cache's local lights: the sum over the first `count` (0..4) records.
vec3 worldLightsIrradiance(WorldLightGpu lights[4], int count, vec3 p, vec3 n)
{
    vec3 e = vec3(0.0);
    for (int i = 0; i < 4; ++i) {
        if (i < count) e = e + worldLightIrradiance(lights[i], p, n);
    }
    return e;
}
)";

}  // namespace

WorldLightGpu packWorldLightGpu(const WorldLight& l) {
    WorldLightGpu g;
    copy4(g.originRadius, l.origin[0], l.origin[1], l.origin[2], l.radius);
    copy4(g.intensityFalloff, l.intensity[0], l.intensity[1], l.intensity[2], float(uint32_t(l.falloff)));
    copy4(g.directionWeight, l.direction[0], l.direction[1], l.direction[2], l.incidenceWeight);
    copy4(g.falloffConstants, l.falloffConstants[0], l.falloffConstants[1], l.falloffConstants[2], l.falloffConstants[3]);
    copy4(g.coneType, l.cone[0], l.cone[1], l.cone[2], float(uint32_t(l.type)));
    return g;
}

std::string worldLightsGlsl() {
    std::string out;
    out += "// WORLDLIGHTS records evaluated in shaders (docs/world-lights-format.md, docs/lightcache.md).\n";
    out += "// Generated by q3sh-glsl world-lights from libs/sh; regenerate instead of editing.\n";
    out += "// Pack records with packWorldLightGpu (libs/sh/world_lights_glsl.h); p and n in BSP axes.\n";
    out += intConstant("WL_TYPE_POINT", uint32_t(WorldLightType::Point));
    out += intConstant("WL_TYPE_SPOT", uint32_t(WorldLightType::Spot));
    out += intConstant("WL_TYPE_SUN", uint32_t(WorldLightType::Sun));
    out += intConstant("WL_FALLOFF_INVERSE_SQUARE", uint32_t(WorldLightFalloff::InverseSquare));
    out += intConstant("WL_FALLOFF_LINEAR", uint32_t(WorldLightFalloff::Linear));
    out += intConstant("WL_FALLOFF_CONTROLLED", uint32_t(WorldLightFalloff::Controlled));
    out += intConstant("WL_FALLOFF_PARALLEL", uint32_t(WorldLightFalloff::Parallel));
    out += floatConstant("WL_CONTROLLED_SQUARE_START", kControlledSquareStart);
    out += floatConstant("WL_DEGREES_PER_RADIAN", kDegreesPerRadian);
    out += kFunctions;
    return out;
}

}  // namespace q3::sh
