// Pipeline steps that prepare lighting: option conversions, world-space surface geometry, the
// shadow scene and BSP tree, and the light list.
#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <future>

#include "entity_keys.h"
#include "light_context.h"
#include "lightmap_layout.h"
#include "light_text.h"
#include "surface_lighting.h"
#include "trace_pieces.h"
#include "patch.h"

namespace q3::light {
namespace {

// Origin of every BSP model from the entity that owns it ("model" "*N" with an "origin").
std::vector<Vec3> modelOrigins(const LightContext& ctx) {
    std::vector<Vec3> origins(ctx.bsp.models.size());
    for (const bsp::Entity& e : ctx.entities) {
        const std::string* model = e.find("model");
        if (!model || model->size() < 2 || (*model)[0] != '*') continue;
        const int index = std::atoi(model->c_str() + 1);
        if (index <= 0 || static_cast<size_t>(index) >= origins.size()) continue;
        origins[static_cast<size_t>(index)] = vecKey(e, {"origin"}).value_or(Vec3{});
    }
    return origins;
}

SceneSurface planarGeometry(const bsp::Bsp& bsp, const bsp::Surface& s, Vec3 offset) {
    SceneSurface out;
    out.xyz.reserve(static_cast<size_t>(s.numVerts));
    out.st.reserve(static_cast<size_t>(s.numVerts) * 2);
    for (int v = 0; v < s.numVerts; ++v) {
        const bsp::DrawVert& dv = bsp.drawVerts[static_cast<size_t>(s.firstVert + v)];
        out.xyz.push_back(Vec3::fromArray(dv.xyz) + offset);
        out.st.push_back(dv.st[0]);
        out.st.push_back(dv.st[1]);
    }
    for (int i = 0; i + 2 < s.numIndexes; i += 3)
        for (int k = 0; k < 3; ++k) {
            const int32_t idx = bsp.drawIndexes[static_cast<size_t>(s.firstIndex + i + k)];
            out.triangles.push_back(idx >= 0 && idx < s.numVerts ? static_cast<uint32_t>(idx) : 0u);
        }
    return out;
}

// `recordedCurve` is the longest curve -bsp wrote to the .srf for the surface's LOD group (0 when
// unknown): q3map2 tessellates shadow facets and emitters with it, so grouped patches get the
// iterations of the group's longest member, not their own.
SceneSurface patchGeometry(const bsp::Bsp& bsp, const bsp::Surface& s, Vec3 offset, float recordedCurve) {
    SceneSurface out;
    out.isPatch = true;
    patch::ControlGrid grid = patchControlGrid(bsp, s, offset);
    if (!patch::isValidGrid(grid)) return out;
    patch::PatchMesh mesh = recordedCurve > 0 ? patch::tessellateForLighting(grid, recordedCurve)
                                              : patch::tessellateForLighting(grid);
    out.meshWidth = mesh.width;
    out.meshHeight = mesh.height;
    for (const patch::PatchVertex& v : mesh.verts) {
        out.xyz.push_back(v.xyz);
        out.normals.push_back(v.normal);
        out.st.push_back(v.st[0]);
        out.st.push_back(v.st[1]);
    }
    out.triangles = mesh.indices;
    return out;
}

// Shadow flags of every BSP model from its entity (q3map2 GetEntityShadowFlags): the world casts
// and receives; other entities receive but cast only with _castShadows / _cs.
struct ShadowFlags {
    int cast = 1;
    int receive = 1;
};

std::vector<ShadowFlags> modelShadowFlags(const LightContext& ctx) {
    std::vector<ShadowFlags> flags(ctx.bsp.models.size());
    for (size_t m = 1; m < flags.size(); ++m) flags[m].cast = 0;
    for (const bsp::Entity& e : ctx.entities) {
        const std::string* model = e.find("model");
        if (!model || model->size() < 2 || (*model)[0] != '*') continue;
        const int index = std::atoi(model->c_str() + 1);
        if (index <= 0 || static_cast<size_t>(index) >= flags.size()) continue;
        flags[static_cast<size_t>(index)].cast = intKey(e, {"_castShadows", "_cs"}).value_or(0);
        flags[static_cast<size_t>(index)].receive = intKey(e, {"_receiveShadows", "_rs"}).value_or(1);
    }
    return flags;
}

}  // namespace

LightScales lightScalesFromOptions(const LightOptions& o) {
    LightScales s;
    s.pointScale = o.pointScale;
    s.spotScale = o.spotScale;
    s.areaScale = o.areaScale;
    s.skyScale = o.skyScale;
    s.extraDist = o.extraDist;
    s.backsplashFractionScale = o.backsplashFractionScale;
    s.backsplashDistance = o.backsplashDistance;
    s.fast = o.fast || o.faster;
    s.fastPoint = o.fastPoint;
    s.wolfLight = o.wolfLight;
    s.noStyles = o.noStyles;
    s.oneSky = o.oneSky;
    return s;
}

ColorOptions colorOptionsFromOptions(const LightOptions& o, float maxLight) {
    ColorOptions c;
    c.brightness = o.brightness;
    c.contrast = o.contrast;
    c.gamma = o.gamma;
    c.exposure = o.exposure;
    c.saturation = o.saturation;
    c.compensate = o.compensate;
    c.maxLight = maxLight;
    c.sRGB = o.lightmapsRGB;
    return c;
}

void buildSurfaceGeometry(LightContext& ctx) {
    const bsp::Bsp& bsp = ctx.bsp;
    const std::vector<Vec3> origins = modelOrigins(ctx);
    const std::vector<ShadowFlags> modelFlags = modelShadowFlags(ctx);
    std::vector<Vec3> surfaceOffset(bsp.surfaces.size());
    std::vector<ShadowFlags> surfaceFlags(bsp.surfaces.size());
    for (size_t m = 0; m < bsp.models.size(); ++m) {
        const bsp::Model& model = bsp.models[m];
        for (int i = 0; i < model.numSurfaces; ++i) {
            const size_t s = static_cast<size_t>(model.firstSurface + i);
            if (s >= surfaceOffset.size()) continue;
            surfaceOffset[s] = origins[m];
            surfaceFlags[s] = modelFlags[m];
        }
    }
    // The .srf records what -bsp decided per surface (func_groups merged into the world, _cs keys).
    if (ctx.extras.loaded)
        for (size_t s = 0; s < surfaceFlags.size(); ++s) {
            const SurfaceExtra& extra = ctx.extras.forSurface(static_cast<int>(s));
            surfaceFlags[s] = {extra.castShadows, extra.receiveShadows};
        }
    ctx.receiveShadows.assign(bsp.surfaces.size(), 1);
    for (size_t s = 0; s < surfaceFlags.size(); ++s) ctx.receiveShadows[s] = surfaceFlags[s].receive;
    ctx.surfaceOffsets = surfaceOffset;
    ctx.surfaceClusters = surfaceClusterLists(bsp, surfaceOffset);
    ctx.surfaces.clear();
    ctx.surfaces.resize(bsp.surfaces.size());
    for (size_t i = 0; i < bsp.surfaces.size(); ++i) {
        const bsp::Surface& s = bsp.surfaces[i];
        SceneSurface geometry;
        if (s.surfaceType == bsp::MST_PLANAR || s.surfaceType == bsp::MST_TRIANGLE_SOUP)
            geometry = planarGeometry(bsp, s, surfaceOffset[i]);
        else if (s.surfaceType == bsp::MST_PATCH)
            geometry = patchGeometry(bsp, s, surfaceOffset[i],
                                     ctx.extras.loaded ? ctx.extras.forSurface(int(i)).longestCurve : 0.0f);
        geometry.surfaceNum = static_cast<int>(i);
        geometry.castShadows = surfaceFlags[i].cast;
        if (s.shaderNum >= 0 && static_cast<size_t>(s.shaderNum) < ctx.shaders.shaders.size())
            geometry.shader = &ctx.shaders.shaders[static_cast<size_t>(s.shaderNum)];
        ctx.surfaces[i] = std::move(geometry);
    }
}

void buildBspQueries(LightContext& ctx) {
    Log quiet(false);
    ctx.skyIndices = assignSkyIndices(ctx.bsp, ctx.shaders.shaders, ctx.world.noShaderSun, ctx.options.oneSky, quiet);
    for (SceneSurface& s : ctx.surfaces) {
        const int shaderNum = ctx.bsp.surfaces[static_cast<size_t>(s.surfaceNum)].shaderNum;
        s.skyIndex = shaderNum >= 0 && static_cast<size_t>(shaderNum) < ctx.skyIndices.size()
                         ? ctx.skyIndices[static_cast<size_t>(shaderNum)]
                         : -1;
    }
    std::vector<uint8_t> translucent;
    translucent.reserve(ctx.shaders.shaders.size());
    for (const LightingShader& s : ctx.shaders.shaders)
        translucent.push_back(s.translucent || s.alphaShadow || s.lightFilter || s.fog ? 1 : 0);
    ctx.tree = std::make_unique<BspTree>(ctx.bsp, translucent);
    std::vector<int> surfaceSkyIndex(ctx.surfaces.size(), -2);
    for (const SceneSurface& s : ctx.surfaces)
        if (s.shader && s.shader->sky) surfaceSkyIndex[static_cast<size_t>(s.surfaceNum)] = s.skyIndex;
    ctx.skyVisibility = SkyVisibility(ctx.bsp, *ctx.tree, surfaceSkyIndex);
}

void buildScene(LightContext& ctx, bool sunRays) {
    if (!ctx.tree) buildBspQueries(ctx);
    TraceSceneOptions options;
    options.patchShadows = ctx.options.patchShadows;
    options.sunRays = sunRays;
    const BspTree* tree = ctx.tree.get();
    options.solidBetween = [tree](Vec3 from, Vec3 to) { return tree->segmentCrossesSolid(from, to); };
    options.hullClearOfSolid = [tree](std::span<const Vec3> points) { return tree->hullWalkOfSolid(points); };
    options.solidBetweenInHull = [tree](const HullVerdict& hull, Vec3 from, Vec3 to) {
        return tree->segmentCrossesSolidFrom(hull, from, to);
    };
    // The casters as q3map2's tracer cuts and tests them: a ray passing within 1 % of a piece
    // beside it is stopped (trace_pieces.h). Sun rays meet solid where its walk does.
    TraceLeafContents contents;
    // The solid shell needs only the tree: made on a thread of its own while the pieces are cut
    // (its serial walk would otherwise leave a core idle).
    std::future<SolidShell> shell =
        std::async(ctx.threads == 1 ? std::launch::deferred : std::launch::async, [&ctx, tree] {
            return solidShellOf(ctx.bsp.models.empty() ? nullptr : &ctx.bsp.models[0], *tree);
        });
    CasterPieces pieces = traceCasterPieces(ctx.surfaces, ctx.bsp, options, &contents, ctx.threads);
    auto skySolid = std::make_shared<const SkyRaySolid>(ctx.bsp, contents);
    options.skySolidBetween = [skySolid](Vec3 from, Vec3 to) { return skySolid->stops(from, to); };
    options.skyHullClear = [skySolid](std::span<const Vec3> points) { return skySolid->hullWalk(points); };
    options.skySolidBetweenInHull = [skySolid](const HullVerdict& hull, Vec3 from, Vec3 to) {
        return skySolid->stopsFrom(hull, from, to);
    };
    options.solidShell = shell.get();
    ctx.scene = std::make_unique<TraceScene>(pieces.surfaces, options, pieces.forSunOnly);
}

void createLights(LightContext& ctx, Log& log) {
    const std::string name = ctx.bspPath.string();
    std::vector<bsp::Entity> all = ctx.entities;
    all.insert(all.end(), ctx.mapLights.begin(), ctx.mapLights.end());
    std::vector<bsp::Entity> targets = all;
    targets.insert(targets.end(), ctx.mapTargets.begin(), ctx.mapTargets.end());
    // Light creation draws from the C library sequence first, as q3map2's does before its grid.
    ctx.random = CLibraryRandom();
    ctx.lights = createEntityLights(all, targets, ctx.scales, log, name, ctx.random);

    const bool noShaderSun = ctx.world.noShaderSun;
    std::vector<Light> shaderLights = createShaderLights(
        ctx.bsp, ctx.shaders.shaders, ctx.skyIndices, noShaderSun, ctx.scales, ctx.random, [&ctx](int surfaceNum) {
            const SceneSurface& s = ctx.surfaces[static_cast<size_t>(surfaceNum)];
            EmitterGeometry g;
            g.xyz = s.xyz;
            g.triangles = s.triangles;
            g.normals = s.normals;
            g.meshWidth = s.meshWidth;
            g.meshHeight = s.meshHeight;
            return g;
        });
    ctx.lights.insert(ctx.lights.end(), shaderLights.begin(), shaderLights.end());

    const int inSolid = assignLightClusters(ctx, ctx.lights);
    if (inSolid > 0) log.info(strCat(inSolid, " lights in solid removed"));

    size_t counts[4] = {0, 0, 0, 0};
    for (const Light& l : ctx.lights) ++counts[static_cast<int>(l.type)];
    log.info(strCat(counts[0], " point lights, ", counts[1], " spotlights, ", counts[2], " suns, ", counts[3],
                    " area lights"));
}

int assignLightClusters(const LightContext& ctx, std::vector<Light>& lights) {
    // Clusters for PVS culling. Lights inside solid are removed, as q3map2 does, after trying
    // small fixed nudges.
    std::vector<Light> kept;
    kept.reserve(lights.size());
    int inSolid = 0;
    for (Light& light : lights) {
        if (light.type == LightType::Sun || !ctx.tree || ctx.bsp.nodes.empty()) {
            kept.push_back(std::move(light));
            continue;
        }
        // q3map2 SetupEnvelopes: LIGHT_EPSILON 0.125; a light in solid tries the 64 nudges of
        // 0, 0, +2, -2 units per axis (x outermost), each from where the last free one moved it,
        // without stopping at the first free one: the light's cluster is the last try's, so a
        // light whose last try lands in solid is removed even when an earlier one was free.
        constexpr float kLightEpsilon = 0.125f;
        constexpr float kSteps[4] = {0.0f, 0.0f, 2.0f, -2.0f};
        int cluster = ctx.tree->clusterForPointExt(light.origin, kLightEpsilon);
        if (cluster < 0)
            for (int i = 0; i < 64; ++i) {
                const Vec3 nudged = light.origin + Vec3{kSteps[i / 16], kSteps[(i / 4) % 4], kSteps[i % 4]};
                cluster = ctx.tree->clusterForPointExt(nudged, kLightEpsilon);
                if (cluster >= 0) light.origin = nudged;
            }
        if (cluster < 0) {
            ++inSolid;
            continue;
        }
        light.cluster = cluster;
        kept.push_back(std::move(light));
    }
    lights = std::move(kept);
    return inSolid;
}

LightingEnv surfaceLightingEnv(const LightContext& ctx) {
    LightingEnv env;
    env.scene = ctx.options.noTrace ? nullptr : ctx.scene.get();
    env.tree = ctx.tree.get();
    env.skies = &ctx.skyVisibility;
    env.settings.faster = ctx.options.faster;
    env.settings.lightAngleHL = ctx.options.lightAngleHL;
    env.settings.sunOnly = ctx.options.sunOnly;
    env.settings.forceFast = ctx.options.fast || ctx.options.faster;
    env.settings.ignoreNear = 1.5f;  // DEFAULT_INHIBIT_RADIUS around luxels and vertices
    return env;
}

LightingEnv gridLightingEnv(const LightContext& ctx, Vec3 cellSize) {
    LightingEnv env = surfaceLightingEnv(ctx);
    // q3map2 TraceGrid: occluders closer to the point than half the largest cell side are ignored
    // (its inhibit radius), so that a point stands for its cell rather than its exact position;
    // structural solid blocks whatever its distance (the scene's solid test, for every sample).
    env.settings.ignoreNear = 0.5f * maxComponent(cellSize);
    env.settings.forceFast = env.settings.forceFast || ctx.options.fastGrid;
    if (ctx.scene) env.rayMask = ctx.scene->receiverMask(1);  // grid points receive as the world does
    return env;
}

LightingEnv receiverLightingEnv(const LightContext& ctx, const LightingEnv& env, int surfaceNum) {
    LightingEnv out = env;
    const int group = static_cast<size_t>(surfaceNum) < ctx.receiveShadows.size()
                          ? ctx.receiveShadows[static_cast<size_t>(surfaceNum)]
                          : 1;
    if (group == 0) out.scene = nullptr;  // lit as if nothing occluded it
    if (out.scene) out.rayMask = out.scene->receiverMask(group);
    return out;
}

}  // namespace q3::light
