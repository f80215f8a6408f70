// The lightmap phase: a direct pass over every lightmapped surface (surface_lighting.h), then
// -bounce radiosity passes lit by the emitters the previous pass made, summed per style; then the
// store: bytes, deluxe pages, packing into the BSP (or external pages), styled lightmaps, and the
// vertex light of lightmapped surfaces. Surfaces are lit in parallel into their own slots.
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <future>

#include "bounce_passes.h"
#include "deluxe.h"
#include "light_context.h"
#include "light_styles.h"
#include "light_text.h"
#include "lightmap_export.h"
#include "lightmap_layout_merge.h"
#include "lightmap_pack.h"
#include "luxel_passes.h"
#include "progress.h"
#include "surface_lighting.h"

namespace q3::light {
namespace {

std::vector<int> lightmappedSurfaces(const LightContext& ctx) {
    std::vector<int> surfaces;
    for (size_t i = 0; i < ctx.bsp.surfaces.size(); ++i) {
        const bsp::Surface& s = ctx.bsp.surfaces[i];
        if (s.shaderNum < 0 || static_cast<size_t>(s.shaderNum) >= ctx.shaders.shaders.size()) continue;
        if (isLightmappedSurface(s, ctx.shaders.shaders[static_cast<size_t>(s.shaderNum)].vertexLit))
            surfaces.push_back(static_cast<int>(i));
    }
    return surfaces;
}

// The raw lightmaps of q3map2's SetupSurfaceLightmaps: groups of surfaces (BSP surface numbers, in
// its order) that share one lightmap and are lit together, with the lights seen from a cluster of
// any of them (`clusters`: per surface, the union of the surfaceClusters of its group).
struct LightmapGroups {
    std::vector<std::vector<int>> groups;
    std::vector<std::vector<int>> clusters;
};

LightmapGroups lightmapGroups(const LightContext& ctx, std::span<const int> surfaces, const LayoutOptions& layoutOptions) {
    std::vector<int> modelOf(ctx.bsp.surfaces.size(), 0);
    for (size_t m = 0; m < ctx.bsp.models.size(); ++m) {
        const bsp::Model& model = ctx.bsp.models[m];
        for (int s = model.firstSurface; s < model.firstSurface + model.numSurfaces; ++s)
            if (s >= 0 && size_t(s) < modelOf.size()) modelOf[size_t(s)] = int(m);
    }
    const LightOptions& o = ctx.options;
    // Each surface's input (a patch's is its tessellated mesh) made in parallel, into its own slot.
    std::vector<SurfaceLightmapInput> inputs(surfaces.size());
    auto makeInput = [&](size_t k) {
        const int s = surfaces[k];
        const bsp::Surface& surface = ctx.bsp.surfaces[size_t(s)];
        const LightingShader& shader = ctx.shaders.shaders[size_t(surface.shaderNum)];
        const SurfaceExtra& extra = ctx.extras.forSurface(s);
        SurfaceLightmapInput in;
        in.geometry = surfaceGeometry(ctx.bsp, s, ctx.shadedNormals);
        if (surface.surfaceType == bsp::MST_PATCH)
            in.geometry.mesh = curvedMesh(ctx.bsp, surface, ctx.shadedNormals, ctx.extras.loaded ? extra.longestCurve : 0.0f);
        in.params.sampleSize = resolveSampleSize(ctx.extras.loaded, extra.sampleSize, shader.lightmapSampleSize,
                                                 o.sampleSize, layoutOptions.sampleScale);
        in.params.axis = extra.lightmapAxis;
        if (shader.lightmapAxis >= 0 && shader.lightmapAxis < 3) {
            in.params.axis = Vec3{};
            in.params.axis[shader.lightmapAxis] = 1;
        }
        in.params.sampleOffset = shader.lightmapSampleOffset;
        in.traits.model = modelOf[size_t(s)];
        in.traits.shader = extra.shader.empty() ? shader.name : extra.shader;
        in.traits.entity = extra.entity;
        in.traits.receiveShadows = extra.receiveShadows;
        in.traits.brightness = shader.lightmapBrightness;
        in.traits.filterRadius = shader.lightmapFilterRadius;
        inputs[k] = std::move(in);
    };
    tbb::task_arena(ctx.threads > 0 ? ctx.threads : tbb::task_arena::automatic).execute([&] {
        tbb::parallel_for(size_t(0), surfaces.size(), makeInput);
    });
    LightmapGroups out;
    out.clusters.resize(ctx.bsp.surfaces.size());
    for (const std::vector<size_t>& group : groupSurfacesForLightmaps(inputs)) {
        std::vector<int> clusters;
        std::vector<int>& members = out.groups.emplace_back();
        for (size_t k : group) {
            members.push_back(surfaces[k]);
            const std::vector<int>& own = ctx.surfaceClusters[size_t(surfaces[k])];
            clusters.insert(clusters.end(), own.begin(), own.end());
        }
        std::sort(clusters.begin(), clusters.end());
        clusters.erase(std::unique(clusters.begin(), clusters.end()), clusters.end());
        for (size_t k : group) out.clusters[size_t(surfaces[k])] = clusters;
    }
    return out;
}

// About how many luxels a group of surfaces takes: their area (a patch's control mesh stands in
// for its curve) over the square of their sample size. Only the order of the work follows it.
double estimatedLuxels(const LightContext& ctx, std::span<const int> group) {
    const bsp::Bsp& bsp = ctx.bsp;
    auto corner = [&](int64_t v) {
        return v >= 0 && size_t(v) < bsp.drawVerts.size() ? Vec3::fromArray(bsp.drawVerts[size_t(v)].xyz) : Vec3{};
    };
    auto area = [&](int64_t a, int64_t b, int64_t c) {
        return 0.5 * double(length(cross(corner(b) - corner(a), corner(c) - corner(a))));
    };
    double total = 0;
    for (const int surfaceNum : group) {
        const bsp::Surface& s = bsp.surfaces[size_t(surfaceNum)];
        double surfaceArea = 0;
        if (s.surfaceType == bsp::MST_PATCH) {
            for (int y = 0; y + 1 < s.patchHeight; ++y)
                for (int x = 0; x + 1 < s.patchWidth; ++x) {
                    const int64_t v = int64_t(s.firstVert) + int64_t(y) * s.patchWidth + x;
                    surfaceArea += area(v, v + 1, v + s.patchWidth) + area(v + 1, v + s.patchWidth + 1, v + s.patchWidth);
                }
        } else {
            for (int i = 0; i + 2 < s.numIndexes; i += 3) {
                const int64_t first = int64_t(s.firstIndex) + i;
                if (first < 0 || size_t(first) + 2 >= bsp.drawIndexes.size()) break;
                const int64_t base = s.firstVert;
                surfaceArea += area(base + bsp.drawIndexes[size_t(first)], base + bsp.drawIndexes[size_t(first) + 1],
                                    base + bsp.drawIndexes[size_t(first) + 2]);
            }
        }
        const double sampleSize = ctx.extras.loaded ? std::max(1, ctx.extras.forSurface(surfaceNum).sampleSize) : 16.0;
        total += surfaceArea / (sampleSize * sampleSize);
    }
    return total;
}

// Lights every raw lightmap (a group of surfaces) for one pass, in parallel, one slot each;
// `previous` (an earlier pass's results, slot for slot) lends them its sample points.
std::vector<SurfaceLight> lightPass(const LightContext& ctx, const std::vector<std::vector<int>>& surfaces,
                                    const LayoutOptions& layoutOptions, const LuxelPasses* passes,
                                    const SurfacePass& pass, Log& log,
                                    const std::vector<SurfaceLight>* previous = nullptr) {
    const LightingEnv env = surfaceLightingEnv(ctx);
    const std::vector<float> envelopes = lightEnvelopes(pass.lights, env.settings.forceFast);
    const LightReach reach(pass.lights, envelopes);
    SurfacePass withEnvelopes = pass;
    withEnvelopes.envelopes = envelopes;
    withEnvelopes.reach = &reach;
    std::vector<SurfaceLight> results(surfaces.size());
    Progress progress = Progress::forConsole(log, surfaces.size());
    // Largest first, each thread taking the next one as it finishes: a large lightmap taken last
    // would keep one core busy long after the others are done. Each result has its own slot, so
    // the order changes nothing but the time.
    std::vector<double> cost(surfaces.size());
    for (size_t k = 0; k < surfaces.size(); ++k) cost[k] = estimatedLuxels(ctx, surfaces[k]);
    std::vector<size_t> order(surfaces.size());
    for (size_t k = 0; k < order.size(); ++k) order[k] = k;
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return cost[a] > cost[b]; });
    std::atomic<size_t> next{0};
    auto worker = [&](int) {
        for (size_t k = next++; k < order.size(); k = next++) {
            const size_t slot = order[k];
            const SurfaceLight* earlier = previous && slot < previous->size() ? &(*previous)[slot] : nullptr;
            results[slot] = lightSurface(ctx, env, surfaces[slot], layoutOptions, passes, withEnvelopes, earlier);
            progress.advance();
        }
    };
    tbb::task_arena arena(ctx.threads > 0 ? ctx.threads : tbb::task_arena::automatic);
    arena.execute([&] { tbb::parallel_for(0, arena.max_concurrency(), worker); });
    progress.finish();
    return results;
}

// total += pass, style by style (a style the total lacks is added while there is room).
void addPass(std::vector<SurfaceLight>& total, const std::vector<SurfaceLight>& pass) {
    for (size_t k = 0; k < total.size(); ++k) {
        SurfaceLight& t = total[k];
        const SurfaceLight& p = pass[k];
        if (!t.ok || !p.ok || t.width != p.width || t.height != p.height) continue;
        for (const LightmapLayer& layer : p.layers) {
            const bool known = t.layer(layer.style) != nullptr;
            if (!known && int(t.layers.size()) >= kMaxLightmapStyles) {
                ++t.styleLimitHits;
                continue;
            }
            LightmapLayer& into = t.layerFor(layer.style);
            for (size_t i = 0; i < into.color.size(); ++i) into.color[i] += layer.color[i];
        }
        for (size_t i = 0; i < t.directions.size() && i < p.directions.size(); ++i) t.directions[i] += p.directions[i];
    }
}

// -bounceonly: the stored light starts from nothing (the direct light only feeds the first bounce).
std::vector<SurfaceLight> emptyLike(const std::vector<SurfaceLight>& pass) {
    std::vector<SurfaceLight> out = pass;
    for (SurfaceLight& s : out) {
        for (LightmapLayer& layer : s.layers) std::fill(layer.color.begin(), layer.color.end(), Vec3{});
        std::fill(s.directions.begin(), s.directions.end(), Vec3{});
    }
    return out;
}

LightmapBlock styleZeroBlock(const LightContext& ctx, const SurfaceLight& s, const DeluxeSettings* deluxe) {
    const bsp::Surface& surface = ctx.bsp.surfaces[size_t(s.surfaceNum)];
    const LightingShader& shader = ctx.shaders.shaders[size_t(surface.shaderNum)];
    LightmapBlock block;
    block.width = s.width;
    block.height = s.height;
    const LightmapLayer* zero = s.layer(0);
    block.texels.resize(size_t(s.width) * size_t(s.height));
    block.light = zero ? zero->color : std::vector<Vec3>(block.texels.size());
    block.brightness = shader.lightmapBrightness;
    for (size_t i = 0; i < block.texels.size(); ++i)
        block.texels[i] = colorToBytes(vmax(block.light[i], ctx.world.minLight), block.brightness, ctx.color);
    if (deluxe) {
        block.directionTexels = encodeDeluxels(ctx.bsp, s, *deluxe);
        if (ctx.options.debugDeluxe) block.texels = block.directionTexels;  // -debugdeluxe: look at them
    }
    block.used = s.used;
    block.sortKey = shader.name;
    block.surfaces = s.layout.surfaces;
    block.vertexCoords = s.layout.surfaceCoords;
    // q3map2 CompareRawLightmap compares the shader names of the surfaces, sorted by name.
    for (int member : s.layout.surfaces)
        block.shaderNames.push_back(ctx.shaders.shaders[size_t(ctx.bsp.surfaces[size_t(member)].shaderNum)].name);
    std::sort(block.shaderNames.begin(), block.shaderNames.end());
    block.styleSum = 0;  // q3map2's four style slots, 255 when empty
    for (size_t k = 0; k < size_t(kMaxLightmapStyles); ++k)
        block.styleSum += k < s.layers.size() ? s.layers[k].style : 255;
    return block;
}

// The vertex light of lightmapped surfaces, read from their own luxels (style 0).
void vertexLightFromLightmaps(LightContext& ctx, const std::vector<SurfaceLight>& lit) {
    ctx.vertexLight.assign(ctx.bsp.drawVerts.size(), Vec3{});
    ctx.vertexFromLightmap.assign(ctx.bsp.drawVerts.size(), 0);
    for (const SurfaceLight& s : lit) {
        if (!s.ok) continue;
        const LightmapLayer* zero = s.layer(0);
        for (size_t m = 0; m < s.layout.surfaces.size() && m < s.layout.surfaceCoords.size(); ++m) {
            const bsp::Surface& surface = ctx.bsp.surfaces[size_t(s.layout.surfaces[m])];
            const auto& coords = s.layout.surfaceCoords[m];
            for (int v = 0; v < surface.numVerts && size_t(v) < coords.size(); ++v) {
                const auto& st = coords[size_t(v)];
                const int x = std::clamp(int(st[0]), 0, s.width - 1);
                const int y = std::clamp(int(st[1]), 0, s.height - 1);
                const size_t vi = size_t(surface.firstVert + v);
                ctx.vertexLight[vi] = zero ? zero->color[size_t(y) * size_t(s.width) + size_t(x)] : Vec3{};
                ctx.vertexFromLightmap[vi] = 1;
            }
        }
    }
}

struct StoreResult {
    size_t blocks = 0;
    size_t pages = 0;
};

// Bytes, packing and (when `final`) the pictures, styled pages and what later phases read.
StoreResult storeLightmaps(LightContext& ctx, const std::vector<SurfaceLight>& lit, bool final, Log& log) {
    const LightOptions& o = ctx.options;
    const std::optional<DeluxeSettings> deluxe = deluxeSettings(ctx);
    // One block per lit raw lightmap, in their order; made in parallel (each its own slot and surfaces).
    std::vector<size_t> litIndex;
    for (size_t k = 0; k < lit.size(); ++k)
        if (lit[k].ok) litIndex.push_back(k);
    std::vector<LightmapBlock> blocks(litIndex.size());
    tbb::task_arena arena(ctx.threads > 0 ? ctx.threads : tbb::task_arena::automatic);
    arena.execute([&] {
        tbb::parallel_for(size_t(0), litIndex.size(), [&](size_t b) {
            const SurfaceLight& s = lit[litIndex[b]];
            blocks[b] = styleZeroBlock(ctx, s, deluxe ? &*deluxe : nullptr);
            for (int member : s.layout.surfaces) applyLightmapOrigin(ctx.bsp.surfaces[size_t(member)], s.layout);
        });
    });
    std::vector<StyledLightmap> styled;
    for (size_t b = 0; b < litIndex.size(); ++b) {
        const SurfaceLight& s = lit[litIndex[b]];
        for (const LightmapLayer& layer : s.layers)
            if (layer.style != 0) styled.push_back({int(b), layer.style, s.width, s.height, layer.color});
    }

    PackOptions pack;
    pack.pageSize = o.lightmapWidth;
    pack.gamePageSize = 128;
    pack.external = o.externalLightmaps;
    // Styled pages address the same texels as their style-0 block: every block keeps its own
    // full-size texels (a styled light sets q3map2's -nocollapse). Deluxe pages only forbid twins:
    // a solid lightmap's one texel takes the direction of its first texel, as in q3map2.
    pack.collapse = !o.noCollapse && styled.empty();
    pack.twins = !deluxe;
    pack.color = ctx.color;
    pack.minLight = ctx.world.minLight;
    PackedLightmaps packed;
    arena.execute([&] { packed = packLightmaps(blocks, pack); });
    if (deluxe) interleaveDirectionPages(packed, blocks);
    applyPackedLightmaps(ctx.bsp, blocks, packed);
    if (final) exportPackedLightmaps(ctx, packed, log);
    if (packed.external) {
        std::filesystem::path dir = o.lightmapDir.empty() ? ctx.bspPath.parent_path() / ctx.bspPath.stem()
                                                           : std::filesystem::path(o.lightmapDir);
        auto written = writeExternalLightmaps(packed, dir);
        log.info(strCat(written.size(), " external lightmaps written to ", dir.string()));
    }
    // Generated shaders are added once, by the final store.
    if (final) storeStyledLightmaps(ctx, blocks, packed, std::move(styled), log);  // also clears stale ones
    return {blocks.size(), packed.pages.size()};
}

}  // namespace

void lightLightmaps(LightContext& ctx, Log& log) {
    const LightOptions& o = ctx.options;
    const LayoutOptions layoutOptions = layoutOptionsFor(ctx, log);
    LightmapGroups grouped = lightmapGroups(ctx, lightmappedSurfaces(ctx), layoutOptions);
    ctx.lightmapGroupClusters = std::move(grouped.clusters);
    const std::vector<std::vector<int>>& surfaces = grouped.groups;
    const LuxelPasses* passes = ctx.luxelPasses.get();
    const bool deluxe = deluxeSettings(ctx).has_value();

    // The bounces reflect off the textures: on more than one thread those are read while the direct
    // pass lights (the reading leaves a core idle, the pass none), and their messages given after
    // it, where a read that follows the pass gives them.
    Log albedoLog;
    albedoLog.setVerbose(log.verbose());
    albedoLog.holdMessages();
    std::future<void> albedoRead;
    if (o.bounce > 0 && ctx.threads != 1)
        albedoRead = std::async(std::launch::async, [&ctx, &albedoLog] { shaderAlbedo(ctx, albedoLog); });
    // With bounces, the direct pass keeps its sample points for them: they light the same luxels.
    SurfacePass direct{ctx.lights, true, deluxe};
    direct.keepSamples = o.bounce > 0;
    std::vector<SurfaceLight> pass = lightPass(ctx, surfaces, layoutOptions, passes, direct, log);
    // The direct pass starts the total; it stays the first bounce's source through `total` (a copy
    // of every luxel would only cost time), but for -bounceonly, whose total starts dark.
    std::vector<SurfaceLight> total = o.bounce > 0 && o.bounceOnly ? emptyLike(pass) : std::move(pass);
    if (o.bounce > 0) {
        if (albedoRead.valid()) {
            albedoRead.get();
            albedoLog.replayInto(log);
        }
        BouncePasses bounce(ctx, shaderAlbedo(ctx, log), log);
        for (int b = 1; b <= o.bounce; ++b) {
            if (!o.noBounceStore) {
                // q3map2 stores the BSP between bounces, so that a long radiosity run can be looked at
                // (and survives being stopped) with the bounces done so far.
                storeLightmaps(ctx, total, false, log);
                writeLitBsp(ctx, log);
            }
            const std::vector<SurfaceLight>& source = b == 1 && !o.bounceOnly ? total : pass;
            std::vector<Light> emitters = bounce.emitters(source, b, b == 1 ? ctx.world.ambient : Vec3{});
            if (emitters.empty()) {
                log.info("No diffuse light to calculate, ending radiosity.");
                break;
            }
            pass = lightPass(ctx, surfaces, layoutOptions, nullptr, SurfacePass{emitters, false, deluxe}, log, &total);
            addPass(total, pass);
            ctx.bounceLights.push_back(std::move(emitters));
        }
    }

    const StoreResult stored = storeLightmaps(ctx, total, true, log);
    vertexLightFromLightmaps(ctx, total);
    uint64_t styleLimitHits = 0;
    for (size_t k = 0; k < total.size(); ++k) {
        SurfaceLight& s = total[k];
        if (!s.ok) continue;
        ctx.stats.luxels += s.luxelCount;
        styleLimitHits += s.styleLimitHits;
        ++ctx.stats.lightmaps;
    }
    if (o.shGather) {
        // Kept for the SH gather, which reads the light of the surfaces its rays hit.
        ctx.bakedLight.assign(ctx.bsp.surfaces.size(), BakedSurfaceLight{});
        for (SurfaceLight& s : total)
            if (s.ok && s.layer(0))
                for (size_t m = 0; m < s.layout.surfaces.size() && m < s.layout.surfaceCoords.size(); ++m)
                    ctx.bakedLight[size_t(s.layout.surfaces[m])] = {s.width, s.height, s.layer(0)->color,
                                                                     s.layout.surfaceCoords[m]};
    }
    log.info(strCat(stored.blocks, " lightmaps on ", stored.pages, " pages, ", ctx.stats.luxels, " luxels"));
    if (styleLimitHits > 0)
        log.warning(strCat("Hit per-surface style limit (", kMaxLightmapStyles, ") on ", styleLimitHits,
                           " surface lights; those lights are left out"));
}

}  // namespace q3::light
