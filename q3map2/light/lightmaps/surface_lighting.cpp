// One lighting pass over one raw lightmap (surface_lighting.h).
#include <algorithm>
#include <cmath>
#include <limits>

#include "surface_lighting.h"

#include "light_context.h"
#include "light_text.h"
#include "lightmap_filter.h"
#include "lightmap_layout.h"
#include "luxel_passes.h"
#include "patch.h"

namespace q3::light {
namespace {

constexpr float kLuxelEpsilon = 0.125f;  // LUXEL_EPSILON of q3map2's point-in-solid test
constexpr float kDefaultSampleOffset = 1.0f;  // DEFAULT_LIGHTMAP_SAMPLE_OFFSET


// q3map2 MapSingleLuxel: a luxel in solid is moved by half a step along two in-plane vectors, in
// this order (never along the normal, so that a luxel under a detail brush lying on the surface
// stays in solid and is filled from its neighbours instead of being lit from the far side of it).
std::array<Vec3, 8> luxelNudges(Vec3 s, Vec3 t) {
    s *= 0.5f;
    t *= 0.5f;
    return {-s, s, t, -t, -s + t, s - t, s + t, -s - t};
}

// Unit vectors perpendicular to `normal`, built as q3map2's MakeNormalVectors does (curved
// lightmaps have no luxel steps, so their nudges are half a unit along these).
std::array<Vec3, 2> normalVectors(Vec3 normal) {
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

    LuxelTiles(const std::vector<std::optional<SamplePoint>>& points, int w, int h, int edge) {
        for (int ty = 0; ty < h; ty += edge)
            for (int tx = 0; tx < w; tx += edge) {
                Bounds b;
                std::vector<uint32_t> members;
                for (int y = ty; y < std::min(h, ty + edge); ++y)
                    for (int x = tx; x < std::min(w, tx + edge); ++x) {
                        const size_t i = static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x);
                        if (!points[i]) continue;
                        b.add(points[i]->origin);
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
    // The smallest rectangle holding the luxels of `tiles` (empty: x1 < x0) in a lightmap `width` wide.
    LuxelRect rectOf(std::span<const uint32_t> tiles, int width) const {
        LuxelRect r;
        forEachLuxel(tiles, [&](uint32_t i) { r.add(int(i % uint32_t(width)), int(i / uint32_t(width))); });
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
    // the shadow rays of the light are traced together as one batch. Entries outside those tiles
    // are not touched.
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
                for (const uint32_t i : members) out[i] = Vec3{};
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
                out[i] = Vec3{};
                if (!points[i] || (skip && (*skip)[i])) return;
                const size_t before = rays.size();
                std::optional<LightContribution> c = lightToSample(light, *points[i], deferred, envelope);
                const bool traced = rays.size() > before;
                if (!c) {
                    rays.resize(before);
                    return;
                }
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

    // q3map2 SubsampleRawLuxel_r: four sub-samples at +-bias of a luxel step around `origin` (first
    // the luxel's own sample point), each kept only out of solid near the surface; the luxel having
    // taken `samples` of at most `maxSamples`, where they disagree (some lit, some not, and more than
    // 4 in some channel) each recurses around itself at half the bias. The result is the mean of
    // `centre` and the kept sub-samples.
    Vec3 subsample(const Light& light, const std::vector<std::optional<SamplePoint>>& points, int w, int h, int x, int y,
                   Vec3 origin, float bias, int samples, int maxSamples, Vec3 centre) const {
        if (samples >= maxSamples) return centre;
        // Sub-sample k sits at (-bias, -bias), (+, -), (-, +), (+, +) steps from `origin`.
        const Vec3 stepS[2] = {luxelStep(points, w, h, x, y, true, false), luxelStep(points, w, h, x, y, true, true)};
        const Vec3 stepT[2] = {luxelStep(points, w, h, x, y, false, false), luxelStep(points, w, h, x, y, false, true)};
        const SamplePoint& luxel = *points[size_t(y) * size_t(w) + size_t(x)];
        Vec3 values[4], origins[4];
        bool mapped[4] = {false, false, false, false};
        int numMapped = 0, lighted = 0;
        Vec3 total;
        // q3map2 tests the PVS of every sub-sample with the first one's cluster (its trace takes the
        // first element of the cluster array): when the first lies in solid, the others it keeps
        // see no light but the sun's, and darken the luxel's mean.
        int firstCluster = -1;
        for (int k = 0; k < 4; ++k) {
            const bool plusS = k & 1, plusT = k & 2;
            origins[k] = origin + stepS[plusS] * (plusS ? bias : -bias) + stepT[plusT] * (plusT ? bias : -bias);
            const int cluster = ctx.tree && !ctx.bsp.nodes.empty() ? freeCluster(origins[k], 2 * kLuxelEpsilon) : 0;
            if (k == 0) firstCluster = cluster;
            if (cluster < 0) continue;
            if (firstCluster < 0 && light.type != LightType::Sun)
                values[k] = Vec3{};
            else
                values[k] = lightAt(light, SamplePoint{origins[k], luxel.normal, ctx.tree ? firstCluster : -1, twoSided});
            mapped[k] = true;
            ++numMapped;
            total += values[k];
            lighted += values[k].x + values[k].y + values[k].z > 0;
        }
        if (samples + 1 < maxSamples && maxComponent(total) > 4 && lighted != 0 && lighted != numMapped)
            for (int k = 0; k < 4; ++k)
                if (mapped[k])
                    values[k] = subsample(light, points, w, h, x, y, origins[k], bias * 0.5f, samples + 1, maxSamples,
                                          values[k]);
        Vec3 sum = centre;
        for (int k = 0; k < 4; ++k)
            if (mapped[k]) sum += values[k];
        return sum / float(1 + numMapped);
    }
};

// Whether a light can reach any luxel of a raw lightmap: inside its envelope, in front of a planar
// one-sided surface, and in the PVS of at least one luxel's cluster.
struct LightmapReach {
    Bounds bounds;
    std::vector<int> clusters;  // sorted, unique; empty = unknown
    bool planar = false;
    bool twoSided = false;
    bool flatNormals = false;  // every luxel normal is exactly the plane normal (no phong shading)
    Vec3 planeNormal;
    float planeDist = 0;
};

bool inFrontOfPlane(const Light& light, const LightmapReach& r) {
    if (!r.planar || r.twoSided) return true;
    if (light.type == LightType::Sun) {
        // A sun below the plane lights no luxel whose normal is the plane's (Lambert term <= 0).
        const bool lambert = light.angleAttenuation || light.controlled;
        return !(r.flatNormals && lambert && dot(r.planeNormal, light.normal) <= 0);
    }
    if (light.type == LightType::Area) {
        for (const Vec3& p : light.winding)
            if (dot(p, r.planeNormal) - r.planeDist > -1.0f) return true;
        return dot(light.origin, r.planeNormal) - r.planeDist > -1.0f;
    }
    return dot(light.origin, r.planeNormal) - r.planeDist >= -1.0f;
}

// q3map2 CreateTraceLightsForBounds: a light no cluster of the raw lightmap's surfaces sees is
// dropped for all its luxels (an empty list keeps every light).
bool seenFromGroup(const Light& light, std::span<const int> clusters, const BspTree* tree) {
    if (!tree || light.type == LightType::Sun || light.cluster < 0 || clusters.empty()) return true;
    for (int c : clusters)
        if (tree->clusterVisible(light.cluster, c)) return true;
    return false;
}

bool visibleFromLightmap(const Light& light, const LightmapReach& r, const BspTree* tree) {
    if (!tree || light.type == LightType::Sun || light.cluster < 0 || r.clusters.empty()) return true;
    for (int c : r.clusters)
        if (c < 0 || tree->clusterVisible(c, light.cluster)) return true;
    return false;
}


// The light of one lighting pass on the super luxels of a raw lightmap, by style.
struct StyledSuperLight {
    std::vector<int> styles;          // styles[k] is the style of images[k]; [0] is style 0
    std::vector<LuxelImage> images;
    std::vector<Vec3> directions;     // -deluxe, style 0 only

    // Index of the image of `style`, creating it while there is room; -1 when four styles are in use.
    int slotFor(int style, const LuxelImage& like) {
        for (size_t k = 0; k < styles.size(); ++k)
            if (styles[k] == style) return int(k);
        if (int(styles.size()) >= kMaxLightmapStyles) return -1;
        styles.push_back(style);
        LuxelImage image(like.width, like.height);
        image.state = like.state;
        images.push_back(std::move(image));
        return int(styles.size()) - 1;
    }
};

// Luminance weights of a contribution's direction (only the ratios between lights matter).
float brightness(Vec3 c) { return 0.299f * c.x + 0.587f * c.y + 0.114f * c.z; }

LightmapReach lightmapReach(const std::vector<std::optional<SamplePoint>>& points, const Bounds& bounds,
                            const RawLightmap& raw, bool planarSurface, bool twoSided, Vec3 offset) {
    LightmapReach reach;
    reach.bounds = bounds;
    reach.twoSided = twoSided;
    reach.planar = raw.planar && planarSurface;
    if (reach.planar) {
        reach.flatNormals = true;
        for (size_t i = 0; i < points.size(); ++i)
            if (points[i] && !(points[i]->normal == raw.planeNormal)) reach.flatNormals = false;
        reach.planeNormal = raw.planeNormal;
        reach.planeDist = raw.planeDist + dot(offset, raw.planeNormal);
    }
    for (const auto& p : points)
        if (p) reach.clusters.push_back(p->cluster);
    std::sort(reach.clusters.begin(), reach.clusters.end());
    reach.clusters.erase(std::unique(reach.clusters.begin(), reach.clusters.end()), reach.clusters.end());
    return reach;
}

// Mean of the super-sample block of every BSP luxel (no state rules: directions and normals).
std::vector<Vec3> downsampleMean(const std::vector<Vec3>& super, int superWidth, int superSample, int width,
                                 int height) {
    std::vector<Vec3> out(size_t(width) * size_t(height));
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            Vec3 sum;
            for (int sy = 0; sy < superSample; ++sy)
                for (int sx = 0; sx < superSample; ++sx)
                    sum += super[size_t(y * superSample + sy) * size_t(superWidth) + size_t(x * superSample + sx)];
            out[size_t(y) * size_t(width) + size_t(x)] = sum;
        }
    return out;
}

// q3map2's adaptive sub-sampling (-samples N): a walk over every 2x2 stamp of the light's luxels,
// in rows; a stamp with lit and unlit luxels and more than 4 in some channel sub-samples each of its
// luxels that may still take a sample, in place, so later stamps see the refined values.
// `lit` holds every luxel of `color` that is not zero, and grows with the refined ones: a stamp
// outside it is all zeros when its turn comes, so the walk visits only the stamps that meet it
// (a light usually reaches a corner of a large lightmap, and this runs once a light). `samples`
// (all 1, as left by the previous call) counts each luxel's samples.
void refineEdges(const LuxelSampler& sampler, const Light& light, const std::vector<std::optional<SamplePoint>>& points,
                 int w, int h, int maxSamples, std::vector<Vec3>& color, std::vector<int>& samples, LuxelRect& lit) {
    if (lit.empty()) return;
    // Each luxel as 0 (no sample point), 1 (dark) or 2 (lit): a window is refined only when it has
    // both a dark and a lit luxel, which four bytes tell. A row's states are made when the windows
    // first reach it and follow the luxels the windows refine.
    auto luxelState = [&](size_t i) -> uint8_t {
        if (!points[i]) return 0;
        return color[i].x + color[i].y + color[i].z > 0 ? 2 : 1;
    };
    std::vector<uint8_t> state(points.size());
    int madeRows = std::max(0, lit.y0 - 1);  // the rows from the first window's up to this one have states
    for (int y = std::max(0, lit.y0 - 1); y + 1 < h && y <= lit.y1; ++y) {
        for (; madeRows <= y + 1; ++madeRows)
            for (int x = 0; x < w; ++x) {
                const size_t i = size_t(madeRows) * size_t(w) + size_t(x);
                state[i] = luxelState(i);
            }
        for (int x = std::max(0, lit.x0 - 1); x + 1 < w && x <= lit.x1; ++x) {
            const uint8_t* top = &state[size_t(y) * size_t(w) + size_t(x)];
            const uint8_t* bottom = top + w;
            if ((((1u << top[0]) | (1u << top[1]) | (1u << bottom[0]) | (1u << bottom[1])) & 6u) != 6u)
                continue;  // no dark luxel or no lit one
            const int sx[4] = {x, x + 1, x, x + 1}, sy[4] = {y, y, y + 1, y + 1};
            Vec3 total;
            for (int t = 0; t < 4; ++t) {
                const size_t i = size_t(sy[t]) * size_t(w) + size_t(sx[t]);
                if (points[i]) total += color[i];
            }
            if (maxComponent(total) <= 4) continue;
            for (int t = 0; t < 4; ++t) {
                const size_t i = size_t(sy[t]) * size_t(w) + size_t(sx[t]);
                if (!points[i] || samples[i] >= maxSamples) continue;
                color[i] = sampler.subsample(light, points, w, h, sx[t], sy[t], points[i]->origin, 0.25f, samples[i],
                                             maxSamples, color[i]);
                state[i] = luxelState(i);
                ++samples[i];
                lit.add(sx[t], sy[t]);
            }
        }
    }
    for (int y = lit.y0; y <= lit.y1; ++y)
        std::fill_n(samples.begin() + ptrdiff_t(y) * w + lit.x0, lit.x1 - lit.x0 + 1, 1);
}

// The rings of unmapped luxels around the mapped ones (LuxelSampler::ringPoint), grown
// max(1, superSample / 2) times; each ring sees only the luxels placed before it.
void mapLuxelRings(const LuxelSampler& sampler, const RawLightmap& raw, LuxelSamples& samples) {
    std::vector<std::optional<SamplePoint>>& points = samples.points;
    std::vector<Vec3>& normals = samples.normals;
    const int w = raw.superWidth(), h = raw.superHeight();
    const int rings = std::max(1, raw.superSample / 2);
    std::vector<uint8_t> placed(points.size(), 0);
    for (size_t i = 0; i < points.size(); ++i) placed[i] = raw.luxels[i].mapped;
    for (int ring = 0; ring < rings; ++ring) {
        const std::vector<uint8_t> before = placed;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const size_t i = size_t(y) * size_t(w) + size_t(x);
                if (before[i]) continue;
                Vec3 normal;
                bool any = false;
                for (int sy = std::max(0, y - 1); sy <= std::min(h - 1, y + 1); ++sy)
                    for (int sx = std::max(0, x - 1); sx <= std::min(w - 1, x + 1); ++sx) {
                        const size_t j = size_t(sy) * size_t(w) + size_t(sx);
                        if (j == i || !before[j] || !points[j]) continue;
                        normal += normals[j];
                        any = true;
                    }
                if (!any || dot(normal, normal) == 0.0f) continue;
                normal = normalize(normal);
                placed[i] = 1;
                normals[i] = normal;
                points[i] = sampler.ringPoint(x, y, normal);
                samples.states[i] = points[i] ? LuxelState::Mapped : LuxelState::Occluded;
            }
    }
}

// Where the super luxels of `raw` are sampled: each mapped one at its sample point (nullopt in
// solid), then the rings around a planar lightmap.
LuxelSamples placeSamples(const LuxelSampler& sampler, const RawLightmap& raw) {
    const int w = raw.superWidth(), h = raw.superHeight();
    const size_t count = static_cast<size_t>(w) * static_cast<size_t>(h);
    LuxelSamples samples{std::vector<std::optional<SamplePoint>>(count), std::vector<Vec3>(count),
                         std::vector<LuxelState>(count, LuxelState::Unmapped)};
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const Luxel& lx = raw.luxel(x, y);
            const size_t i = static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x);
            if (!lx.mapped) continue;
            samples.normals[i] = lx.normal;
            samples.points[i] = sampler.samplePoint(lx);
            samples.states[i] = samples.points[i] ? LuxelState::Mapped : LuxelState::Occluded;
        }
    if (raw.planar && raw.axisNum >= 0) mapLuxelRings(sampler, raw, samples);
    return samples;
}

}  // namespace

std::vector<std::vector<int>> surfaceClusterLists(const bsp::Bsp& bsp, std::span<const Vec3> offsets) {
    // World-space bounds of every surface, as q3map2 tests them against the leafs' bounds.
    std::vector<Bounds> bounds(bsp.surfaces.size());
    for (size_t i = 0; i < bsp.surfaces.size(); ++i) {
        const bsp::Surface& s = bsp.surfaces[i];
        const Vec3 offset = i < offsets.size() ? offsets[i] : Vec3{};
        for (int v = 0; v < s.numVerts; ++v) {
            const size_t k = size_t(s.firstVert) + size_t(v);
            if (k < bsp.drawVerts.size()) bounds[i].add(Vec3::fromArray(bsp.drawVerts[k].xyz) + offset);
        }
    }
    std::vector<std::vector<int>> out(bsp.surfaces.size());
    for (const bsp::Leaf& leaf : bsp.leafs)
        for (int k = 0; k < leaf.numLeafSurfaces; ++k) {
            const size_t i = size_t(leaf.firstLeafSurface) + size_t(k);
            if (i >= bsp.leafSurfaces.size()) continue;
            const int32_t surface = bsp.leafSurfaces[i];
            if (surface < 0 || size_t(surface) >= out.size()) continue;
            // q3map2 skips a listing leaf whose stored (integer) bounds miss the surface's bounds,
            // so a face half a unit outside its leaf's rounded box brings no cluster.
            const Bounds& b = bounds[size_t(surface)];
            bool touches = true;
            for (int a = 0; a < 3; ++a)
                if (float(leaf.mins[a]) > b.maxs[a] || float(leaf.maxs[a]) < b.mins[a]) touches = false;
            if (touches) out[size_t(surface)].push_back(leaf.cluster);
        }
    for (std::vector<int>& clusters : out) {
        std::sort(clusters.begin(), clusters.end());
        clusters.erase(std::unique(clusters.begin(), clusters.end()), clusters.end());
    }
    return out;
}

int clusterSeenBySurface(const BspTree& tree, int cluster, std::span<const int> clusters) {
    if (cluster < 0 || clusters.empty()) return cluster;
    for (int c : clusters)
        if (c == cluster || tree.clusterVisible(cluster, c)) return cluster;
    return -1;
}

const LightmapLayer* SurfaceLight::layer(int style) const {
    for (const LightmapLayer& l : layers)
        if (l.style == style) return &l;
    return nullptr;
}

LightmapLayer& SurfaceLight::layerFor(int style) {
    for (LightmapLayer& l : layers)
        if (l.style == style) return l;
    layers.push_back({style, std::vector<Vec3>(size_t(width) * size_t(height))});
    return layers.back();
}

LayoutOptions layoutOptionsFor(const LightContext& ctx, Log& log) {
    const LightOptions& o = ctx.options;
    LayoutOptions layoutOptions;
    layoutOptions.superSample = std::clamp(o.superSample, 1, kMaxSuperSample);
    if (layoutOptions.superSample != o.superSample)
        log.warning(strCat("-super ", o.superSample, " clamped to ", layoutOptions.superSample));
    layoutOptions.sampleScale = o.sampleScale;
    layoutOptions.pageSize = o.lightmapWidth;
    layoutOptions.rawSizeLimit = o.rawLightmapSizeLimit;
    return layoutOptions;
}

SurfaceLight lightSurface(const LightContext& ctx, const LightingEnv& sharedEnv, std::span<const int> surfaceNums,
                          const LayoutOptions& layoutOptions, const LuxelPasses* passes, const SurfacePass& pass,
                          const SurfaceLight* previous) {
    SurfaceLight result;
    if (surfaceNums.empty()) return result;
    // The first surface speaks for the group: its members share model, shader, entity, shadow
    // group, sample size and projection (lightmap_layout_merge.h).
    const int surfaceNum = surfaceNums[0];
    result.surfaceNum = surfaceNum;
    // The receive shadow group picks the casters (group 0: lit without occlusion).
    const LightingEnv env = receiverLightingEnv(ctx, sharedEnv, surfaceNum);
    const bsp::Surface& surface = ctx.bsp.surfaces[static_cast<size_t>(surfaceNum)];
    const LightingShader& shader = ctx.shaders.shaders[static_cast<size_t>(surface.shaderNum)];
    const SurfaceExtra& extra = ctx.extras.forSurface(surfaceNum);
    const LightOptions& o = ctx.options;

    const bool reuse = previous && previous->ok && previous->samples;
    std::optional<RawLightmap> layout;
    if (reuse) {
        layout = previous->layout;
    } else {
        std::vector<SurfaceGeometry> geometries;
        for (int member : surfaceNums) {
            SurfaceGeometry& geometry = geometries.emplace_back(surfaceGeometry(ctx.bsp, member, ctx.shadedNormals));
            const bsp::Surface& memberSurface = ctx.bsp.surfaces[size_t(member)];
            if (memberSurface.surfaceType == bsp::MST_PATCH)
                geometry.mesh = curvedMesh(ctx.bsp, memberSurface, ctx.shadedNormals,
                                           ctx.extras.loaded ? ctx.extras.forSurface(member).longestCurve : 0.0f);
        }
        SurfaceLightmapParams params;
        params.sampleSize = resolveSampleSize(ctx.extras.loaded, extra.sampleSize, shader.lightmapSampleSize,
                                              o.sampleSize, o.sampleScale);
        params.axis = extra.lightmapAxis;
        if (shader.lightmapAxis >= 0 && shader.lightmapAxis < 3) {
            params.axis = Vec3{};
            params.axis[shader.lightmapAxis] = 1;
        }
        params.sampleOffset = shader.lightmapSampleOffset;
        Log quiet(false);
        layout = layoutSurfaceGroup(geometries, params, layoutOptions, &quiet);
    }
    if (!layout) return result;
    RawLightmap& raw = *layout;

    const int w = raw.superWidth(), h = raw.superHeight();
    const Vec3 offset = ctx.surfaceOffsets[static_cast<size_t>(surfaceNum)];
    // Luxels filter their clusters by those of every surface of the lightmap (q3map2's lightClusters).
    const std::vector<int>& lightmapClusters =
        surfaceNums.size() > 1 && size_t(surfaceNum) < ctx.lightmapGroupClusters.size()
            ? ctx.lightmapGroupClusters[size_t(surfaceNum)]
            : ctx.surfaceClusters[size_t(surfaceNum)];
    LuxelSampler sampler{ctx, env, raw, offset, shader.twoSided, lightmapClusters};

    // Sample points of every super luxel (an earlier pass's, when given): each lit one starts at
    // the ambient light.
    const Vec3 ambient = pass.direct ? surfaceAmbient(ctx, surfaceNum) : Vec3{};
    const std::shared_ptr<const LuxelSamples> samples =
        reuse ? previous->samples : std::make_shared<const LuxelSamples>(placeSamples(sampler, raw));
    const std::vector<std::optional<SamplePoint>>& points = samples->points;
    const std::vector<Vec3>& superNormals = samples->normals;
    LuxelImage total(w, h);
    total.state = samples->states;
    Bounds bounds;
    for (size_t i = 0; i < points.size(); ++i)
        if (points[i]) {
            total.color[i] = ambient;
            bounds.add(points[i]->origin);
            ++result.luxelCount;
        }
    if (pass.keepSamples) result.samples = samples;

    const std::span<const int> groupClusters =
        size_t(surfaceNum) < ctx.lightmapGroupClusters.size()
            ? std::span<const int>(ctx.lightmapGroupClusters[size_t(surfaceNum)])
            : std::span<const int>();
    const LightmapReach reach =
        lightmapReach(points, bounds, raw, surface.surfaceType == bsp::MST_PLANAR, shader.twoSided, offset);
    StyledSuperLight light{{0}, {std::move(total)}, {}};
    if (pass.deluxe) light.directions.assign(points.size(), Vec3{});
    const int maxLevel = std::max(0, o.lightSamples - 1);
    LuxelImage single(w, h);
    single.state = light.images[0].state;
    std::vector<Vec3> singleDirs(pass.deluxe ? points.size() : 0);
    std::vector<uint8_t> skip(points.size(), 0);  // -cheap: luxels already saturated
    std::vector<int> subsamples(maxLevel > 0 ? points.size() : 0, 1);  // refineEdges' sample counts
    std::vector<Vec3> filtered;  // a filtered light (boxFilterLuxelsWithin)
    const LuxelTiles tiles(points, w, h, kTileEdge);
    std::vector<uint32_t> active;  // tiles the light reaches
    LuxelSampler::Scratch scratch;
    std::vector<uint32_t> candidates;  // the lights whose envelope reaches the sample points, in order
    if (!bounds.empty()) {
        if (pass.reach) {
            pass.reach->reaching(bounds, candidates);
        } else {
            for (size_t i = 0; i < pass.lights.size(); ++i) {
                const float envelope =
                    i < pass.envelopes.size() ? pass.envelopes[i] : lightEnvelope(pass.lights[i], env.settings.forceFast);
                if (lightReachesBounds(pass.lights[i], bounds, envelope)) candidates.push_back(uint32_t(i));
            }
        }
    }
    for (const uint32_t lightIndex : candidates) {
        const Light& lt = pass.lights[lightIndex];
        const float envelope = lightIndex < pass.envelopes.size() ? pass.envelopes[lightIndex]
                                                                  : lightEnvelope(lt, env.settings.forceFast);
        if (!inFrontOfPlane(lt, reach) || !visibleFromLightmap(lt, reach, env.tree)) continue;
        if (!seenFromGroup(lt, groupClusters, env.tree)) continue;
        tiles.reachedBy(lt, envelope, env.settings, active);
        if (active.empty()) continue;
        const int slot = light.slotFor(lt.style, light.images[0]);
        if (slot < 0) {
            ++result.styleLimitHits;
            continue;
        }
        LuxelImage& target = light.images[size_t(slot)];
        if (o.cheap)
            for (size_t i = 0; i < points.size(); ++i)
                skip[i] = target.color[i].x >= 255 && target.color[i].y >= 255 && target.color[i].z >= 255;
        const bool withDirs = pass.deluxe && slot == 0;
        sampler.lightAll(lt, envelope, points, tiles, active, o.cheap ? &skip : nullptr, single.color,
                         withDirs ? &singleDirs : nullptr, scratch);
        const int radius = luxelFilterRadius(std::max(shader.lightmapFilterRadius, lt.filterRadius), raw.sampleSize,
                                             raw.superSample, o.filter);
        if (maxLevel == 0 && radius == 0) {
            // Plain sampling: only the active luxels changed.
            tiles.forEachLuxel(active, [&](uint32_t i) {
                target.color[i] += single.color[i];
                if (withDirs) light.directions[i] += singleDirs[i] * brightness(single.color[i]);
                single.color[i] = Vec3{};
            });
            continue;
        }
        bool any = false;
        tiles.forEachLuxel(active, [&](uint32_t i) { any = any || !(single.color[i] == Vec3{}); });
        if (!any) continue;  // sub-sampling and filtering keep an all-dark light dark
        // The light is zero outside `lit` (and, once added, outside `changed`), which leaves the
        // sums as they are there.
        LuxelRect lit = tiles.rectOf(active, w);
        LuxelRect changed;
        const std::vector<Vec3>* add = &single.color;
        if (radius == 0) {
            // Sub-sampling (q3map2 skips it where the light is filtered: it would be smoothed away).
            refineEdges(sampler, lt, points, w, h, o.lightSamples, single.color, subsamples, lit);
            changed = lit;
        } else {
            changed = boxFilterLuxelsWithin(single, radius, lit, filtered);
            add = &filtered;
        }
        for (int y = changed.y0; y <= changed.y1; ++y)
            for (int x = changed.x0; x <= changed.x1; ++x) {
                const size_t i = size_t(y) * size_t(w) + size_t(x);
                if (!points[i]) continue;
                target.color[i] += (*add)[i];
                if (withDirs) light.directions[i] += singleDirs[i] * brightness((*add)[i]);
            }
        for (int y = lit.y0; y <= lit.y1; ++y)
            std::fill_n(single.color.begin() + ptrdiff_t(y) * w + lit.x0, lit.x1 - lit.x0 + 1, Vec3{});
    }

    for (size_t k = 0; k < light.images.size(); ++k) {
        LuxelImage& image = light.images[k];
        if (passes && pass.direct && k == 0)
            applyLuxelPasses(*passes, surface.shaderNum, image, points);  // floodlight, then dirt
        fillFromNeighbours(image, k == 0 ? ambient : Vec3{}, false, false);
        BspLuxels luxels = downsampleSuperLuxels(image, raw.superSample);
        if (k == 0) {
            result.width = luxels.width;
            result.height = luxels.height;
            result.used = std::move(luxels.used);
        }
        result.layers.push_back({light.styles[k], std::move(luxels.color)});
    }
    if (pass.deluxe) {
        result.directions = downsampleMean(light.directions, w, raw.superSample, result.width, result.height);
        result.normals = downsampleMean(superNormals, w, raw.superSample, result.width, result.height);
    }
    result.ok = true;
    // The luxels and triangles serve only this pass, unless a later one reuses the layout with the
    // sample points: freed here, their memory lights the next lightmap instead of fresh pages.
    if (!pass.keepSamples) {
        std::vector<Luxel>().swap(raw.luxels);
        std::vector<LightmapTriangle>().swap(raw.triangles);
    }
    result.layout = std::move(raw);
    return result;
}

}  // namespace q3::light
