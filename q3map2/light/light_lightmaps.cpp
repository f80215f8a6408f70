// The lightmap phase: lay out every lightmapped surface, light its luxels (per light: sample,
// adaptive sub-samples at light/shadow edges, per-light box filter), fill and average them, convert
// to bytes and pack the pages into the BSP. Raw lightmaps are lit in parallel into their own slots.
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "light_context.h"
#include "light_text.h"
#include "lightmap_export.h"
#include "lightmap_filter.h"
#include "lightmap_layout.h"
#include "lightmap_pack.h"
#include "luxel_passes.h"
#include "patch.h"
#include "progress.h"

namespace q3::light {
namespace {

constexpr float kLuxelEpsilon = 0.125f;  // LUXEL_EPSILON of q3map2's point-in-solid test

struct RawResult {
    bool ok = false;
    LightmapBlock block;
    RawLightmap layout;
    BspLuxels luxels;
    uint64_t luxelCount = 0;
    uint64_t droppedStyled = 0;
};

// Patch mesh for the layout, with each point's position in control-point index space carried
// through the tessellation in the texture-coordinate channel (Bezier blending of evenly spaced
// indices is linear, so the result is the exact control-space coordinate).
CurvedMesh curvedMesh(const bsp::Bsp& bsp, const bsp::Surface& s) {
    patch::ControlGrid grid;
    grid.width = s.patchWidth;
    grid.height = s.patchHeight;
    for (int v = 0; v < s.numVerts; ++v) {
        const bsp::DrawVert& dv = bsp.drawVerts[static_cast<size_t>(s.firstVert + v)];
        patch::PatchVertex pv;
        pv.xyz = Vec3::fromArray(dv.xyz);
        pv.normal = Vec3::fromArray(dv.normal);
        pv.st[0] = static_cast<float>(v % std::max(1, s.patchWidth));
        pv.st[1] = static_cast<float>(v / std::max(1, s.patchWidth));
        grid.points.push_back(pv);
    }
    CurvedMesh mesh;
    if (!patch::isValidGrid(grid)) return mesh;
    patch::PatchMesh tess = patch::tessellateForLighting(grid);
    mesh.width = tess.width;
    mesh.height = tess.height;
    for (const patch::PatchVertex& v : tess.verts) {
        mesh.positions.push_back(v.xyz);
        mesh.normals.push_back(v.normal);
        mesh.controlU.push_back(v.st[0]);
        mesh.controlV.push_back(v.st[1]);
    }
    return mesh;
}

// q3map2 MapSingleLuxel: a luxel in solid is moved by half a luxel along the lightmap's s and t
// steps (never along the normal, so that a luxel under a detail brush lying on the surface stays
// in solid and is filled from its neighbours instead of being lit from the far side of that brush).
std::vector<Vec3> luxelNudges(Vec3 sStep, Vec3 tStep, int superSample) {
    const Vec3 s = sStep * (0.5f / static_cast<float>(std::max(1, superSample)));
    const Vec3 t = tStep * (0.5f / static_cast<float>(std::max(1, superSample)));
    return {s, -s, t, -t, s + t, s - t, -s + t, -s - t};
}
std::vector<Vec3> luxelNudges(const std::array<Vec3, 2>& tangents, int superSample) {
    return luxelNudges(tangents[0], tangents[1], superSample);
}

// Curved surfaces have no lightmap steps: q3map2 uses unit vectors perpendicular to the normal.
std::array<Vec3, 2> curvedTangents(Vec3 normal) {
    const Vec3 helper = std::fabs(normal.x) < 0.9f ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
    const Vec3 s = normalize(cross(normal, helper));
    return {s, cross(normal, s)};
}

// Luxels grouped in square tiles of the super-sampled lightmap: a light whose envelope misses a
// tile's bounds skips its luxels (large surfaces meet many lights that reach only a corner).
struct LuxelTiles {
    std::vector<Bounds> bounds;
    std::vector<std::vector<uint32_t>> luxels;  // indices of the luxels with a sample point

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
                bounds.push_back(b);
                luxels.push_back(std::move(members));
            }
    }

    // The tiles the light's envelope reaches.
    void reachedBy(const Light& light, bool forceFast, std::vector<uint32_t>& out) const {
        out.clear();
        for (size_t t = 0; t < bounds.size(); ++t)
            if (lightReachesBounds(light, bounds[t], forceFast)) out.push_back(static_cast<uint32_t>(t));
    }
    template <typename Visit>
    void forEachLuxel(std::span<const uint32_t> tiles, Visit&& visit) const {
        for (uint32_t t : tiles)
            for (uint32_t i : luxels[t]) visit(i);
    }
};

constexpr int kTileEdge = 8;  // super luxels per tile edge

struct LuxelSampler {
    const LightContext& ctx;
    const LightingEnv& env;
    const RawLightmap& raw;
    Vec3 offset;
    bool twoSided;
    // Planar lightmaps: the in-plane nudges of every luxel (see luxelNudges).
    std::vector<Vec3> planarNudges = raw.planar ? luxelNudges(raw.vecs[0], raw.vecs[1], raw.superSample)
                                                : std::vector<Vec3>{};

    std::optional<SamplePoint> samplePoint(Vec3 origin, Vec3 normal) const {
        SamplePoint p{origin + offset, normal, -1, twoSided};
        if (ctx.tree && !ctx.bsp.nodes.empty()) {
            int cluster = ctx.tree->clusterForPointExt(p.origin, kLuxelEpsilon);
            if (cluster < 0) {
                const std::vector<Vec3> nudges =
                    raw.planar ? std::vector<Vec3>{} : luxelNudges(curvedTangents(normal), raw.superSample);
                std::optional<Vec3> free =
                    ctx.tree->nudgeOutOfSolid(p.origin, raw.planar ? planarNudges : nudges, kLuxelEpsilon);
                if (!free) return std::nullopt;
                p.origin = *free;
                cluster = ctx.tree->clusterForPoint(p.origin);
            }
            p.cluster = cluster;
        }
        return p;
    }

    // Reused between lights so that lighting a surface allocates once, not once per light.
    struct Scratch {
        std::vector<ShadowRay> rays;
        std::vector<size_t> rayLuxel;  // luxel of each ray; kStyledFlag marks a dropped styled light
        std::vector<Vec3> transmission;
    };
    static constexpr size_t kStyledFlag = size_t{1} << (sizeof(size_t) * 8 - 1);

    // lightAt for the sample points of the tiles `active` (nullopt = no light; `skip[i]` = leave
    // dark), written to out[i]; the shadow rays of the light are traced together as one batch.
    // Entries of `out` outside those tiles are not touched.
    void lightAll(const Light& light, const std::vector<std::optional<SamplePoint>>& points, const LuxelTiles& tiles,
                  std::span<const uint32_t> active, const std::vector<uint8_t>& skip, std::vector<Vec3>& out,
                  Scratch& scratch, uint64_t& dropped) const {
        std::vector<ShadowRay>& rays = scratch.rays;
        std::vector<size_t>& rayLuxel = scratch.rayLuxel;
        rays.clear();
        rayLuxel.clear();
        LightingEnv deferred = env;
        deferred.deferredRays = env.scene ? &rays : nullptr;
        tiles.forEachLuxel(active, [&](uint32_t i) {
            out[i] = Vec3{};
            if (!points[i] || skip[i]) return;
            const size_t before = rays.size();
            std::optional<LightContribution> c = lightToSample(light, *points[i], deferred);
            const bool traced = rays.size() > before;
            if (!c) {
                rays.resize(before);
                return;
            }
            if (c->style != 0) {
                if (traced)
                    rayLuxel.push_back(i | kStyledFlag);
                else
                    ++dropped;
                return;
            }
            out[i] = c->color;
            if (traced) rayLuxel.push_back(i);
        });
        if (rays.empty()) return;
        scratch.transmission.resize(rays.size());
        env.scene->traceBatch(rays, scratch.transmission);
        for (size_t k = 0; k < rays.size(); ++k) {
            const size_t i = rayLuxel[k] & ~kStyledFlag;
            if (rayLuxel[k] & kStyledFlag) {
                if (!(scratch.transmission[k] == Vec3{})) ++dropped;
                continue;
            }
            out[i] *= scratch.transmission[k];
        }
    }

    Vec3 lightAt(const Light& light, const SamplePoint& p, uint64_t& dropped) const {
        std::optional<LightContribution> c = lightToSample(light, p, env);
        if (!c) return {};
        if (c->style != 0) {
            ++dropped;
            return {};
        }
        return c->color;
    }

    // Mean of four sub-samples around (fx, fy), recursing where they disagree.
    Vec3 subsample(const Light& light, float fx, float fy, int level, int maxLevel, Vec3 centre,
                   uint64_t& dropped) const {
        const auto offsets = subsampleOffsets(level);
        Vec3 values[4];
        bool lit[4];
        for (int k = 0; k < 4; ++k) {
            const float sx = fx + offsets[static_cast<size_t>(k)][0];
            const float sy = fy + offsets[static_cast<size_t>(k)][1];
            values[k] = centre;
            if (std::optional<Luxel> lx = sampleRawLightmap(raw, sx, sy))
                if (std::optional<SamplePoint> p = samplePoint(lx->origin, lx->normal))
                    values[k] = lightAt(light, *p, dropped);
            lit[k] = maxComponent(values[k]) > 0;
        }
        const bool mixed = !(lit[0] == lit[1] && lit[1] == lit[2] && lit[2] == lit[3]);
        Vec3 sum;
        for (int k = 0; k < 4; ++k) {
            if (mixed && level + 1 < maxLevel)
                values[k] = subsample(light, fx + offsets[static_cast<size_t>(k)][0],
                                      fy + offsets[static_cast<size_t>(k)][1], level + 1, maxLevel, values[k], dropped);
            sum += values[k];
        }
        return sum * 0.25f;
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

bool visibleFromLightmap(const Light& light, const LightmapReach& r, const BspTree* tree) {
    if (!tree || light.type == LightType::Sun || light.cluster < 0 || r.clusters.empty()) return true;
    for (int c : r.clusters)
        if (c < 0 || tree->clusterVisible(c, light.cluster)) return true;
    return false;
}


RawResult lightOneSurface(const LightContext& ctx, const LightingEnv& sharedEnv, int surfaceNum,
                          const LayoutOptions& layoutOptions, const LuxelPasses* passes) {
    RawResult result;
    // The receive shadow group picks the casters (group 0: lit without occlusion).
    const LightingEnv env = receiverLightingEnv(ctx, sharedEnv, surfaceNum);
    const bsp::Surface& surface = ctx.bsp.surfaces[static_cast<size_t>(surfaceNum)];
    const LightingShader& shader = ctx.shaders.shaders[static_cast<size_t>(surface.shaderNum)];
    const SurfaceExtra& extra = ctx.extras.forSurface(surfaceNum);
    const LightOptions& o = ctx.options;

    SurfaceGeometry geometry = surfaceGeometry(ctx.bsp, surfaceNum);
    if (surface.surfaceType == bsp::MST_PATCH) geometry.mesh = curvedMesh(ctx.bsp, surface);
    SurfaceLightmapParams params;
    params.sampleSize =
        resolveSampleSize(ctx.extras.loaded, extra.sampleSize, shader.lightmapSampleSize, o.sampleSize, o.sampleScale);
    params.axis = extra.lightmapAxis;
    if (shader.lightmapAxis >= 0 && shader.lightmapAxis < 3) {
        params.axis = Vec3{};
        params.axis[shader.lightmapAxis] = 1;
    }
    params.sampleOffset = shader.lightmapSampleOffset;
    Log quiet(false);
    std::optional<RawLightmap> layout = layoutSurfaceLightmap(geometry, params, layoutOptions, &quiet);
    if (!layout) return result;
    RawLightmap& raw = *layout;

    const int w = raw.superWidth(), h = raw.superHeight();
    const Vec3 offset = ctx.surfaceOffsets[static_cast<size_t>(surfaceNum)];
    LuxelSampler sampler{ctx, env, raw, offset, shader.twoSided};

    // Sample points of every super luxel.
    LuxelImage total(w, h);
    std::vector<std::optional<SamplePoint>> points(static_cast<size_t>(w) * static_cast<size_t>(h));
    Bounds bounds;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const Luxel& lx = raw.luxel(x, y);
            const size_t i = total.index(x, y);
            if (!lx.mapped) continue;
            points[i] = sampler.samplePoint(lx.origin, lx.normal);
            if (points[i]) {
                total.state[i] = LuxelState::Mapped;
                total.color[i] = ctx.world.ambient;
                bounds.add(points[i]->origin);
                ++result.luxelCount;
            } else {
                total.state[i] = LuxelState::Occluded;
            }
        }

    LightmapReach reach;
    reach.bounds = bounds;
    reach.twoSided = shader.twoSided;
    reach.planar = raw.planar && surface.surfaceType == bsp::MST_PLANAR;
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

    const int maxLevel = std::max(0, o.lightSamples - 1);
    LuxelImage single(w, h);
    single.state = total.state;
    std::vector<uint8_t> skip(points.size(), 0);  // -cheap: luxels already saturated
    const LuxelTiles tiles(points, w, h, kTileEdge);
    std::vector<uint32_t> active;  // tiles the light reaches
    LuxelSampler::Scratch scratch;
    for (const Light& light : ctx.lights) {
        if (bounds.empty() || !lightReachesBounds(light, bounds, env.settings.forceFast)) continue;
        if (!inFrontOfPlane(light, reach) || !visibleFromLightmap(light, reach, env.tree)) continue;
        tiles.reachedBy(light, env.settings.forceFast, active);
        if (active.empty()) continue;
        if (o.cheap)
            for (size_t i = 0; i < points.size(); ++i)
                skip[i] = total.color[i].x >= 255 && total.color[i].y >= 255 && total.color[i].z >= 255;
        sampler.lightAll(light, points, tiles, active, skip, single.color, scratch, result.droppedStyled);
        const int radius = luxelFilterRadius(std::max(shader.lightmapFilterRadius, light.filterRadius), raw.sampleSize,
                                             raw.superSample, o.filter);
        if (maxLevel == 0 && radius == 0) {
            // Plain sampling: only the active luxels changed.
            tiles.forEachLuxel(active, [&](uint32_t i) {
                total.color[i] += single.color[i];
                single.color[i] = Vec3{};
            });
            continue;
        }
        bool any = false;
        tiles.forEachLuxel(active, [&](uint32_t i) { any = any || !(single.color[i] == Vec3{}); });
        if (!any && maxLevel == 0) continue;
        if (maxLevel > 0) {
            // Adaptive sub-sampling where this light's lit/unlit state changes between neighbours.
            std::vector<Vec3> refined = single.color;
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x) {
                    const size_t i = total.index(x, y);
                    if (!points[i]) continue;
                    const bool lit = maxComponent(single.color[i]) > 0;
                    bool edge = false;
                    for (auto [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
                        const int nx = x + dx, ny = y + dy;
                        if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
                        const size_t j = total.index(nx, ny);
                        if (points[j] && (maxComponent(single.color[j]) > 0) != lit) edge = true;
                    }
                    if (edge)
                        refined[i] = sampler.subsample(light, x + 0.5f, y + 0.5f, 0, maxLevel, single.color[i],
                                                       result.droppedStyled);
                }
            single.color = std::move(refined);
        }
        const LuxelImage& add = radius > 0 ? boxFilterLuxels(single, radius) : single;
        for (size_t i = 0; i < points.size(); ++i)
            if (points[i]) total.color[i] += add.color[i];
        std::fill(single.color.begin(), single.color.end(), Vec3{});
    }

    if (passes) applyLuxelPasses(*passes, surface.shaderNum, total, points);  // floodlight, then dirt
    fillFromNeighbours(total, ctx.world.ambient, false, false);
    BspLuxels luxels = downsampleSuperLuxels(total, raw.superSample);

    LightmapBlock block;
    block.width = luxels.width;
    block.height = luxels.height;
    block.texels.resize(luxels.color.size());
    for (size_t i = 0; i < luxels.color.size(); ++i) {
        const Vec3 c = vmax(luxels.color[i], ctx.world.minLight);
        block.texels[i] = colorToBytes(c, shader.lightmapBrightness, ctx.color);
    }
    block.used = luxels.used;
    block.sortKey = shader.name;
    block.surfaces = {surfaceNum};
    block.vertexCoords = {raw.vertexCoords};

    result.ok = true;
    result.block = std::move(block);
    result.luxels = std::move(luxels);
    result.layout = std::move(raw);
    return result;
}

}  // namespace

void lightLightmaps(LightContext& ctx, Log& log) {
    const LightOptions& o = ctx.options;
    std::vector<int> surfaces;
    for (size_t i = 0; i < ctx.bsp.surfaces.size(); ++i) {
        const bsp::Surface& s = ctx.bsp.surfaces[i];
        if (s.shaderNum < 0 || static_cast<size_t>(s.shaderNum) >= ctx.shaders.shaders.size()) continue;
        if (isLightmappedSurface(s, ctx.shaders.shaders[static_cast<size_t>(s.shaderNum)].vertexLit))
            surfaces.push_back(static_cast<int>(i));
    }
    LayoutOptions layoutOptions;
    layoutOptions.superSample = std::clamp(o.superSample, 1, kMaxSuperSample);
    if (layoutOptions.superSample != o.superSample)
        log.warning(strCat("-super ", o.superSample, " clamped to ", layoutOptions.superSample));
    layoutOptions.sampleScale = o.sampleScale;
    layoutOptions.pageSize = o.lightmapWidth;
    layoutOptions.rawSizeLimit = o.rawLightmapSizeLimit;

    const LightingEnv env = surfaceLightingEnv(ctx);
    const std::unique_ptr<LuxelPasses> passes = prepareLuxelPasses(ctx, log);
    std::vector<RawResult> results(surfaces.size());
    Progress progress = Progress::forConsole(log, surfaces.size());
    auto body = [&](const tbb::blocked_range<size_t>& range) {
        for (size_t k = range.begin(); k != range.end(); ++k) {
            results[k] = lightOneSurface(ctx, env, surfaces[k], layoutOptions, passes.get());
            progress.advance();
        }
    };
    tbb::task_arena arena(ctx.threads > 0 ? ctx.threads : tbb::task_arena::automatic);
    arena.execute([&] { tbb::parallel_for(tbb::blocked_range<size_t>(0, surfaces.size(), 1), body); });
    progress.finish();

    // Blocks in surface order; vertex light of lightmapped surfaces from their own luxels.
    std::vector<LightmapBlock> blocks;
    ctx.vertexLight.assign(ctx.bsp.drawVerts.size(), Vec3{});
    ctx.vertexFromLightmap.assign(ctx.bsp.drawVerts.size(), 0);
    if (o.shGather) ctx.bakedLight.assign(ctx.bsp.surfaces.size(), BakedSurfaceLight{});
    for (size_t k = 0; k < results.size(); ++k) {
        RawResult& r = results[k];
        if (!r.ok) continue;
        if (o.shGather)  // kept for the SH gather, which reads the light of the surfaces its rays hit
            ctx.bakedLight[size_t(surfaces[k])] = {r.luxels.width, r.luxels.height, r.luxels.color, r.layout.vertexCoords};
        ctx.stats.luxels += r.luxelCount;
        ctx.stats.droppedStyledLight += r.droppedStyled;
        ++ctx.stats.lightmaps;
        const bsp::Surface& s = ctx.bsp.surfaces[static_cast<size_t>(surfaces[k])];
        for (int v = 0; v < s.numVerts && static_cast<size_t>(v) < r.layout.vertexCoords.size(); ++v) {
            const auto& st = r.layout.vertexCoords[static_cast<size_t>(v)];
            const int x = std::clamp(static_cast<int>(st[0]), 0, r.luxels.width - 1);
            const int y = std::clamp(static_cast<int>(st[1]), 0, r.luxels.height - 1);
            const size_t vi = static_cast<size_t>(s.firstVert + v);
            ctx.vertexLight[vi] = r.luxels.color[static_cast<size_t>(y) * static_cast<size_t>(r.luxels.width) +
                                                 static_cast<size_t>(x)];
            ctx.vertexFromLightmap[vi] = 1;
        }
        applyLightmapOrigin(ctx.bsp.surfaces[static_cast<size_t>(surfaces[k])], r.layout);
        blocks.push_back(std::move(r.block));
    }

    PackOptions pack;
    pack.pageSize = o.lightmapWidth;
    pack.gamePageSize = 128;
    pack.external = o.externalLightmaps;
    pack.collapse = !o.noCollapse;
    PackedLightmaps packed = packLightmaps(blocks, pack);
    applyPackedLightmaps(ctx.bsp, blocks, packed);
    exportPackedLightmaps(ctx, packed, log);
    if (packed.external) {
        std::filesystem::path dir = o.lightmapDir.empty()
                                        ? ctx.bspPath.parent_path() / ctx.bspPath.stem()
                                        : std::filesystem::path(o.lightmapDir);
        auto written = writeExternalLightmaps(packed, dir);
        log.info(strCat(written.size(), " external lightmaps written to ", dir.string()));
    }
    log.info(strCat(blocks.size(), " lightmaps on ", packed.pages.size(), " pages, ", ctx.stats.luxels, " luxels"));
    if (ctx.stats.droppedStyledLight > 0)
        log.warning(strCat("light styles other than 0 are not stored in lightmaps; ", ctx.stats.droppedStyledLight,
                           " styled luxel contributions dropped"));
}

}  // namespace q3::light
