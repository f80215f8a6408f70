// The light cache query: cull by visibility and reach, rank by strength, trace the strongest until
// the caller's local slots are full, and fold the rest into the SH probe.
#include "light_cache.h"

#include <algorithm>
#include <cmath>

#include "sh.h"

namespace q3::sh {
namespace {

struct Candidate {
    float strength;  // |luminance| of the arriving light: negative lights rank by their size too
    uint32_t index;
    std::array<float, 3> arriving;
};

// Strongest first; equal strengths in record order, so results never depend on the sort.
bool ranksBefore(const Candidate& a, const Candidate& b) {
    return a.strength != b.strength ? a.strength > b.strength : a.index < b.index;
}

std::string withName(const std::string& name, const std::string& message) {
    return name.empty() ? message : name + ": " + message;
}

bool finitePoint(const float p[3]) { return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]); }

// The direction evaluateWorldLight lights a surface from, or false when it lights nothing from
// the point (a light exactly at the point, other than a controlled one).
bool towardsLight(const WorldLight& light, const float position[3], Vec3d& out) {
    if (light.type == WorldLightType::Sun) {
        out = {light.direction[0], light.direction[1], light.direction[2]};
        return true;
    }
    out = normalized({double(light.origin[0]) - position[0], double(light.origin[1]) - position[1],
                      double(light.origin[2]) - position[2]});
    if (out.x == 0 && out.y == 0 && out.z == 0) {
        if (light.falloff != WorldLightFalloff::Controlled) return false;
        out = {0, 0, 1};
    }
    return true;
}

}  // namespace

float luminance(const std::array<float, 3>& rgb) { return 0.2126f * rgb[0] + 0.7152f * rgb[1] + 0.0722f * rgb[2]; }

std::string LightCache::loadFromBsp(const uint8_t* bsp, size_t size, const std::string& name) {
    world_ = BspCollision{};
    lights_.clear();
    if (std::string err = grid_.loadFromBsp(bsp, size, name); !err.empty()) return err;
    std::string err;
    BspDirectory dir;
    err = readBspDirectory(bsp, size, dir);
    if (err.empty()) err = loadBspCollision(dir, world_);
    ByteRange lump;
    bool found = false;
    if (err.empty()) err = findBspxLump(bsp, size, dir, kWorldLightsLumpName, lump, found);
    if (err.empty() && found) decodeWorldLights(lump.data, lump.size, lights_, err);
    for (size_t i = 0; err.empty() && i < lights_.size(); ++i)
        if (world_.hasVisibility() && lights_[i].cluster >= world_.numClusters)
            err = "WORLDLIGHTS: light " + std::to_string(i) + " cluster " + std::to_string(lights_[i].cluster) +
                  " is not below the map's " + std::to_string(world_.numClusters) + " clusters";
    if (err.empty()) return {};
    *this = LightCache{};  // a failed load keeps nothing
    return withName(name, err);
}

bool LightCache::reaches(const WorldLight& light, const float position[3]) const {
    if (light.type == WorldLightType::Sun) {
        float end[3];
        for (int axis = 0; axis < 3; ++axis) end[axis] = position[axis] + light.direction[axis] * kSunTraceDistance;
        const RayHit hit = traceRay(world_, position, end, false);
        return !hit.hit || hit.sky;
    }
    return !traceRay(world_, position, light.origin.data(), true).hit;
}

LightCacheResult LightCache::query(const float position[3], int maxLocal) const {
    LightCacheResult result;
    result.probe = grid_.sample(position);
    if (!finitePoint(position) || world_.leafs.empty()) return result;
    result.leaf = pointLeaf(world_, position);
    result.cluster = world_.leafs[result.leaf].cluster;
    maxLocal = std::clamp(maxLocal, 0, kMaxLocalLights);

    std::vector<Candidate> candidates;
    candidates.reserve(lights_.size());
    const std::array<float, 3> point{position[0], position[1], position[2]};
    for (uint32_t i = 0; i < lights_.size(); ++i) {
        const WorldLight& light = lights_[i];
        // Already in the grid's probe: adding it again would count it twice (docs/lightcache.md).
        if (light.flags & kWorldLightInShGrid) continue;
        if (light.type != WorldLightType::Sun && !clusterVisible(world_, result.cluster, light.cluster)) continue;
        const std::array<float, 3> arriving = worldLightArriving(light, point);  // radius, cone, falloff
        if (arriving[0] == 0 && arriving[1] == 0 && arriving[2] == 0) continue;
        candidates.push_back({std::fabs(luminance(arriving)), i, arriving});
    }
    std::sort(candidates.begin(), candidates.end(), ranksBefore);

    // Every candidate is traced: a blocked light neither takes a local slot nor reaches the probe.
    SH9Color rest;
    for (const Candidate& c : candidates) {
        const WorldLight& light = lights_[c.index];
        if (!reaches(light, position)) {
            ++result.occludedCount;
            continue;
        }
        if (result.localCount < maxLocal) {
            result.local[result.localCount++] = {c.index, c.arriving};
            continue;
        }
        Vec3d towards;
        if (!towardsLight(light, position, towards)) continue;
        addControlledIncidence(rest, towards, {c.arriving[0], c.arriving[1], c.arriving[2]}, light.incidenceWeight);
        ++result.projectedCount;
    }
    for (int i = 0; i < kCoeffCount; ++i)
        for (int ch = 0; ch < 3; ++ch) result.probe.coeffs[i][ch] += float(rest.c[i][ch]);
    return result;
}

}  // namespace q3::sh
