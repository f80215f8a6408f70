#include "lightmap_layout_merge.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <numeric>
#include <tuple>

namespace q3::light {

namespace {

constexpr float kEqualEpsilon = 0.001f;  // q3map2 EQUAL_EPSILON for plane comparisons

struct Info {
    Vec3 axis;
    bool planar = false;
    bool curved = false;
    Vec3 normal;
    float dist = 0.0f;
    Bounds bounds;
};

Info infoFor(const SurfaceLightmapInput& in) {
    Info info;
    const SurfaceGeometry& g = in.geometry;
    info.axis = lightmapProjectionAxis(g, in.params);
    info.curved = dot(info.axis, info.axis) == 0.0f;
    info.planar = dot(g.planeNormal, g.planeNormal) > 0.0f && !g.positions.empty();
    if (info.planar) {
        info.normal = g.planeNormal;
        info.dist = dot(g.positions[0], g.planeNormal);
    }
    for (const Vec3& p : g.positions) info.bounds.add(p);
    return info;
}

bool nearlyEqual(Vec3 a, Vec3 b) {
    return std::fabs(a.x - b.x) <= kEqualEpsilon && std::fabs(a.y - b.y) <= kEqualEpsilon &&
           std::fabs(a.z - b.z) <= kEqualEpsilon;
}

// q3map2 CompareSurfaceInfo ordering, with the input index as the final tie-break.
bool sortsBefore(const SurfaceLightmapInput& a, const Info& ia, size_t ai, const SurfaceLightmapInput& b,
                 const Info& ib, size_t bi) {
    if (a.traits.model != b.traits.model) return a.traits.model > b.traits.model;
    if (a.traits.shader != b.traits.shader) return a.traits.shader < b.traits.shader;
    if (a.params.sampleSize != b.params.sampleSize) return a.params.sampleSize > b.params.sampleSize;
    for (int i = 0; i < 3; ++i)
        if (ia.axis[i] != ib.axis[i]) return ia.axis[i] > ib.axis[i];
    if (ia.planar != ib.planar) return ia.planar;
    if (ia.planar) {
        for (int i = 0; i < 3; ++i)
            if (ia.normal[i] != ib.normal[i]) return ia.normal[i] > ib.normal[i];
        if (ia.dist != ib.dist) return ia.dist > ib.dist;
    }
    for (int i = 0; i < 3; ++i)
        if (ia.bounds.mins[i] != ib.bounds.mins[i]) return ia.bounds.mins[i] > ib.bounds.mins[i];
    return ai < bi;
}

// q3map2 AddSurfaceToRawLightmap's acceptance test for a surface joining a group.
bool canJoin(const SurfaceLightmapInput& first, const Info& firstInfo, const Bounds& groupBounds,
             const SurfaceLightmapInput& cand, const Info& info) {
    if (info.curved || firstInfo.curved) return false;
    if (!(info.axis == firstInfo.axis)) return false;
    const LightmapMergeTraits& a = first.traits;
    const LightmapMergeTraits& b = cand.traits;
    if (a.model != b.model || first.params.sampleSize != cand.params.sampleSize || a.entity != b.entity ||
        a.receiveShadows != b.receiveShadows || first.params.pageWidth != cand.params.pageWidth ||
        first.params.pageHeight != cand.params.pageHeight || a.brightness != b.brightness ||
        a.filterRadius != b.filterRadius || a.splotchFix != b.splotchFix)
        return false;
    if (!info.bounds.intersects(groupBounds)) return false;
    if (!b.mergeable) {
        if (!info.planar || !firstInfo.planar) return false;
        if (!nearlyEqual(info.normal, firstInfo.normal) || std::fabs(info.dist - firstInfo.dist) > kEqualEpsilon)
            return false;
    }
    return true;
}

// What canJoin requires a candidate to share with a group's first surface, as one sortable key
// (floats by value: -0 as +0; a NaN makes its own key, and canJoin rejects it anyway).
using JoinKey = std::tuple<int, int, int, int, int, int, uint32_t, uint32_t, bool, uint32_t, uint32_t, uint32_t>;

uint32_t keyBits(float v) {
    const float normal = v + 0.0f;
    uint32_t bits = 0;
    std::memcpy(&bits, &normal, sizeof bits);
    return bits;
}

JoinKey joinKey(const SurfaceLightmapInput& in, const Info& info) {
    const LightmapMergeTraits& t = in.traits;
    return {t.model,
            in.params.sampleSize,
            t.entity,
            t.receiveShadows,
            in.params.pageWidth,
            in.params.pageHeight,
            keyBits(t.brightness),
            keyBits(t.filterRadius),
            t.splotchFix,
            keyBits(info.axis.x),
            keyBits(info.axis.y),
            keyBits(info.axis.z)};
}

}  // namespace

std::vector<std::vector<size_t>> groupSurfacesForLightmaps(std::span<const SurfaceLightmapInput> inputs) {
    std::vector<Info> infos;
    infos.reserve(inputs.size());
    for (const SurfaceLightmapInput& in : inputs) infos.push_back(infoFor(in));
    std::vector<size_t> order(inputs.size());
    std::iota(order.begin(), order.end(), size_t{0});
    std::sort(order.begin(), order.end(),
              [&](size_t a, size_t b) { return sortsBefore(inputs[a], infos[a], a, inputs[b], infos[b], b); });

    // Only surfaces alike in everything canJoin compares can join one group: each scans the later
    // surfaces of its own kind (in sorted order), not every later surface of the map.
    std::map<JoinKey, std::vector<size_t>> kinds;  // sorted positions of each kind's surfaces
    std::vector<const std::vector<size_t>*> kindOf(order.size());
    for (size_t oi = 0; oi < order.size(); ++oi) {
        std::vector<size_t>& kind = kinds[joinKey(inputs[order[oi]], infos[order[oi]])];
        kind.push_back(oi);
    }
    for (const auto& [key, positions] : kinds)
        for (const size_t oi : positions) kindOf[oi] = &positions;

    std::vector<uint8_t> assigned(inputs.size(), 0);
    std::vector<std::vector<size_t>> groups;
    for (size_t oi = 0; oi < order.size(); ++oi) {
        const size_t first = order[oi];
        if (assigned[first]) continue;
        assigned[first] = 1;
        std::vector<size_t> group{first};
        Bounds bounds = infos[first].bounds;
        const std::vector<size_t>& kind = *kindOf[oi];
        const auto later = std::upper_bound(kind.begin(), kind.end(), oi);
        // Exhaustive: a surface added later can make earlier rejected ones touch the group.
        for (bool added = true; added && !infos[first].curved;) {
            added = false;
            for (auto it = later; it != kind.end(); ++it) {
                const size_t cand = order[*it];
                // The box test first: most surfaces of a kind lie elsewhere in the map.
                if (assigned[cand] || !infos[cand].bounds.intersects(bounds) ||
                    !canJoin(inputs[first], infos[first], bounds, inputs[cand], infos[cand]))
                    continue;
                assigned[cand] = 1;
                group.push_back(cand);
                bounds.add(infos[cand].bounds);
                added = true;
            }
        }
        groups.push_back(std::move(group));
    }
    return groups;
}

std::vector<RawLightmap> layoutMergedLightmaps(std::span<const SurfaceLightmapInput> inputs, const LayoutOptions& options,
                                               Log* log) {
    std::vector<RawLightmap> out;
    for (const std::vector<size_t>& group : groupSurfacesForLightmaps(inputs)) {
        std::vector<SurfaceGeometry> geometries;
        geometries.reserve(group.size());
        for (size_t i : group) geometries.push_back(inputs[i].geometry);
        if (auto lm = layoutSurfaceGroup(geometries, inputs[group[0]].params, options, log)) out.push_back(std::move(*lm));
    }
    return out;
}

}  // namespace q3::light
