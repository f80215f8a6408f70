// Where a raw lightmap's super luxels are sampled and how one light reaches them: the sample
// points (q3map2 MapSingleLuxel's nudges and cluster filter), the tiles that let a light skip the
// luxels its envelope misses, the batched light of one light over those tiles, and the quads of
// q3map2's adaptive sub-sampling.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "bsp_tree.h"
#include "light_context.h"
#include "light_contribution.h"
#include "lightmap_filter.h"
#include "lightmap_layout.h"
#include "lights.h"
#include "surface_lighting.h"
#include "trace_scene.h"
#include "vec3.h"

namespace q3::light {

constexpr float kLuxelEpsilon = 0.125f;  // LUXEL_EPSILON of q3map2's point-in-solid test
constexpr float kDefaultSampleOffset = 1.0f;  // DEFAULT_LIGHTMAP_SAMPLE_OFFSET

// q3map2 MapSingleLuxel: a luxel in solid is moved by half a step along two in-plane vectors, in
// this order (never along the normal, so that a luxel under a detail brush lying on the surface
// stays in solid and is filled from its neighbours instead of being lit from the far side of it).
inline std::array<Vec3, 8> luxelNudges(Vec3 s, Vec3 t) {
    s *= 0.5f;
    t *= 0.5f;
    return {-s, s, t, -t, -s + t, s - t, s + t, -s - t};
}

// Unit vectors perpendicular to `normal`, built as q3map2's MakeNormalVectors does (curved
// lightmaps have no luxel steps, so their nudges are half a unit along these).
inline std::array<Vec3, 2> normalVectors(Vec3 normal) {
    Vec3 right{normal.z, -normal.x, normal.y};
    right = normalize(right - normal * dot(right, normal));
    return {right, cross(right, normal)};
}

// Luxels grouped in square tiles of the super-sampled lightmap: a light whose envelope misses a
// tile's bounds skips its luxels (large surfaces meet many lights that reach only a corner).
struct LuxelTiles {
    std::vector<Bounds> bounds;
    std::vector<std::vector<uint32_t>> luxels;  // indices of the luxels with a sample point
    std::vector<std::optional<Vec3>> normals;   // the one normal of every sample of the tile, if any
    std::vector<LuxelRect> rects;               // the smallest rectangle holding the tile's luxels

    LuxelTiles(const std::vector<std::optional<SamplePoint>>& points, int w, int h, int edge) {
        for (int ty = 0; ty < h; ty += edge)
            for (int tx = 0; tx < w; tx += edge) {
                Bounds b;
                LuxelRect rect;
                std::vector<uint32_t> members;
                members.reserve(size_t(edge) * size_t(edge));
                for (int y = ty; y < std::min(h, ty + edge); ++y)
                    for (int x = tx; x < std::min(w, tx + edge); ++x) {
                        const size_t i = static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x);
                        if (!points[i]) continue;
                        b.add(points[i]->origin);
                        rect.add(x, y);
                        members.push_back(static_cast<uint32_t>(i));
                    }
                if (members.empty()) continue;
                std::optional<Vec3> normal = points[members[0]]->normal;
                for (uint32_t i : members)
                    if (!(points[i]->normal == *normal)) {
                        normal.reset();
                        break;
                    }
                bounds.push_back(b);
                rects.push_back(rect);
                luxels.push_back(std::move(members));
                normals.push_back(normal);
            }
    }

    // The tiles the light's envelope reaches (and for area lights, whose form factor bound allows
    // more than the -fast tolerance).
    void reachedBy(const Light& light, float envelope, const ContributionSettings& settings,
                   std::vector<uint32_t>& out) const {
        out.clear();
        for (size_t t = 0; t < bounds.size(); ++t)
            if (lightReachesBounds(light, bounds[t], envelope) &&
                !areaLightSurelyDarkIn(light, bounds[t], settings, normals[t] ? &*normals[t] : nullptr))
                out.push_back(static_cast<uint32_t>(t));
    }
    template <typename Visit>
    void forEachLuxel(std::span<const uint32_t> tiles, Visit&& visit) const {
        for (uint32_t t : tiles)
            for (uint32_t i : luxels[t]) visit(i);
    }
    // Whether `test` holds for some luxel of `tiles`; stops at the first.
    template <typename Test>
    bool anyLuxel(std::span<const uint32_t> tiles, Test&& test) const {
        for (uint32_t t : tiles)
            for (uint32_t i : luxels[t])
                if (test(i)) return true;
        return false;
    }
    // The smallest rectangle holding the luxels of `tiles` (empty: x1 < x0).
    LuxelRect rectOf(std::span<const uint32_t> tiles) const {
        LuxelRect r;
        for (uint32_t t : tiles) {
            r.add(rects[t].x0, rects[t].y0);
            r.add(rects[t].x1, rects[t].y1);
        }
        return r;
    }
};

constexpr int kTileEdge = 8;  // super luxels per tile edge

struct LuxelSampler {
    const LightContext& ctx;
    const LightingEnv& env;
    const RawLightmap& raw;
    Vec3 offset;
    bool twoSided;
    std::span<const int> clusters;  // the surface's clusters: a sample point must see one of them
    // Planar lightmaps: the in-plane nudges of every luxel, half a super luxel step.
    std::array<Vec3, 8> planarNudges =
        luxelNudges(raw.vecs[0] / float(std::max(1, raw.superSample)), raw.vecs[1] / float(std::max(1, raw.superSample)));

    // q3map2 ClusterForPointExtFilter: the cluster of a point out of solid that is one of the
    // surface's clusters or sees one of them; -1 otherwise.
    int freeCluster(Vec3 point, float epsilon = kLuxelEpsilon) const {
        return clusterSeenBySurface(*ctx.tree, ctx.tree->clusterForPointExt(point, epsilon, leafHint), clusters);
    }
    // The leaf of the last point asked (a sampler serves one lightmap on one thread; its points
    // lie close together). Only a shortcut: the answers do not depend on it.
    mutable BspTree::LeafHint leafHint{};

    // The luxel's sample point; in solid, the nudges in q3map2's order, then the surface point under
    // the luxel pushed off along its normal; nullopt when all of them are in solid.
    std::optional<SamplePoint> samplePoint(const Luxel& lx) const {
        SamplePoint p{lx.origin + offset, lx.normal, -1, twoSided};
        if (!ctx.tree || ctx.bsp.nodes.empty()) return p;
        int cluster = freeCluster(p.origin);
        if (cluster < 0) {
            std::array<Vec3, 2> curved{};
            if (!raw.planar) curved = normalVectors(lx.faceNormal);
            const std::array<Vec3, 8> nudges = raw.planar ? planarNudges : luxelNudges(curved[0], curved[1]);
            for (size_t k = 0; k < nudges.size() && cluster < 0; ++k) {
                cluster = freeCluster(p.origin + nudges[k]);
                if (cluster >= 0) p.origin += nudges[k];
            }
        }
        if (cluster < 0) {
            const Vec3 lastResort = lx.surfacePoint + offset + lx.surfaceNormal * raw.sampleOffset;
            cluster = freeCluster(lastResort);
            if (cluster >= 0) p.origin = lastResort;
        }
        if (cluster < 0) return std::nullopt;
        p.cluster = cluster;
        return p;
    }

    // q3map2 maps the unmapped luxels next to mapped ones of a planar lightmap as well: at their
    // grid point pushed off by the default sample offset, with the mean normal of those neighbours,
    // nudged like any luxel but with neither the cluster filter nor the last resort.
    std::optional<SamplePoint> ringPoint(int x, int y, Vec3 normal) const {
        const float S = float(std::max(1, raw.superSample));
        const float s = (float(x) + 0.5f) / S - 0.5f, t = (float(y) + 0.5f) / S - 0.5f;
        SamplePoint p{raw.origin + raw.vecs[0] * s + raw.vecs[1] * t + offset, normal, -1, twoSided};
        p.origin[raw.axisNum] += raw.planeNormal[raw.axisNum] < 0.0f ? -kDefaultSampleOffset : kDefaultSampleOffset;
        if (!ctx.tree || ctx.bsp.nodes.empty()) return p;
        int cluster = ctx.tree->clusterForPointExt(p.origin, kLuxelEpsilon, leafHint);
        for (size_t k = 0; k < planarNudges.size() && cluster < 0; ++k) {
            cluster = ctx.tree->clusterForPointExt(p.origin + planarNudges[k], kLuxelEpsilon, leafHint);
            if (cluster >= 0) p.origin += planarNudges[k];
        }
        if (cluster < 0) return std::nullopt;
        p.cluster = cluster;
        return p;
    }

    // Reused between lights so that lighting a surface allocates once, not once per light.
    struct Scratch {
        std::vector<ShadowRay> rays;
        std::vector<size_t> rayLuxel;  // luxel of each ray
        std::vector<Vec3> transmission;
        std::vector<uint32_t> luxels;  // the luxels a batched light is asked about
    };

    // lightAt for the sample points of the tiles `active` (`skip`, when given: skip[i] = leave
    // dark), written to out[i] (and the direction towards the light to dirs[i] when `dirs` is set);
    // the shadow rays of the light are traced together as one batch. `out` must be zero on the
    // tiles' luxels (the caller clears what each light wrote before the next); only lit luxels are
    // written, and entries outside those tiles are not touched.
    void lightAll(const Light& light, float envelope, const std::vector<std::optional<SamplePoint>>& points,
                  const LuxelTiles& tiles, std::span<const uint32_t> active, const std::vector<uint8_t>* skip,
                  std::vector<Vec3>& out, std::vector<Vec3>* dirs, Scratch& scratch) const {
        std::vector<ShadowRay>& rays = scratch.rays;
        std::vector<size_t>& rayLuxel = scratch.rayLuxel;
        rays.clear();
        rayLuxel.clear();
        LightingEnv deferred = env;
        deferred.deferredRays = env.scene ? &rays : nullptr;
        if (samplesBatchable(light, deferred)) {
            std::vector<uint32_t>& lit = scratch.luxels;
            lit.clear();
            for (const uint32_t t : active) {
                const std::vector<uint32_t>& members = tiles.luxels[t];  // the luxels with a sample point
                if (!skip) {
                    lit.insert(lit.end(), members.begin(), members.end());
                    continue;
                }
                for (const uint32_t i : members)
                    if (!(*skip)[i]) lit.push_back(i);
            }
            lightToSamples(light, deferred, envelope, points, lit, out, dirs ? dirs->data() : nullptr, rayLuxel);
        } else {
            tiles.forEachLuxel(active, [&](uint32_t i) {
                if (!points[i] || (skip && (*skip)[i])) return;
                bool traced = false;
                std::optional<LightContribution> c = deferredLight(light, *points[i], deferred, envelope, traced);
                if (!c) return;
                out[i] = c->color;
                if (dirs) (*dirs)[i] = c->direction;
                if (traced) rayLuxel.push_back(i);
            });
        }
        if (rays.empty()) return;
        scratch.transmission.resize(rays.size());
        env.scene->traceBatch(rays, scratch.transmission);
        for (size_t k = 0; k < rays.size(); ++k) out[rayLuxel[k]] *= scratch.transmission[k];
    }

    // lightToSample with its shadow ray appended to deferred.deferredRays (when it has one: then
    // `traced`): the contribution before occlusion, or nullopt, and no ray kept, when there is none.
    static std::optional<LightContribution> deferredLight(const Light& light, const SamplePoint& p,
                                                          const LightingEnv& deferred, float envelope, bool& traced) {
        std::vector<ShadowRay>* rays = deferred.deferredRays;
        const size_t before = rays ? rays->size() : 0;
        std::optional<LightContribution> c = lightToSample(light, p, deferred, envelope);
        traced = rays && rays->size() > before;
        if (!c && traced) {
            rays->resize(before);
            traced = false;
        }
        return c;
    }

    Vec3 lightAt(const Light& light, const SamplePoint& p) const {
        std::optional<LightContribution> c = lightToSample(light, p, env);
        return c ? c->color : Vec3{};
    }

    // q3map2 SubmapRawLuxel: the step from luxel (x, y) to its neighbour along one axis, towards
    // the next luxel (`forward`) or the previous one, taken the other way at the lightmap's edges
    // (the luxel itself stands in for a neighbour without a sample point).
    static Vec3 luxelStep(const std::vector<std::optional<SamplePoint>>& points, int w, int h, int x, int y, bool alongX,
                          bool forward) {
        const int pos = alongX ? x : y, size = alongX ? w : h;
        auto at = [&](int k) -> Vec3 {
            const std::optional<SamplePoint>& p =
                points[size_t(alongX ? y : k) * size_t(w) + size_t(alongX ? k : x)];
            return p ? p->origin : points[size_t(y) * size_t(w) + size_t(x)]->origin;
        };
        if ((pos < size - 1 && forward) || pos == 0) return pos < size - 1 ? at(pos + 1) - at(pos) : Vec3{};
        return at(pos) - at(pos - 1);
    }

    // q3map2 SubsampleRawLuxel_r's four sub-samples at +-bias of a luxel step around `origin`
    // (first the luxel's own sample point): where they lie, which are kept (out of solid near the
    // surface), the point each kept one is lit at (none: kept but dark) and, once lit, their values.
    struct SubsampleQuad {
        std::array<Vec3, 4> origins{}, values{};
        std::array<bool, 4> mapped{};
        std::array<std::optional<SamplePoint>, 4> litAt{};
    };
    SubsampleQuad subsampleQuad(const Light& light, const std::vector<std::optional<SamplePoint>>& points, int w, int h,
                                int x, int y, Vec3 origin, float bias) const {
        // Sub-sample k sits at (-bias, -bias), (+, -), (-, +), (+, +) steps from `origin`.
        const Vec3 stepS[2] = {luxelStep(points, w, h, x, y, true, false), luxelStep(points, w, h, x, y, true, true)};
        const Vec3 stepT[2] = {luxelStep(points, w, h, x, y, false, false), luxelStep(points, w, h, x, y, false, true)};
        const SamplePoint& luxel = *points[size_t(y) * size_t(w) + size_t(x)];
        SubsampleQuad q;
        // q3map2 tests the PVS of every sub-sample with the first one's cluster (its trace takes the
        // first element of the cluster array): when the first lies in solid, the others it keeps
        // see no light but the sun's, and darken the luxel's mean.
        int firstCluster = -1;
        for (int k = 0; k < 4; ++k) {
            const bool plusS = k & 1, plusT = k & 2;
            q.origins[k] = origin + stepS[plusS] * (plusS ? bias : -bias) + stepT[plusT] * (plusT ? bias : -bias);
            const int cluster = ctx.tree && !ctx.bsp.nodes.empty() ? freeCluster(q.origins[k], 2 * kLuxelEpsilon) : 0;
            if (k == 0) firstCluster = cluster;
            if (cluster < 0) continue;
            q.mapped[k] = true;
            if (firstCluster >= 0 || light.type == LightType::Sun)
                q.litAt[k] = SamplePoint{q.origins[k], luxel.normal, ctx.tree ? firstCluster : -1, twoSided};
        }
        return q;
    }

    // The rest of SubsampleRawLuxel_r once a quad's values are known: the luxel having taken
    // `samples` of at most `maxSamples`, where they disagree (some lit, some not, and more than 4
    // in some channel) each recurses around itself at half the bias. The result is the mean of
    // `centre` and the kept sub-samples.
    Vec3 finishSubsample(const Light& light, const std::vector<std::optional<SamplePoint>>& points, int w, int h, int x,
                         int y, SubsampleQuad& q, float bias, int samples, int maxSamples, Vec3 centre) const {
        int numMapped = 0, lighted = 0;
        Vec3 total;
        for (int k = 0; k < 4; ++k) {
            if (!q.mapped[k]) continue;
            ++numMapped;
            total += q.values[k];
            lighted += q.values[k].x + q.values[k].y + q.values[k].z > 0;
        }
        if (samples + 1 < maxSamples && maxComponent(total) > 4 && lighted != 0 && lighted != numMapped)
            for (int k = 0; k < 4; ++k)
                if (q.mapped[k])
                    q.values[k] = subsample(light, points, w, h, x, y, q.origins[k], bias * 0.5f, samples + 1, maxSamples,
                                            q.values[k]);
        Vec3 sum = centre;
        for (int k = 0; k < 4; ++k)
            if (q.mapped[k]) sum += q.values[k];
        return sum / float(1 + numMapped);
    }

    Vec3 subsample(const Light& light, const std::vector<std::optional<SamplePoint>>& points, int w, int h, int x, int y,
                   Vec3 origin, float bias, int samples, int maxSamples, Vec3 centre) const {
        if (samples >= maxSamples) return centre;
        SubsampleQuad q = subsampleQuad(light, points, w, h, x, y, origin, bias);
        for (int k = 0; k < 4; ++k)
            if (q.litAt[k]) q.values[k] = lightAt(light, *q.litAt[k]);
        return finishSubsample(light, points, w, h, x, y, q, bias, samples, maxSamples, centre);
    }

    // The first quads (bias 0.25 around the sample point) of the luxels `which`, lit by `light`
    // with their shadow rays traced as one batch: each is what subsample would find, but the rays
    // share the batch's hull walks and Embree's coherent streams.
    void firstQuads(const Light& light, const std::vector<std::optional<SamplePoint>>& points, int w, int h,
                    std::span<const uint32_t> which, std::vector<SubsampleQuad>& quads, Scratch& scratch) const {
        std::vector<ShadowRay>& rays = scratch.rays;
        std::vector<size_t>& rayValue = scratch.rayLuxel;  // quad * 4 + sub-sample of each ray
        rays.clear();
        rayValue.clear();
        LightingEnv deferred = env;
        deferred.deferredRays = env.scene ? &rays : nullptr;
        const float envelope = lightEnvelope(light, env.settings.forceFast);
        quads.resize(which.size());
        for (size_t j = 0; j < which.size(); ++j) {
            const int x = int(which[j] % uint32_t(w)), y = int(which[j] / uint32_t(w));
            SubsampleQuad& q = quads[j] = subsampleQuad(light, points, w, h, x, y, points[which[j]]->origin, 0.25f);
            for (size_t k = 0; k < 4; ++k) {
                if (!q.litAt[k]) continue;
                bool traced = false;
                std::optional<LightContribution> c = deferredLight(light, *q.litAt[k], deferred, envelope, traced);
                if (!c) continue;
                q.values[k] = c->color;
                if (traced) rayValue.push_back(j * 4 + k);
            }
        }
        if (rays.empty()) return;
        scratch.transmission.resize(rays.size());
        // Rays along an axial plane alone: there Embree's packets may answer otherwise than the
        // single rays that subsample traces.
        env.scene->traceBatch(rays, scratch.transmission, true, true);
        for (size_t r = 0; r < rays.size(); ++r) quads[rayValue[r] / 4].values[rayValue[r] % 4] *= scratch.transmission[r];
    }
};

}  // namespace q3::light
