// The vertex-light phase: the colour of every draw vertex (used by vertex-lit surfaces and by
// engines running with r_vertexlight). Lightmapped surfaces take it from their finished lightmap;
// the others trace it like a luxel. Surfaces are lit in parallel, each writing only its own vertices.
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <span>

#include "light_context.h"
#include "light_text.h"

namespace q3::light {
namespace {

constexpr float kVertexEpsilon = -0.125f;  // VERTEX_EPSILON of q3map2's point-in-solid test
constexpr float kVertexNudge = 4.0f;       // how far a vertex sample may move out of solid
constexpr float kVertexPushOff = 1.0f;     // sample just in front of the surface

Vec3 traceVertex(const LightContext& ctx, const LightingEnv& env, Vec3 xyz, Vec3 normal, bool twoSided,
                 bool forceSunlight) {
    // q3map_forceSunlight: suns reach the vertex without occlusion.
    LightingEnv unoccluded = env;
    unoccluded.scene = nullptr;
    SamplePoint p{xyz + normal * kVertexPushOff, normal, -1, twoSided};
    if (ctx.tree && !ctx.bsp.nodes.empty()) {
        int cluster = ctx.tree->clusterForPointExt(p.origin, kVertexEpsilon);
        if (cluster < 0) {
            if (std::optional<Vec3> free = ctx.tree->nudgeOutOfSolid(p.origin, kVertexNudge, 1.0f, kVertexEpsilon)) {
                p.origin = *free;
                cluster = ctx.tree->clusterForPoint(p.origin);
            }
        }
        p.cluster = cluster;
    }
    Vec3 color = ctx.world.ambient;
    // Vertex-lit surfaces receive every radiosity pass (as q3map2 relights vertices each bounce).
    for (std::span<const Light> lights : {std::span<const Light>(ctx.lights), std::span<const Light>(ctx.bounceLights)})
        for (const Light& light : lights) {
            const bool open = forceSunlight && light.type == LightType::Sun;
            std::optional<LightContribution> c = lightToSample(light, p, open ? unoccluded : env);
            if (c && c->style == 0) color += c->color;
            if (ctx.options.cheap && color.x >= 255 && color.y >= 255 && color.z >= 255) return color;
        }
    return color;
}

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
    std::vector<uint64_t> counts(bsp.surfaces.size(), 0);
    auto body = [&](const tbb::blocked_range<size_t>& range) {
        for (size_t i = range.begin(); i != range.end(); ++i) {
            const bsp::Surface& s = bsp.surfaces[i];
            if (s.surfaceType == bsp::MST_FLARE || s.surfaceType == bsp::MST_BAD) continue;
            if (s.shaderNum < 0 || static_cast<size_t>(s.shaderNum) >= ctx.shaders.shaders.size()) continue;
            const LightingShader& shader = ctx.shaders.shaders[static_cast<size_t>(s.shaderNum)];
            if (shader.noVertexLight) continue;
            const Vec3 offset = ctx.surfaceOffsets[i];
            const LightingEnv surfaceEnv = receiverLightingEnv(ctx, env, static_cast<int>(i));
            for (int v = 0; v < s.numVerts; ++v) {
                const size_t vi = static_cast<size_t>(s.firstVert + v);
                bsp::DrawVert& dv = bsp.drawVerts[vi];
                Vec3 color = ctx.vertexFromLightmap[vi]
                                 ? ctx.vertexLight[vi]
                                 : traceVertex(ctx, surfaceEnv, Vec3::fromArray(dv.xyz) + offset,
                                               normalize(vi < ctx.shadedNormals.size() ? ctx.shadedNormals[vi]
                                                                                        : Vec3::fromArray(dv.normal)),
                                               shader.twoSided,
                                               shader.forceSunlight);
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
    arena.execute([&] { tbb::parallel_for(tbb::blocked_range<size_t>(0, bsp.surfaces.size(), 16), body); });
    for (uint64_t c : counts) ctx.stats.vertexes += c;
    log.info(strCat(ctx.stats.vertexes, " vertexes lit"));
}

}  // namespace q3::light
