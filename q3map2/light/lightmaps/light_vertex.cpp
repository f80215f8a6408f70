// The vertex-light phase: the colour of every draw vertex (used by vertex-lit surfaces and by
// engines running with r_vertexlight). Lightmapped surfaces take it from their finished lightmap;
// the others trace it like a luxel. Surfaces are lit in parallel, each writing only its own vertices.
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <span>

#include "dirt.h"
#include "light_context.h"
#include "light_reach.h"
#include "light_text.h"
#include "surface_lighting.h"

namespace q3::light {
namespace {

constexpr float kVertexEpsilon = -0.125f;  // VERTEX_EPSILON of q3map2's point-in-solid test
constexpr float kVertexNudge = 4.0f;       // VERTEX_NUDGE: the step of the search for a lit position
// Steps of the search along each axis, in q3map2's order (its formula yields 0, 0, 1, -1, 2; the
// repeated 0 would only retry the same point).
constexpr int kNudgeSteps[4] = {0, 1, -1, 2};

// Whether any channel is above the ambient light (q3map2 keeps searching until a vertex is).
bool brighterThan(Vec3 c, Vec3 ambient) { return c.x > ambient.x || c.y > ambient.y || c.z > ambient.z; }

struct VertexTracer {
    const LightContext& ctx;
    const LightingEnv& env;
    std::span<const int> clusters;  // the surface's clusters: a sample point must see one of them
    std::span<const Light* const> lights;  // the lights whose envelope reaches the surface's vertexes
    Vec3 ambient;  // the surface's ambient (surfaceAmbient) in the direct pass; radiosity passes add none
    bool twoSided = false;
    bool forceSunlight = false;
    // -dirty: q3map2 darkens each traced vertex by the dirt at the vertex itself, also when the
    // light comes from a nudged position (no smoothing between vertexes, unlike luxels). Null: no
    // dirt on this surface.
    const LuxelPasses* dirt = nullptr;

    int freeCluster(Vec3 point) const {
        if (!ctx.tree || ctx.bsp.nodes.empty()) return 0;
        return clusterSeenBySurface(*ctx.tree, ctx.tree->clusterForPointExt(point, kVertexEpsilon), clusters);
    }

    float dirtAt(Vec3 xyz, Vec3 normal) const {
        if (!dirt) return 1.0f;
        return dirtForSample(xyz, normal, *dirt->scene, dirt->dirt, dirtSeed(xyz), env.settings.ignoreNear, dirt->tree);
    }

    Vec3 lightAt(Vec3 origin, Vec3 normal, int cluster, float dirtFactor) const {
        // q3map_forceSunlight: suns reach the vertex without occlusion.
        LightingEnv unoccluded = env;
        unoccluded.scene = nullptr;
        const SamplePoint p{origin, normal, ctx.tree && !ctx.bsp.nodes.empty() ? cluster : -1, twoSided};
        Vec3 color = ambient;
        for (const Light* light : lights) {
            const bool open = forceSunlight && light->type == LightType::Sun;
            std::optional<LightContribution> c = lightToSample(*light, p, open ? unoccluded : env);
            if (c && c->style == 0) color += c->color;
            if (ctx.options.cheap && color.x >= 255 && color.y >= 255 && color.z >= 255) break;
        }
        return color * dirtFactor;
    }

    // q3map2 IlluminateVertexes: the light at the vertex itself; when that is out of the world or no
    // brighter than the ambient light, the first position of a 4-unit lattice around it (x, then y,
    // then z outermost first) that is lit, else the last one out of solid. nullopt: every position
    // was in solid.
    std::optional<Vec3> trace(Vec3 xyz, Vec3 normal) const {
        std::optional<Vec3> color;
        const float dirtFactor = dirtAt(xyz, normal);
        if (const int cluster = freeCluster(xyz); cluster >= 0) color = lightAt(xyz, normal, cluster, dirtFactor);
        if (color && brighterThan(*color, ambient)) return color;
        for (int x : kNudgeSteps)
            for (int y : kNudgeSteps)
                for (int z : kNudgeSteps) {
                    const Vec3 origin = xyz + Vec3{float(x), float(y), float(z)} * kVertexNudge;
                    const int cluster = freeCluster(origin);
                    if (cluster < 0) continue;
                    color = lightAt(origin, normal, cluster, dirtFactor);
                    if (brighterThan(*color, ambient)) return color;
                }
        return color;
    }
};

}  // namespace

void lightVertexes(LightContext& ctx, Log& log) {
    const LightOptions& o = ctx.options;
    bsp::Bsp& bsp = ctx.bsp;
    if (o.noVertexLight) {
        if (o.vertexLightValue >= 0) {
            const uint8_t v = static_cast<uint8_t>(std::clamp(o.vertexLightValue, 0.f, 1.f) * 255.0f);
            for (bsp::DrawVert& dv : bsp.drawVerts) dv.color[0] = dv.color[1] = dv.color[2] = v;
            log.info(strCat("vertex light set to ", static_cast<int>(v), " on every vertex"));
        }
        return;
    }
    if (ctx.vertexLight.size() != bsp.drawVerts.size()) {
        ctx.vertexLight.assign(bsp.drawVerts.size(), Vec3{});
        ctx.vertexFromLightmap.assign(bsp.drawVerts.size(), 0);
    }
    const LightingEnv env = surfaceLightingEnv(ctx);
    const LuxelPasses* passes = ctx.luxelPasses && ctx.luxelPasses->dirty ? ctx.luxelPasses.get() : nullptr;
    std::vector<uint64_t> counts(bsp.surfaces.size(), 0);
    // Each pass's light envelopes, once for all surfaces: [0] the direct lights, then each bounce.
    std::vector<std::vector<float>> envelopes{lightEnvelopes(ctx.lights, env.settings.forceFast)};
    for (const std::vector<Light>& bounced : ctx.bounceLights)
        envelopes.push_back(lightEnvelopes(bounced, env.settings.forceFast));
    std::vector<LightReach> reaches{LightReach(ctx.lights, envelopes[0])};
    for (size_t b = 0; b < ctx.bounceLights.size(); ++b) reaches.emplace_back(ctx.bounceLights[b], envelopes[b + 1]);
    auto body = [&](const tbb::blocked_range<size_t>& range) {
        for (size_t i = range.begin(); i != range.end(); ++i) {
            const bsp::Surface& s = bsp.surfaces[i];
            if (s.surfaceType == bsp::MST_FLARE || s.surfaceType == bsp::MST_BAD) continue;
            if (s.shaderNum < 0 || static_cast<size_t>(s.shaderNum) >= ctx.shaders.shaders.size()) continue;
            const LightingShader& shader = ctx.shaders.shaders[static_cast<size_t>(s.shaderNum)];
            if (shader.noVertexLight) continue;
            const Vec3 offset = ctx.surfaceOffsets[i];
            const LightingEnv surfaceEnv = receiverLightingEnv(ctx, env, static_cast<int>(i));
            const std::vector<int>& clusters = ctx.surfaceClusters[i];
            Bounds reach;
            for (int v = 0; v < s.numVerts; ++v)
                reach.add(Vec3::fromArray(bsp.drawVerts[static_cast<size_t>(s.firstVert + v)].xyz) + offset);
            reach.mins -= Vec3::splat(2 * kVertexNudge);
            reach.maxs += Vec3::splat(2 * kVertexNudge);
            const bool dirty = passes && !passes->noDirty[static_cast<size_t>(s.shaderNum)];
            // q3map2 relights vertexes after the direct pass and after each bounce, and adds the
            // passes up: each pass searches for its own lit position (a vertex the direct light
            // reaches only from a nudged point still takes the bounce where it stands).
            std::vector<Vec3> lit(size_t(std::max(0, s.numVerts)));
            auto addPass = [&](std::span<const Light> passLights, const LightReach& passReach, Vec3 ambient) {
                // Lights whose envelope misses every position the search may try are skipped.
                std::vector<uint32_t> indices;
                passReach.reaching(reach, indices);
                std::vector<const Light*> reaching;
                for (const uint32_t k : indices) reaching.push_back(&passLights[k]);
                const VertexTracer tracer{ctx,     surfaceEnv,      clusters,           reaching,
                                          ambient, shader.twoSided, shader.forceSunlight, dirty ? passes : nullptr};
                // Traced vertexes first; those whose every position was in solid take the mean of
                // the lit ones (the pass's ambient light when none is).
                std::vector<std::optional<Vec3>> traced(lit.size());
                auto traceRange = [&](const tbb::blocked_range<int>& vertexes) {
                    for (int v = vertexes.begin(); v != vertexes.end(); ++v) {
                        const size_t vi = static_cast<size_t>(s.firstVert + v);
                        if (ctx.vertexFromLightmap[vi]) continue;
                        const bsp::DrawVert& dv = bsp.drawVerts[vi];
                        const Vec3 normal = normalize(vi < ctx.shadedNormals.size() ? ctx.shadedNormals[vi]
                                                                                    : Vec3::fromArray(dv.normal));
                        traced[size_t(v)] = tracer.trace(Vec3::fromArray(dv.xyz) + offset, normal);
                    }
                };
                // A surface of many vertexes (a large soup or terrain) would otherwise keep one core
                // busy after the others have finished: its vertexes are traced in parallel too.
                constexpr int kVertexGrain = 4;
                if (s.numVerts > 2 * kVertexGrain)
                    tbb::parallel_for(tbb::blocked_range<int>(0, s.numVerts, kVertexGrain), traceRange);
                else
                    traceRange(tbb::blocked_range<int>(0, std::max(0, s.numVerts)));
                Vec3 litSum;
                int litCount = 0;
                for (int v = 0; v < s.numVerts; ++v) {
                    if (traced[size_t(v)] && brighterThan(*traced[size_t(v)], ambient)) {
                        litSum += *traced[size_t(v)];
                        ++litCount;
                    }
                }
                const Vec3 fallback = litCount > 0 ? litSum / float(litCount) : ambient;
                for (size_t v = 0; v < lit.size(); ++v) lit[v] += traced[v].value_or(fallback);
            };
            // A lightmapped surface takes every vertex colour from its lightmap: nothing to trace.
            bool traces = false;
            for (int v = 0; v < s.numVerts && !traces; ++v) traces = !ctx.vertexFromLightmap[size_t(s.firstVert + v)];
            if (traces) {
                addPass(ctx.lights, reaches[0], surfaceAmbient(ctx, static_cast<int>(i)));
                for (size_t b = 0; b < ctx.bounceLights.size(); ++b)
                    addPass(ctx.bounceLights[b], reaches[b + 1], Vec3{});
            }
            for (int v = 0; v < s.numVerts; ++v) {
                const size_t vi = static_cast<size_t>(s.firstVert + v);
                bsp::DrawVert& dv = bsp.drawVerts[vi];
                Vec3 color = ctx.vertexFromLightmap[vi] ? ctx.vertexLight[vi] : lit[size_t(v)];
                color = vmax(color, ctx.world.minVertexLight);
                const Rgb8 bytes = colorToBytes(color, o.vertexScale * shader.vertexScale, ctx.color);
                dv.color[0] = bytes[0];
                dv.color[1] = bytes[1];
                dv.color[2] = bytes[2];
                ++counts[i];
            }
        }
    };
    tbb::task_arena arena(ctx.threads > 0 ? ctx.threads : tbb::task_arena::automatic);
    arena.execute([&] { tbb::parallel_for(tbb::blocked_range<size_t>(0, bsp.surfaces.size(), 1), body); });
    for (uint64_t c : counts) ctx.stats.vertexes += c;
    log.info(strCat(ctx.stats.vertexes, " vertexes lit"));
}

}  // namespace q3::light
