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
// How far from its vertex the search may go on each axis (a box that holds every position it tries).
constexpr float kSearchReach = 2 * kVertexNudge;

// Whether any channel is above the ambient light (q3map2 keeps searching until a vertex is).
bool brighterThan(Vec3 c, Vec3 ambient) { return c.x > ambient.x || c.y > ambient.y || c.z > ambient.z; }

// Whether a light other than a sun lies behind a one-sided vertex's plane from every position its
// search may try (lightToSample then gives nothing at any of them): by more than the search's reach
// along the normal and a margin for the roundings of the dot products.
bool behindEverywhere(const Light& light, Vec3 xyz, Vec3 normal) {
    if (light.type == LightType::Sun) return false;
    const float reach = kSearchReach * (std::fabs(normal.x) + std::fabs(normal.y) + std::fabs(normal.z));
    const float scale = std::max({std::fabs(light.origin.x), std::fabs(light.origin.y), std::fabs(light.origin.z),
                                  std::fabs(xyz.x), std::fabs(xyz.y), std::fabs(xyz.z)});
    const float margin = 0.05f + 1e-5f * scale;
    return dot(light.origin, normal) - dot(xyz, normal) + reach < -margin;
}

// One pass's lights (the direct lights, or one bounce's emitters), their lightEnvelope each, and the
// index of which reach a box.
struct PassLights {
    std::span<const Light> lights;
    std::span<const float> envelopes;
    const LightReach& reach;

    // The lights that reach `box`, in light order, with their envelopes, but those `skip` rejects.
    template <typename Skip>
    void select(const Bounds& box, Skip&& skip, std::vector<uint32_t>& indices, std::vector<const Light*>& out,
                std::vector<float>& outEnvelopes) const {
        reach.reaching(box, indices);
        out.clear();
        outEnvelopes.clear();
        for (const uint32_t k : indices) {
            if (skip(lights[k])) continue;
            out.push_back(&lights[k]);
            outEnvelopes.push_back(envelopes[k]);
        }
    }
};

struct VertexTracer {
    const LightContext& ctx;
    const LightingEnv& env;
    std::span<const int> clusters;  // the surface's clusters: a sample point must see one of them
    std::span<const Light* const> lights;  // the lights whose envelope reaches the surface's vertexes
    std::span<const float> envelopes;      // their lightEnvelope, in the same order
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

    SamplePoint samplePoint(Vec3 origin, Vec3 normal, int cluster) const {
        return SamplePoint{origin, normal, ctx.tree && !ctx.bsp.nodes.empty() ? cluster : -1, twoSided};
    }

    // q3map_forceSunlight: suns reach the vertex without occlusion.
    bool unoccludedSun(const Light& light) const { return forceSunlight && light.type == LightType::Sun; }

    Vec3 lightAt(Vec3 origin, Vec3 normal, int cluster, float dirtFactor) const {
        LightingEnv unoccluded = env;
        unoccluded.scene = nullptr;
        const SamplePoint p = samplePoint(origin, normal, cluster);
        Vec3 color = ambient;
        for (size_t k = 0; k < lights.size(); ++k) {
            const Light& light = *lights[k];
            const LightingEnv& lightEnv = unoccludedSun(light) ? unoccluded : env;
            std::optional<LightContribution> c = lightToSample(light, p, lightEnv, envelopes[k]);
            if (c && c->style == 0) color += c->color;
            if (ctx.options.cheap && color.x >= 255 && color.y >= 255 && color.z >= 255) break;
        }
        return color * dirtFactor;
    }

    // lightAt for every point set in `points` at once (into out[i]): each light's shadow rays wait,
    // and all of them are traced as one batch; then each point adds its lights up in light order, as
    // lightAt does. Not with -cheap, whose early stop needs each sum as it grows.
    void lightAtAll(std::span<const std::optional<SamplePoint>> points, std::span<const float> dirtFactors,
                    std::span<std::optional<Vec3>> out) const {
        const size_t n = points.size();
        std::vector<uint32_t> which;
        for (size_t i = 0; i < n; ++i)
            if (points[i]) which.push_back(uint32_t(i));
        if (which.empty()) return;
        std::vector<ShadowRay> rays;
        std::vector<size_t> rayEntry;  // the contribution (light * n + point) each ray darkens
        LightingEnv deferred = env;
        deferred.deferredRays = env.scene ? &rays : nullptr;
        LightingEnv unoccluded = env;
        unoccluded.scene = nullptr;
        std::vector<Vec3> contributions(lights.size() * n);
        std::vector<size_t> traced;
        for (size_t k = 0; k < lights.size(); ++k) {
            const Light& light = *lights[k];
            if (light.style != 0) continue;  // lightAt keeps style 0 alone
            const std::span<Vec3> row(contributions.data() + k * n, n);
            if (!unoccludedSun(light) && samplesBatchable(light, deferred)) {
                traced.clear();
                lightToSamples(light, deferred, envelopes[k], points, which, row, nullptr, traced);
                for (const size_t i : traced) rayEntry.push_back(k * n + i);
                continue;
            }
            for (const uint32_t i : which) {
                const size_t before = rays.size();
                std::optional<LightContribution> c =
                    lightToSample(light, *points[i], unoccludedSun(light) ? unoccluded : deferred, envelopes[k]);
                if (!c) {
                    rays.resize(before);
                    continue;
                }
                row[i] = c->color;
                if (rays.size() > before) rayEntry.push_back(k * n + i);
            }
        }
        if (!rays.empty()) {
            std::vector<Vec3> transmission(rays.size());
            env.scene->traceBatch(rays, transmission);
            for (size_t r = 0; r < rays.size(); ++r) contributions[rayEntry[r]] *= transmission[r];
        }
        for (const uint32_t i : which) {
            Vec3 color = ambient;
            for (size_t k = 0; k < lights.size(); ++k) color += contributions[k * n + i];
            out[i] = color * dirtFactors[i];
        }
    }

    // q3map2 IlluminateVertexes, once the light at the vertex itself is known (`color`, nullopt when
    // the vertex is out of the world): when that is missing or no brighter than the ambient light,
    // the first position of a 4-unit lattice around it (x, then y, then z outermost first) that is
    // lit, else the last one out of solid. nullopt: every position was in solid.
    std::optional<Vec3> search(Vec3 xyz, Vec3 normal, float dirtFactor, std::optional<Vec3> color) const {
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

    // Vertexes [first, first + count) of `surface` (moved by `offset`) into traced[v - first] (those
    // that take their colour from a lightmap are left alone): the light at each vertex itself for
    // the whole block at once (its shadow rays traced together), then the search of each vertex that
    // is not lit there. A searching vertex asks only the lights of `pass` that reach the positions it
    // may try and, on a one-sided surface, are not behind it from all of them: the tracer's own list
    // holds every light that reaches any vertex of the surface, the others add nothing there, and
    // the rest keep their order.
    void traceBlock(const bsp::Surface& surface, Vec3 offset, int first, size_t count, const PassLights& pass,
                    std::span<std::optional<Vec3>> traced) const {
        std::vector<Vec3> xyz(count), normals(count);
        std::vector<float> dirtFactors(count, 1.0f);
        std::vector<std::optional<SamplePoint>> points(count);
        std::vector<std::optional<Vec3>> colors(count);
        std::vector<uint8_t> traces(count, 0);
        for (size_t j = 0; j < count; ++j) {
            const size_t vi = static_cast<size_t>(surface.firstVert + first) + j;
            if (ctx.vertexFromLightmap[vi]) continue;
            traces[j] = 1;
            const bsp::DrawVert& dv = ctx.bsp.drawVerts[vi];
            normals[j] = normalize(vi < ctx.shadedNormals.size() ? ctx.shadedNormals[vi] : Vec3::fromArray(dv.normal));
            xyz[j] = Vec3::fromArray(dv.xyz) + offset;
            dirtFactors[j] = dirtAt(xyz[j], normals[j]);
            if (const int cluster = freeCluster(xyz[j]); cluster >= 0)
                points[j] = samplePoint(xyz[j], normals[j], cluster);
        }
        if (ctx.options.cheap) {
            for (size_t j = 0; j < count; ++j)
                if (points[j]) colors[j] = lightAt(xyz[j], normals[j], points[j]->cluster, dirtFactors[j]);
        } else {
            lightAtAll(points, dirtFactors, colors);
        }
        std::vector<uint32_t> nearIndices;
        std::vector<const Light*> nearLights;
        std::vector<float> nearEnvelopes;
        for (size_t j = 0; j < count; ++j) {
            if (!traces[j]) continue;
            if (colors[j] && brighterThan(*colors[j], ambient)) {
                traced[j] = colors[j];
                continue;
            }
            const Vec3 reachBox = Vec3::splat(kSearchReach);
            const auto behind = [&](const Light& light) {
                return !twoSided && behindEverywhere(light, xyz[j], normals[j]);
            };
            pass.select(Bounds{xyz[j] - reachBox, xyz[j] + reachBox}, behind, nearIndices, nearLights, nearEnvelopes);
            VertexTracer near = *this;
            near.lights = nearLights;
            near.envelopes = nearEnvelopes;
            traced[j] = near.search(xyz[j], normals[j], dirtFactors[j], colors[j]);
        }
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
            reach.mins -= Vec3::splat(kSearchReach);
            reach.maxs += Vec3::splat(kSearchReach);
            const bool dirty = passes && !passes->noDirty[static_cast<size_t>(s.shaderNum)];
            // q3map2 relights vertexes after the direct pass and after each bounce, and adds the
            // passes up: each pass searches for its own lit position (a vertex the direct light
            // reaches only from a nudged point still takes the bounce where it stands).
            std::vector<Vec3> lit(size_t(std::max(0, s.numVerts)));
            auto addPass = [&](const PassLights& pass, Vec3 ambient) {
                // Lights whose envelope misses every position the search may try are skipped.
                std::vector<uint32_t> indices;
                std::vector<const Light*> reaching;
                std::vector<float> reachingEnvelopes;
                pass.select(reach, [](const Light&) { return false; }, indices, reaching, reachingEnvelopes);
                const VertexTracer tracer{ctx,         surfaceEnv,      clusters,
                                          reaching,    reachingEnvelopes, ambient,
                                          shader.twoSided, shader.forceSunlight, dirty ? passes : nullptr};
                // Traced vertexes first; those whose every position was in solid take the mean of
                // the lit ones (the pass's ambient light when none is). Blocks of kVertexBlock
                // vertexes, fixed whatever the threads; a surface of many vertexes (a large soup or
                // terrain) would otherwise keep one core busy after the others have finished, so
                // its blocks are traced in parallel too.
                std::vector<std::optional<Vec3>> traced(lit.size());
                constexpr int kVertexBlock = 32;
                auto traceBlock = [&](int block) {
                    const int first = block * kVertexBlock;
                    const size_t count = size_t(std::min(s.numVerts - first, kVertexBlock));
                    tracer.traceBlock(s, offset, first, count, pass, std::span(traced).subspan(size_t(first), count));
                };
                const int blocks = (std::max(0, s.numVerts) + kVertexBlock - 1) / kVertexBlock;
                if (blocks > 1)
                    tbb::parallel_for(0, blocks, traceBlock);
                else if (blocks == 1)
                    traceBlock(0);
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
                addPass(PassLights{ctx.lights, envelopes[0], reaches[0]}, surfaceAmbient(ctx, static_cast<int>(i)));
                for (size_t b = 0; b < ctx.bounceLights.size(); ++b)
                    addPass(PassLights{ctx.bounceLights[b], envelopes[b + 1], reaches[b + 1]}, Vec3{});
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
