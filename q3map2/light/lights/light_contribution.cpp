// Light contributions to luxels, vertices and grid points (see light_contribution.h).
#include "light_contribution.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

#include "angle.h"
#include "bsp_tree.h"
#include "contribution_lanes.h"
#include "sky_visibility.h"
#include "trace_scene.h"
#include "world_lights.h"

namespace q3::light {
namespace {

using contribution::kLinearScale;
using contribution::kMinDistance;
constexpr float kSpotFadeWidth = 32.0f;  // spot cones fade over their last 32 units

float clampedDistance(float dist, float extraDist) {
    return std::max(kMinDistance, std::sqrt(dist * dist + extraDist * extraDist));
}

// Spot cone factor of q3map2 (1 inside, linear fade over the last 32 units, 0 outside), or
// nullopt when the point is behind the spotlight or outside its cone.
std::optional<float> spotFactor(const Light& light, Vec3 point) {
    const Vec3 displacement = light.origin - point;
    const float distByNormal = -dot(displacement, light.normal);
    if (distByNormal < 0) return std::nullopt;
    const Vec3 pointAtDist = light.origin + light.normal * distByNormal;
    const float radiusAtDist = light.radiusByDist * distByNormal;
    const float sampleRadius = length(point - pointAtDist);
    if (sampleRadius >= radiusAtDist) return std::nullopt;
    if (sampleRadius > radiusAtDist - kSpotFadeWidth)
        return std::max(0.f, (radiusAtDist - sampleRadius) / kSpotFadeWidth);
    return 1.0f;
}

float angleTerm(float dot, bool twoSided, bool halfLambert) {
    if (twoSided && dot < 0) dot = -dot;
    if (halfLambert) {
        if (dot > 0.001f) {
            dot = std::min(dot, 1.0f) * 0.5f + 0.5f;
            dot *= dot;
        } else {
            dot = 0;
        }
    }
    return dot;
}

// What becomes of a segment's shadow ray when the rays are deferred: appended to env.deferredRays,
// or, too short for an occluder to count, settled at once by structural solid alone (the scene
// tests the other rays for solid itself, after Embree, so that blocked rays skip the tree walk).
enum class DeferredRay { Queued, Open, Blocked };

// The segment from `from` to `to`, `dist` long in unit `direction` (as segmentRay computes them).
[[gnu::always_inline]] inline DeferredRay deferShadowRay(const LightingEnv& env, Vec3 from, Vec3 to, Vec3 direction,
                                                          float dist) {
    std::optional<ShadowRay> ray = TraceScene::segmentRayAlong(from, direction, dist, env.settings.ignoreNear);
    if (!ray) return !env.clearOfSolid && env.scene->crossesSolid(from, to) ? DeferredRay::Blocked : DeferredRay::Open;
    ray->mask = env.rayMask;
    ray->clearOfSolid = env.clearOfSolid;
    env.deferredRays->push_back(*ray);
    return DeferredRay::Queued;
}

Vec3 occlusion(const LightingEnv& env, Vec3 from, Vec3 to) {
    if (!env.scene) return {1, 1, 1};
    if (!env.deferredRays)
        return env.scene->transmission(from, to, env.settings.ignoreNear, env.rayMask, env.clearOfSolid);
    const Vec3 d = to - from;
    const float dist = length(d);
    const DeferredRay ray = deferShadowRay(env, from, to, dist > 0 ? d / dist : Vec3{}, dist);
    return ray == DeferredRay::Blocked ? Vec3{} : Vec3{1, 1, 1};
}

Vec3 skyOcclusion(const LightingEnv& env, const Light& sun, Vec3 from) {
    if (!env.scene) return {1, 1, 1};
    if (env.deferredRays) {
        // Sun normals are unit vectors already (skyRay would normalise again).
        env.deferredRays->push_back(ShadowRay{from, sun.normal, TraceScene::firstTestedDepth(env.settings.ignoreNear),
                                              std::numeric_limits<float>::infinity(), true, sun.skyIndex,
                                              env.rayMask});
        return {1, 1, 1};
    }
    return env.scene->skyTransmission(from, sun.normal, sun.skyIndex, env.settings.ignoreNear, env.rayMask);
}

std::optional<LightContribution> finish(const Light& light, Vec3 color, Vec3 direction, Vec3 transmission) {
    Vec3 c = color * transmission;
    if (c == Vec3{}) return std::nullopt;
    return LightContribution{c, direction, light.style};
}

// Controlled model; `normal` null for grid points (no incidence term).
std::optional<LightContribution> controlledContribution(const Light& light, Vec3 point, const Vec3* normal,
                                                        bool twoSided, const LightingEnv& env) {
    const ControlledParams& p = *light.controlled;
    if (light.type == LightType::Sun) {
        const Vec3 l = light.normal;
        float incidence = 1;
        if (normal) {
            float c = dot(*normal, l);
            if (twoSided && c < 0) c = -c;
            if (c <= 0) return std::nullopt;
            incidence = c;  // suns force dot_product_weight 1
        }
        Vec3 value = light.color * (255.0f * p.brightness * incidence);
        if (value == Vec3{}) return std::nullopt;
        return finish(light, value, l, skyOcclusion(env, light, point));
    }
    const Vec3 toLight = light.origin - point;
    const float d = length(toLight);
    const float falloff = controlledFalloff(p, d);
    if (falloff <= 0) return std::nullopt;
    const Vec3 l = d > 0 ? toLight / d : Vec3{0, 0, 1};
    const float cone = light.type == LightType::Spot ? controlledCone(p, light.normal, l) : 1.0f;
    if (cone <= 0) return std::nullopt;
    float incidence = 1;
    if (normal) {
        float c = dot(*normal, l);
        if (twoSided && c < 0) c = -c;
        incidence = controlledIncidence(p, c);
        if (incidence <= 0) return std::nullopt;
    }
    Vec3 value = light.color * (255.0f * p.brightness * falloff * cone * incidence);
    if (value == Vec3{}) return std::nullopt;
    return finish(light, value, l, occlusion(env, point, light.origin));
}

// The least and greatest of `offset` + n . p over the points p of `box`, summed axis by axis.
std::pair<float, float> rangeAlong(Vec3 n, const Bounds& box, float offset = 0) {
    float lo = offset, hi = offset;
    for (int k = 0; k < 3; ++k) {
        lo += n[k] * (n[k] >= 0 ? box.mins[k] : box.maxs[k]);
        hi += n[k] * (n[k] >= 0 ? box.maxs[k] : box.mins[k]);
    }
    return {lo, hi};
}

// pvsCulled, inlined where every sample asks it.
[[gnu::always_inline]] inline bool pvsCulledInline(const Light& light, int cluster, const LightingEnv& env) {
    if (light.type == LightType::Sun) return env.skies && !env.skies->maySeeSky(cluster, light.skyIndex);
    return env.tree && cluster >= 0 && light.cluster >= 0 && !env.tree->clusterVisible(cluster, light.cluster);
}

// Most area-light pairs inside the envelope end below the -fast tolerance: the cheap bound rejects
// those before the exact form factor, with the outcome the exact factor would give.
[[gnu::always_inline]] inline bool surelyBelowFastTolerance(const Light& light, Vec3 pushed, Vec3 normal,
                                                            const LightingEnv& env) {
    return (light.fast || env.settings.forceFast) && light.add > 0 &&
           formFactorUpperBound(light.emitter, pushed, normal) * light.add <= light.falloffTolerance;
}

// q3map2's point or spot light at a luxel or vertex before occlusion: the light's amount (0 when
// it sends none: beyond the envelope, outside the cone, or under the -fast tolerance), with the
// distance to the light and the direction towards it (the normal when the point is the light's).
[[gnu::always_inline]] inline float pointLightAdd(const Light& light, Vec3 p, Vec3 n, bool twoSided, float envelope,
                                                  const ContributionSettings& settings, float& dist, Vec3& dir) {
    const Vec3 toLight = light.origin - p;
    dist = length(toLight);
    if (dist >= envelope) return 0;
    dir = dist > 0 ? toLight / dist : n;
    const float clamped = clampedDistance(dist, light.extraDist);
    float angle = light.angleAttenuation ? angleTerm(dot(n, dir), twoSided, settings.lightAngleHL) : 1;
    if (light.angleScale != 0) angle = std::min(angle / light.angleScale, 1.0f);
    float add = light.linear ? std::max(0.f, angle * light.photons * kLinearScale - clamped * light.fade)
                             : std::max(0.f, light.photons / (clamped * clamped) * angle);
    if (light.type == LightType::Spot) {
        std::optional<float> cone = spotFactor(light, p);
        if (!cone) return 0;
        add *= *cone;
    }
    if (add <= 0 || ((light.fast || settings.forceFast) && add <= light.falloffTolerance)) return 0;
    return add;
}

// areaLightAdd's end without -faster, once the point is pushed off the emitter's plane and past the
// -fast bound: the light from the exact form factor `factor`, and for a two-sided emitter seen from
// its back the point behind it that the shadow ray aims at. `target`, `dist` and `dir` come in as
// those towards the emitter's origin.
[[gnu::always_inline]] inline float areaLightAddFromFactor(const Light& light, float factor, Vec3 p, Vec3 n,
                                                           bool twoSided, float envelope, const LightingEnv& env,
                                                           Vec3& target, float& dist, Vec3& dir) {
    if (factor == 0) return 0;
    if (factor < 0) {
        if (!(twoSided || light.twoSided)) return 0;
        factor = -factor;
        target = light.origin - light.normal * 2.0f;  // trace to the emitter's other side
        const Vec3 toLight = target - p;
        dist = length(toLight);
        if (dist >= envelope) return 0;
        dir = dist > 0 ? toLight / dist : n;
    }
    const float add = factor * light.add;
    if (add <= 0 || ((light.fast || env.settings.forceFast) && add <= light.falloffTolerance)) return 0;
    return add;
}

// The same, taking the form factor at the pushed point itself (one point at a time).
[[gnu::always_inline]] inline float areaLightFormFactorAdd(const Light& light, Vec3 p, Vec3 n, bool twoSided,
                                                           float envelope, const LightingEnv& env, Vec3 pushed,
                                                           Vec3& target, float& dist, Vec3& dir) {
    return areaLightAddFromFactor(light, pointToPolygonFormFactor(pushed, n, light.winding), p, n, twoSided, envelope,
                                  env, target, dist, dir);
}

// q3map2's area light at a luxel or vertex before occlusion: the light's amount (0 when it sends
// none), the point its shadow ray aims at (the emitter's origin, or just behind it for a two-sided
// emitter seen from its back), and the unclamped distance and direction to that point.
[[gnu::always_inline]] inline float areaLightAdd(const Light& light, Vec3 p, Vec3 n, bool twoSided, float envelope,
                                                 const LightingEnv& env, Vec3& target, float& dist, Vec3& dir) {
    const float d = dot(p, light.normal) - light.planeDist;
    if (d < 3.0f) {
        if (!light.twoSided && d < -1.0f) return 0;                // behind the emitter
        if (d > -3.0f && dot(n, light.normal) > 0.9f) return 0;  // coplanar with it
    }
    // Points close to the emitter plane are pushed in front of it, so that surfaces meeting an
    // emitter do not get black edges.
    const Vec3 pushed = (d > -8.0f && d < 8.0f) ? p + light.normal * (8.0f - d) : p;
    target = light.origin;
    Vec3 toLight = target - p;
    dist = length(toLight);
    if (dist >= envelope) return 0;
    dir = dist > 0 ? toLight / dist : n;
    float add;
    if (env.settings.faster) {
        float angle = dot(n, dir);
        if (twoSided && angle < 0) angle = -angle;
        angle *= -dot(light.normal, dir);
        if (angle == 0) return 0;
        if (angle < 0 && (twoSided || light.twoSided)) angle = -angle;
        const float clamped = clampedDistance(dist, light.extraDist);
        add = light.photons / (clamped * clamped) * angle;
    } else {
        if (surelyBelowFastTolerance(light, pushed, n, env)) return 0;
        return areaLightFormFactorAdd(light, p, n, twoSided, envelope, env, pushed, target, dist, dir);
    }
    if (add <= 0 || ((light.fast || env.settings.forceFast) && add <= light.falloffTolerance)) return 0;
    return add;
}

// q3map2's point or spot light at a grid point `dist` from it (the unclamped distance), before
// the -fast tolerance and occlusion.
[[gnu::always_inline]] inline float pointLightAtGridPoint(const Light& light, Vec3 origin, float dist) {
    dist = clampedDistance(dist, light.extraDist);
    float add = light.linear ? std::max(0.f, light.photons * kLinearScale - dist * light.fade)
                             : light.photons / (dist * dist);
    if (light.type == LightType::Spot) {
        std::optional<float> cone = spotFactor(light, origin);
        if (!cone) return 0;
        add *= *cone;
    }
    return add;
}

// areaLightAtGridPoint's end without -faster, once the point is pushed off the emitter's plane and
// past the -fast bound: from the exact form factor with the direction to the light as the normal.
[[gnu::always_inline]] inline float areaLightGridAddFromFactor(const Light& light, float factor) {
    if (factor == 0) return 0;
    if (factor < 0) {
        if (!light.twoSided) return 0;
        factor = -factor;
    }
    return factor * light.add;
}

// q3map2's area light at a grid point `dist` from its origin in direction `dir` (the grid point's
// normal), before the -fast tolerance and occlusion; 0 when it sends none.
[[gnu::always_inline]] inline float areaLightAtGridPoint(const Light& light, Vec3 origin, float dist, Vec3 dir,
                                                         const LightingEnv& env) {
    if (env.settings.faster) {
        dist = clampedDistance(dist, light.extraDist);
        return light.photons / (dist * dist);
    }
    const float d = dot(origin, light.normal) - light.planeDist;
    if (!light.twoSided && d < -1.0f) return 0;
    const Vec3 pushed = (d > -8.0f && d < 8.0f) ? origin + light.normal * (8.0f - d) : origin;
    if (surelyBelowFastTolerance(light, pushed, dir, env)) return 0;
    return areaLightGridAddFromFactor(light, pointToPolygonFormFactor(pushed, dir, light.winding));
}

}  // namespace

bool pvsCulled(const Light& light, int cluster, const LightingEnv& env) {
    return pvsCulledInline(light, cluster, env);
}

bool areaLightSurelyDarkIn(const Light& light, const Bounds& box, const ContributionSettings& settings,
                           const Vec3* receiverNormal) {
    if (light.type != LightType::Area || light.controlled || settings.faster || box.empty()) return false;
    // The box's least and greatest height over the emitter's plane.
    const auto [lowest, highest] = rangeAlong(light.normal, box, -light.planeDist);
    // The per-point tests drop points more than 1 unit behind a one-sided emitter.
    if (!light.twoSided && highest < -1.01f) return true;
    if (!(light.fast || settings.forceFast) || !(light.add > 0) || light.emitter.radius < 0) return false;
    // Points within 8 units of the emitter's plane are pushed to 8 in front of it: under 16 units.
    // A box wholly beyond that band (with a unit to spare for the roundings) holds no pushed point.
    const float pushReach = (lowest >= 9.0f || highest <= -9.0f) ? 0.0f : 16.0f;
    // The nearer of two lower bounds of the distance between the box and the polygon: to the
    // emitter's sphere and to its corners' box.
    const Vec3 nearestInBox = vmin(vmax(light.emitter.center, box.mins), box.maxs);
    Vec3 gap;
    for (int k = 0; k < 3; ++k)
        gap[k] = std::max({0.0f, light.emitter.box.mins[k] - box.maxs[k], box.mins[k] - light.emitter.box.maxs[k]});
    const float nearest = std::max(distance(nearestInBox, light.emitter.center) - light.emitter.radius, length(gap)) -
                          pushReach;
    if (!(nearest > 1.0f)) return false;
    // The emitter's cosine is at most the box's greatest height over the emitter's plane (pushed
    // points sit 8 units above it) over the nearest distance. The extra 10 % in the bound below
    // keeps it above every per-point one whatever their roundings.
    float emitterCosine = 1;
    if (light.emitter.flat) {
        float height = 0;
        for (int corner = 0; corner < 8; ++corner) {
            const Vec3 c{(corner & 1) ? box.maxs.x : box.mins.x, (corner & 2) ? box.maxs.y : box.mins.y,
                         (corner & 4) ? box.maxs.z : box.mins.z};
            height = std::max(height, std::fabs(dot(c - light.emitter.center, light.emitter.planeNormal)));
        }
        emitterCosine = std::min(1.0f, (height + pushReach + light.emitter.flatness) / nearest);
    }
    // The receiver's: the greatest |normal . (corner - point)| over the emitter's corner box and the
    // box, over the nearest distance (a push moves a point by under pushReach).
    float receiverCosine = 1;
    if (receiverNormal) {
        const auto [emitterLo, emitterHi] = rangeAlong(*receiverNormal, light.emitter.box);
        const auto [boxLo, boxHi] = rangeAlong(*receiverNormal, box);
        const float reach = std::max(std::fabs(emitterHi - boxLo), std::fabs(emitterLo - boxHi)) + pushReach;
        receiverCosine = std::min(1.0f, reach / nearest);
    }
    const float bound = light.emitter.area * receiverCosine * emitterCosine / (kPi * nearest * nearest) * 1.1f + 1e-5f;
    return bound * light.add <= light.falloffTolerance;
}

float controlledFalloff(const ControlledParams& p, float d) {
    return sh::controlledFalloffFactor(d, p.falloffStart, p.falloffEnd, p.falloffCurvature);
}

float controlledCone(const ControlledParams& p, Vec3 spotAxis, Vec3 towardsLight) {
    return sh::controlledConeFactor(dot(-towardsLight, spotAxis), p.angleHotspot * 0.5f, p.anglePenumbra * 0.5f,
                                    p.sphericalAmbient);
}

float controlledIncidence(const ControlledParams& p, float cosine) {
    if (cosine <= 0) return 0;
    return (1 - p.dotProductWeight) + p.dotProductWeight * cosine;
}

std::optional<LightContribution> lightToSample(const Light& light, const SamplePoint& sample, const LightingEnv& env) {
    return lightToSample(light, sample, env, lightEnvelope(light, env.settings.forceFast));
}

std::optional<LightContribution> lightToSample(const Light& light, const SamplePoint& sample, const LightingEnv& env,
                                               float envelope) {
    if (!light.affectsSurfaces) return std::nullopt;
    const Vec3 p = sample.origin;
    const Vec3 n = sample.normal;
    if (light.type != LightType::Sun) {
        if (env.settings.sunOnly) return std::nullopt;
        if (!sample.twoSided && dot(light.origin, n) - dot(p, n) < 0) return std::nullopt;  // behind the surface
    }
    if (pvsCulledInline(light, sample.cluster, env)) return std::nullopt;
    if (light.controlled) return controlledContribution(light, p, &n, sample.twoSided, env);

    switch (light.type) {
        case LightType::Sun: {
            const Vec3 dir = light.normal;
            float angle = light.angleAttenuation ? angleTerm(dot(n, dir), sample.twoSided, env.settings.lightAngleHL) : 1;
            const float add = light.photons * angle;
            if (add <= 0) return std::nullopt;
            return finish(light, light.color * add, dir, skyOcclusion(env, light, p));
        }
        case LightType::Point:
        case LightType::Spot: {
            Vec3 dir;
            float dist;
            const float add = pointLightAdd(light, p, n, sample.twoSided, envelope, env.settings, dist, dir);
            if (add <= 0) return std::nullopt;
            return finish(light, light.color * add, dir, occlusion(env, p, light.origin));
        }
        case LightType::Area: {
            Vec3 target, dir;
            float dist;
            const float add = areaLightAdd(light, p, n, sample.twoSided, envelope, env, target, dist, dir);
            if (add <= 0) return std::nullopt;
            return finish(light, light.color * add, dir, occlusion(env, p, target));
        }
    }
    return std::nullopt;
}

std::optional<LightContribution> lightToGridPoint(const Light& light, Vec3 origin, int cluster,
                                                  const LightingEnv& env) {
    return lightToGridPoint(light, origin, cluster, env, lightEnvelope(light, env.settings.forceFast));
}

std::optional<LightContribution> lightToGridPoint(const Light& light, Vec3 origin, int cluster,
                                                  const LightingEnv& env, float envelope) {
    if (!light.affectsGrid) return std::nullopt;
    if (light.type != LightType::Sun && env.settings.sunOnly) return std::nullopt;
    if (pvsCulledInline(light, cluster, env)) return std::nullopt;
    if (light.controlled) return controlledContribution(light, origin, nullptr, false, env);

    if (light.type == LightType::Sun) {
        if (light.photons <= 0) return std::nullopt;
        return finish(light, light.color * light.photons, light.normal, skyOcclusion(env, light, origin));
    }
    const Vec3 toLight = light.origin - origin;
    float dist = length(toLight);
    if (dist > envelope) return std::nullopt;
    // A light on the point has no direction (q3map2 normalises the zero vector to zero): all of its
    // light goes to the ambient part, none to the point's main direction.
    const Vec3 dir = dist > 0 ? toLight / dist : Vec3{};
    const float add = light.type == LightType::Area ? areaLightAtGridPoint(light, origin, dist, dir, env)
                                                    : pointLightAtGridPoint(light, origin, dist);
    if (add <= 0 || ((light.fast || env.settings.forceFast) && add <= light.falloffTolerance)) return std::nullopt;
    return finish(light, light.color * add, dir, occlusion(env, origin, light.origin));
}

bool samplesBatchable(const Light& light, const LightingEnv& env) {
    return light.type != LightType::Sun && !light.controlled && light.affectsSurfaces && !env.settings.sunOnly &&
           env.scene && env.deferredRays;
}

namespace {

using namespace contribution;

// The lanes of `candidates` (a mask of four) whose cluster the PVS lets the light reach; a run of
// lanes in one cluster asks once, `lastCluster` and `lastCulled` carrying the verdict between calls.
template <typename ClusterOf>
int lanesSeenThroughPvs(int candidates, ClusterOf clusterOf, const Light& light, const LightingEnv& env,
                        int& lastCluster, bool& lastCulled) {
    int seen = 0;
    for (int l = 0; l < 4; ++l) {
        if (!(candidates & (1 << l))) continue;
        const int cluster = clusterOf(l);
        if (cluster != lastCluster) {
            lastCluster = cluster;
            lastCulled = pvsCulledInline(light, cluster, env);
        }
        if (!lastCulled) seen |= 1 << l;
    }
    return seen;
}

template <bool area>
void lightToSamplesOf(const Light& light, const LightingEnv& env, float envelope,
                      std::span<const std::optional<SamplePoint>> points, std::span<const uint32_t> which,
                      std::span<Vec3> out, Vec3* dirs, std::vector<size_t>& traced) {
    // The PVS verdict of the last cluster asked: runs of samples share one.
    int lastCluster = -2;
    bool lastCulled = false;
    size_t first = 0;
    // Four samples at a time (point lights, and area lights up to their form factor); a lane the
    // lanes leave open takes the scalar path below. `prepare` gets the lanes still lit after the
    // PVS; `laneAdd` gives such a lane's light and may move the point its ray aims at, with that
    // ray's distance and direction.
    auto byLanes = [&](auto& lanes, auto makeLanes, auto prepare, auto laneAdd) {
        const SamplePoint* four[4];
        for (; first + 4 <= which.size(); first += 4) {
            for (int l = 0; l < 4; ++l) four[l] = &*points[which[first + size_t(l)]];
            makeLanes(four, lanes);
            const int lit = lanesSeenThroughPvs(
                lanes.settled & lanes.candidate, [&](int l) { return four[l]->cluster; }, light, env, lastCluster,
                lastCulled);
            if (lit) prepare(lanes);
            for (int l = 0; l < 4; ++l) {
                const int bit = 1 << l;
                if (!(lanes.settled & bit)) {
                    lightToSamplesOf<area>(light, env, envelope, points, std::span<const uint32_t>(&which[first + size_t(l)], 1),
                                           out, dirs, traced);
                    continue;
                }
                if (!(lit & bit)) continue;
                const uint32_t i = which[first + size_t(l)];
                const SamplePoint& sample = *four[l];
                Vec3 target = light.origin, dir{lanes.dirX[l], lanes.dirY[l], lanes.dirZ[l]};
                float dist = lanes.dist[l];
                const float add = laneAdd(lanes, l, sample, target, dist, dir);
                if (add <= 0) continue;
                const Vec3 color = light.color * add;
                if (color == Vec3{}) continue;
                const DeferredRay ray = deferShadowRay(env, sample.origin, target, dir, dist);
                if (ray == DeferredRay::Blocked) continue;
                if (ray == DeferredRay::Queued) traced.push_back(i);
                out[i] = color;
                if (dirs) dirs[i] = dir;
            }
        }
    };
    if (!area && light.type == LightType::Point) {
        PointLightLanes lanes;
        byLanes(
            lanes,
            [&](const SamplePoint* const* four, PointLightLanes& ln) {
                pointLightLanes(light, env.settings, envelope, four, ln);
            },
            [](PointLightLanes&) {},
            [](const PointLightLanes& ln, int l, const SamplePoint&, Vec3&, float&, Vec3&) { return ln.add[l]; });
    }
    if (area && !env.settings.faster) {
        AreaLightLanes lanes;
        byLanes(
            lanes,
            [&](const SamplePoint* const* four, AreaLightLanes& ln) { areaLightLanes(light, env, envelope, four, ln); },
            [&](AreaLightLanes& ln) { pointToPolygonFormFactor4(ln.pushed, light.winding, ln.factor); },
            [&](const AreaLightLanes& ln, int l, const SamplePoint& sample, Vec3& target, float& dist, Vec3& dir) {
                return areaLightAddFromFactor(light, ln.factor[l], sample.origin, sample.normal, sample.twoSided,
                                              envelope, env, target, dist, dir);
            });
    }
    for (const uint32_t i : which.subspan(first)) {
        const SamplePoint& sample = *points[i];
        const Vec3 p = sample.origin, n = sample.normal;
        if (!sample.twoSided && dot(light.origin, n) - dot(p, n) < 0) continue;  // behind the surface
        if (sample.cluster != lastCluster) {
            lastCluster = sample.cluster;
            lastCulled = pvsCulledInline(light, sample.cluster, env);
        }
        if (lastCulled) continue;
        Vec3 target = light.origin, dir;
        float dist;
        const float add = area ? areaLightAdd(light, p, n, sample.twoSided, envelope, env, target, dist, dir)
                               : pointLightAdd(light, p, n, sample.twoSided, envelope, env.settings, dist, dir);
        if (add <= 0) continue;
        const Vec3 color = light.color * add;
        if (color == Vec3{}) continue;
        // occlusion()'s ray, from the vector, length and direction the contribution already has.
        const DeferredRay ray = deferShadowRay(env, p, target, dir, dist);
        if (ray == DeferredRay::Blocked) continue;
        if (ray == DeferredRay::Queued) traced.push_back(i);
        out[i] = color;
        if (dirs) dirs[i] = dir;
    }
}

}  // namespace

void lightToSamples(const Light& light, const LightingEnv& env, float envelope,
                    std::span<const std::optional<SamplePoint>> points, std::span<const uint32_t> which,
                    std::span<Vec3> out, Vec3* dirs, std::vector<size_t>& traced) {
    if (light.type == LightType::Area)
        lightToSamplesOf<true>(light, env, envelope, points, which, out, dirs, traced);
    else
        lightToSamplesOf<false>(light, env, envelope, points, which, out, dirs, traced);
}

bool gridPointsBatchable(const Light& light, const LightingEnv& env) {
    return light.type != LightType::Sun && !light.controlled && light.affectsGrid && !env.settings.sunOnly &&
           env.scene && env.deferredRays;
}

namespace {

template <bool area>
void lightToGridPointsOf(const Light& light, const LightingEnv& env, float envelope, std::span<const Vec3> origins,
                         std::span<const int> clusters, std::span<const uint32_t> which,
                         std::span<std::optional<LightContribution>> out, std::span<int32_t> rayOf) {
    const bool fast = light.fast || env.settings.forceFast;
    int lastCluster = -2;
    bool lastCulled = false;
    size_t first = 0;
    // Four points at a time (point lights, and area lights up to their form factor); a lane the
    // lanes leave open takes the scalar path below. `prepare` gets the lanes still lit after the
    // PVS; `laneAdd` gives such a lane's light.
    auto byLanes = [&](auto& lanes, auto makeLanes, auto prepare, auto laneAdd) {
        const Vec3* four[4];
        for (; first + 4 <= which.size(); first += 4) {
            for (int l = 0; l < 4; ++l) four[l] = &origins[which[first + size_t(l)]];
            makeLanes(four, lanes);
            const int lit = lanesSeenThroughPvs(
                lanes.settled & lanes.candidate, [&](int l) { return clusters[which[first + size_t(l)]]; }, light, env,
                lastCluster, lastCulled);
            if (lit) prepare(lanes);
            for (int l = 0; l < 4; ++l) {
                const int bit = 1 << l;
                const uint32_t p = which[first + size_t(l)];
                if (!(lanes.settled & bit)) {
                    lightToGridPointsOf<area>(light, env, envelope, origins, clusters,
                                              std::span<const uint32_t>(&which[first + size_t(l)], 1), out, rayOf);
                    continue;
                }
                if (!(lit & bit)) continue;
                const Vec3 dir{lanes.dirX[l], lanes.dirY[l], lanes.dirZ[l]};
                const float add = laneAdd(lanes, l, dir);
                if (add <= 0 || (fast && add <= light.falloffTolerance)) continue;
                const Vec3 color = light.color * add;
                if (color == Vec3{}) continue;
                const int32_t next = int32_t(env.deferredRays->size());
                const DeferredRay ray = deferShadowRay(env, *four[l], light.origin, dir, lanes.dist[l]);
                if (ray == DeferredRay::Blocked) continue;
                if (ray == DeferredRay::Queued) rayOf[p] = next;
                out[p] = LightContribution{color, dir, light.style};
            }
        }
    };
    if (!area && light.type == LightType::Point) {
        PointLightLanes lanes;
        byLanes(
            lanes, [&](const Vec3* const* four, PointLightLanes& ln) { pointLightGridLanes(light, envelope, fast, four, ln); },
            [](PointLightLanes&) {}, [](const PointLightLanes& ln, int l, Vec3) { return ln.add[l]; });
    }
    if (area && !env.settings.faster) {
        AreaLightLanes lanes;
        byLanes(
            lanes, [&](const Vec3* const* four, AreaLightLanes& ln) { areaLightGridLanes(light, env, envelope, four, ln); },
            [&](AreaLightLanes& ln) { pointToPolygonFormFactor4(ln.pushed, light.winding, ln.factor); },
            [&](const AreaLightLanes& ln, int l, Vec3) { return areaLightGridAddFromFactor(light, ln.factor[l]); });
    }
    for (const uint32_t p : which.subspan(first)) {
        if (clusters[p] != lastCluster) {
            lastCluster = clusters[p];
            lastCulled = pvsCulledInline(light, clusters[p], env);
        }
        if (lastCulled) continue;
        const Vec3 origin = origins[p];
        const Vec3 toLight = light.origin - origin;
        const float dist = length(toLight);
        if (dist > envelope) continue;
        // A light on the point has no direction (see lightToGridPoint); the ray is occlusion()'s.
        const Vec3 dir = dist > 0 ? toLight / dist : Vec3{};
        const float add =
            area ? areaLightAtGridPoint(light, origin, dist, dir, env) : pointLightAtGridPoint(light, origin, dist);
        if (add <= 0 || (fast && add <= light.falloffTolerance)) continue;
        const Vec3 color = light.color * add;
        if (color == Vec3{}) continue;
        const int32_t next = int32_t(env.deferredRays->size());
        const DeferredRay ray = deferShadowRay(env, origin, light.origin, dir, dist);
        if (ray == DeferredRay::Blocked) continue;
        if (ray == DeferredRay::Queued) rayOf[p] = next;
        out[p] = LightContribution{color, dir, light.style};
    }
}

}  // namespace

void lightToGridPoints(const Light& light, const LightingEnv& env, float envelope, std::span<const Vec3> origins,
                       std::span<const int> clusters, std::span<const uint32_t> which,
                       std::span<std::optional<LightContribution>> out, std::span<int32_t> rayOf) {
    if (light.type == LightType::Area)
        lightToGridPointsOf<true>(light, env, envelope, origins, clusters, which, out, rayOf);
    else
        lightToGridPointsOf<false>(light, env, envelope, origins, clusters, which, out, rayOf);
}

void gatherSampleLight(std::span<const Light> lights, const SamplePoint& sample, const LightingEnv& env,
                       std::vector<LightContribution>& out) {
    for (const Light& light : lights)
        if (std::optional<LightContribution> c = lightToSample(light, sample, env)) out.push_back(*c);
}

void gatherGridLight(std::span<const Light> lights, Vec3 origin, int cluster, const LightingEnv& env,
                     std::vector<LightContribution>& out) {
    for (const Light& light : lights)
        if (std::optional<LightContribution> c = lightToGridPoint(light, origin, cluster, env)) out.push_back(*c);
}

}  // namespace q3::light
