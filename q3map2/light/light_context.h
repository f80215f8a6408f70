// The state that flows through the -light pipeline, step by step: inputs are loaded into it, the
// scene and light list are built from them, and the lighting steps write their results into the
// BSP it holds. Each step is a free function of this struct so that it can be run and tested alone.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "bsp_tree.h"
#include "bspfile.h"
#include "color_pipeline.h"
#include "grid_blocks.h"
#include "grid_encode.h"
#include "grid_sh_gather.h"
#include "light_contribution.h"
#include "light_options.h"
#include "light_shaders.h"
#include "lights.h"
#include "luxel_passes.h"
#include "common_options.h"
#include "log.h"
#include "shader_info.h"
#include "sky_visibility.h"
#include "srf_file.h"
#include "trace_scene.h"
#include "vfs.h"

namespace q3::light {

struct LightStats {
    uint64_t luxels = 0;          // super luxels lit
    uint64_t vertexes = 0;        // draw vertices lit
    uint64_t gridPoints = 0;      // grid points lit
    uint64_t gridPointsInSolid = 0;  // grid points left dark (no free point nearby)
    uint64_t lightmaps = 0;       // raw lightmaps
    uint64_t shGatherRays = 0;    // -shgather rays traced
    double shGatherSeconds = 0;   // -shgather time (scene build, rays, projection)
};

struct LightContext {
    LightOptions options;
    int threads = 0;  // 0 = one per core

    // Inputs.
    std::filesystem::path bspPath;
    std::string commandLine;
    bsp::Bsp bsp;
    std::vector<bsp::Entity> entities;   // of the BSP; written back
    std::vector<bsp::Entity> mapLights;  // light entities re-read from the .map (never written back)
    std::vector<bsp::Entity> mapTargets; // other .map entities with a targetname (spotlight targets)
    std::unique_ptr<Vfs> vfs;
    std::unique_ptr<ShaderTable> shaderTable;
    SurfaceExtras extras;
    LightingShaderSet shaders;           // one per BSP shader
    WorldLighting world;

    // Scene.
    std::vector<SceneSurface> surfaces;  // world-space geometry of every BSP surface
    std::vector<Vec3> surfaceOffsets;    // per BSP surface: origin of the brush model it belongs to
    std::vector<std::vector<int>> surfaceClusters;  // per BSP surface: clusters of the leafs listing it
    // Per lightmapped BSP surface: the surfaceClusters of every surface sharing its q3map2 raw
    // lightmap; a light must be seen from one of them (empty: no test).
    std::vector<std::vector<int>> lightmapGroupClusters;
    std::vector<int> receiveShadows;     // per BSP surface: shadow group it receives from (0 = none)
    std::vector<Vec3> shadedNormals;     // per draw vertex; empty = the BSP's normals (phong.h)
    std::unique_ptr<ShaderAlbedoSet> albedo;  // textures as reflectors (-bounce, -shgather); shaderAlbedo()
    std::vector<int> skyIndices;         // per BSP shader
    std::unique_ptr<BspTree> tree;
    SkyVisibility skyVisibility;         // skies each cluster may see (sun culling)
    std::unique_ptr<TraceScene> scene;
    std::vector<Light> lights;
    // q3map2's rand() sequence as light creation left it; the legacy grid's nudges continue it.
    CLibraryRandom random;
    std::vector<std::vector<Light>> bounceLights;  // -bounce: the emitters of each radiosity pass
    // Floodlight and dirt (luxel_passes.h), prepared once by the stage for lightmaps and vertexes;
    // null when neither is in use.
    std::unique_ptr<LuxelPasses> luxelPasses;

    // Settings derived from the options.
    LightScales scales;
    ColorOptions color;

    // Vertex light taken from finished lightmaps (per draw vertex; `vertexLit` false = trace it).
    std::vector<Vec3> vertexLight;
    std::vector<uint8_t> vertexFromLightmap;
    // -shgather only: the linear light of every lightmapped surface, per BSP surface (grid_sh_gather.h).
    std::vector<BakedSurfaceLight> bakedLight;

    LightStats stats;
};

// The ambient light of a surface's lightmap and vertexes. With a .srf, its ambientColor, as q3map2's
// -light takes it: the surface entity's _color x _ambient, else the default block's (the worldspawn's,
// as -bsp writes it). Without a .srf (q3map2 refuses to light then), the worldspawn's.
inline Vec3 surfaceAmbient(const LightContext& ctx, int surfaceNum) {
    return ctx.extras.loaded ? ctx.extras.forSurface(surfaceNum).ambientColor : ctx.world.ambient;
}

// Options -> light scales, colour options (the -scale multiplier applied to every light scale).
LightScales lightScalesFromOptions(const LightOptions& options);
ColorOptions colorOptionsFromOptions(const LightOptions& options, float maxLight);

// Pipeline steps, in order. Each reads what earlier steps left in the context.
// Shaders, .srf, BSP, entities and (unless worldspawn _keepLights) the .map's light entities.
void loadLightInputs(LightContext& ctx, const CommonOptions& common, Log& log);
// World-space geometry of every surface: bmodel origins applied, patches tessellated.
void buildSurfaceGeometry(LightContext& ctx);
// -shade / -shadeangle: the phong-smoothed normal of every draw vertex into shadedNormals (left
// empty when phong shading is off or changes nothing); logs how many vertices were smoothed.
void smoothNormals(LightContext& ctx, Log& log);
// Sky indices, the BSP tree (clusters, PVS, solidity) and the sky visibility.
void buildBspQueries(LightContext& ctx);
// The casters' Embree scene (after buildBspQueries, which it runs when that has not run).
// `sunRays` false: no sun ray will be traced (the lights have none), and the pieces that only sun
// rays meet are left out.
void buildScene(LightContext& ctx, bool sunRays = true);
// The light list: entity lights of the BSP and the .map, shader suns, skies and surface lights.
void createLights(LightContext& ctx, Log& log);
// PVS cluster of every non-sun light; lights stuck in solid are removed (their count is returned).
int assignLightClusters(const LightContext& ctx, std::vector<Light>& lights);
// Lightmaps of every lightmapped surface (direct light, then -bounce passes whose emitters are
// kept in ctx.bounceLights), packed into the BSP (or external pages).
void lightLightmaps(LightContext& ctx, Log& log);
// Vertex colours of every draw vertex, from ctx.lights and the radiosity emitters ctx.bounceLights.
void lightVertexes(LightContext& ctx, Log& log);
// Where the legacy grid's points sit: its layout, and each lattice point as q3map2 places it
// (nudged out of solid by the C library sequence light creation left in ctx.random; nullopt when
// every nudge stays in solid). Reads only the BSP's tree, entities and that sequence, so it may
// run while the lightmaps are lit.
struct GridPlacement {
    GridLayout layout;
    std::vector<std::optional<PlacedGridPoint>> points;  // lattice order
};
GridPlacement placeLightGrid(const LightContext& ctx);
// The legacy light grid (lump 15), from `placed` (placeLightGrid's, made here when null); writes
// the grid size back to worldspawn when it grew.
void lightGrid(LightContext& ctx, Log& log, const GridPlacement* placed = nullptr);
// Worldspawn gains _q3map2_cmdline / _q3map2_version; the BSP is written atomically.
void writeLitBsp(LightContext& ctx, Log& log);
// Seams for the later stages: SH grid (SetupGridSH / TraceGridSH), bounce, dirt and deluxe maps
// plug in between lightVertexes and lightGrid, reading the same context.

// Environment used to light luxels and vertices (scene, tree, settings).
LightingEnv surfaceLightingEnv(const LightContext& ctx);
LightingEnv gridLightingEnv(const LightContext& ctx, Vec3 cellSize);
// `env` for the luxels and vertices of one surface: its receive shadow group picks the casters.
LightingEnv receiverLightingEnv(const LightContext& ctx, const LightingEnv& env, int surfaceNum);

}  // namespace q3::light
