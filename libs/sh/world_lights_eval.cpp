// Unoccluded light of one WORLDLIGHTS record at a point (docs/world-lights-format.md). The float
// operations follow the compiler's own (q3map2's spot and falloff formulas, the controlled model of
// light-models.md), so a record evaluates to what the SH grid projected for its light.
#include <algorithm>
#include <cmath>

#include "world_lights.h"

namespace q3::sh {
namespace {

using V3 = std::array<float, 3>;

V3 sub(const V3& a, const V3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
float dot3(const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
float length3(const V3& a) { return std::sqrt(dot3(a, a)); }
V3 scaled(const V3& a, float s) { return {a[0] * s, a[1] * s, a[2] * s}; }

// q3map2's spot cone: 1 inside, a linear fade over the last `fadeWidth` units of the cone's radius
// at the point's distance along the axis, 0 outside and behind.
float q3map2Spot(const WorldLight& l, const V3& point) {
    const float along = -dot3(sub(l.origin, point), l.direction);
    if (along < 0) return 0;
    const V3 onAxis{l.origin[0] + l.direction[0] * along, l.origin[1] + l.direction[1] * along,
                    l.origin[2] + l.direction[2] * along};
    const float radiusAtDist = l.cone[0] * along;
    const float fromAxis = length3(sub(point, onAxis));
    if (fromAxis >= radiusAtDist) return 0;
    const float fadeWidth = l.cone[1];
    if (fromAxis > radiusAtDist - fadeWidth) return std::max(0.f, (radiusAtDist - fromAxis) / fadeWidth);
    return 1;
}

// Distance falloff times cone of a point or spot light at `point`; `towardsLight` is set.
float pointFactor(const WorldLight& l, const V3& point, V3& towardsLight) {
    const V3 toLight = sub(l.origin, point);
    const float d = length3(toLight);
    towardsLight = d > 0 ? V3{toLight[0] / d, toLight[1] / d, toLight[2] / d} : V3{0, 0, 0};
    if (l.radius > 0 && d > l.radius) return 0;
    const bool spot = l.type == WorldLightType::Spot;
    if (l.falloff == WorldLightFalloff::Controlled) {
        const auto& c = l.falloffConstants;
        const float falloff = controlledFalloffFactor(d, c[0], c[1], c[2]);
        if (falloff <= 0) return 0;
        if (d == 0) towardsLight = {0, 0, 1};
        const float cone =
            spot ? controlledConeFactor(-dot3(towardsLight, l.direction), l.cone[0], l.cone[1], l.cone[2]) : 1.0f;
        return cone <= 0 ? 0 : falloff * cone;
    }
    const float minDistance = l.falloffConstants[0], extra = l.falloffConstants[1];
    const float clamped = std::max(minDistance, std::sqrt(d * d + extra * extra));
    float factor = l.falloff == WorldLightFalloff::Linear ? std::max(0.f, 1 - clamped * l.falloffConstants[3])
                                                          : 1 / (clamped * clamped);
    if (spot) factor *= q3map2Spot(l, point);
    return factor <= l.falloffConstants[2] ? 0 : factor;
}

}  // namespace

float controlledFalloffFactor(float d, float start, float end, float curvature) {
    if (d <= start) return 1;
    if (d >= end) return 0;
    const float lin = 1 - (d - start) / (end - start);
    const float s = std::max(start, kControlledSquareStart);
    const float see = (s * s) / (end * end);
    float isq = see < 1 ? ((s * s) / (d * d) - see) / (1 - see) : lin;
    isq = std::clamp(isq, 0.f, 1.f);
    return (1 - curvature) * lin + curvature * isq;
}

// 1 within the inner half angle, linear in angle down to 0 at the outer one, then lifted by the
// spherical ambient fraction.
float controlledConeFactor(float cosAngle, float inner, float outer, float ambient) {
    const float angle = std::acos(std::clamp(cosAngle, -1.f, 1.f)) * kDegreesPerRadian;
    float cone;
    if (angle <= inner)
        cone = 1;
    else if (angle >= outer)
        cone = 0;
    else
        cone = 1 - (angle - inner) / (outer - inner);
    return ambient + (1 - ambient) * cone;
}

std::array<float, 3> worldLightArriving(const WorldLight& l, const std::array<float, 3>& point) {
    if (l.type == WorldLightType::Sun) return l.intensity;
    V3 towardsLight;
    return scaled(l.intensity, pointFactor(l, point, towardsLight));
}

std::array<float, 3> evaluateWorldLight(const WorldLight& l, const std::array<float, 3>& point,
                                        const std::array<float, 3>& normal) {
    V3 towardsLight = l.direction;
    float factor = 1;
    if (l.type != WorldLightType::Sun) factor = pointFactor(l, point, towardsLight);
    if (factor == 0) return {0, 0, 0};
    const float cosine = dot3(normal, towardsLight);
    if (cosine <= 0) return {0, 0, 0};
    const float incidence = (1 - l.incidenceWeight) + l.incidenceWeight * cosine;
    return scaled(l.intensity, factor * incidence);
}

}  // namespace q3::sh
