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
#include "luxel_sampler.h"
#include "luxel_subsampling.h"
#include "patch.h"

namespace q3::light {
namespace {

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
    const std::vector<uint8_t> darkFlags = maxLevel > 0 ? darkFlagsOf(points) : std::vector<uint8_t>{};
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
        // Sub-sampling and filtering keep an all-dark light dark.
        if (!tiles.anyLuxel(active, [&](uint32_t i) { return !(single.color[i] == Vec3{}); })) continue;
        // The light is zero outside `lit` (and, once added, outside `changed`), which leaves the
        // sums as they are there.
        LuxelRect lit = tiles.rectOf(active);
        LuxelRect changed;
        const std::vector<Vec3>* add = &single.color;
        if (radius == 0) {
            // Sub-sampling (q3map2 skips it where the light is filtered: it would be smoothed away).
            refineEdges(sampler, lt, points, w, h, o.lightSamples, single.color, subsamples, lit, darkFlags, scratch);
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
