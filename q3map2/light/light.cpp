// The -light stage driver: load -> scene -> lights -> lightmaps -> vertex light -> legacy grid ->
// write. Each step is a function of the LightContext (light_context.h); this file only sequences
// them, times them and writes the result.
#include <oneapi/tbb/task_arena.h>
#include <oneapi/tbb/task_group.h>

#include <algorithm>
#include <cstring>
#include <future>
#include <memory>

#include "file_io.h"
#include "light_context.h"
#include "light_stage.h"

#include "deluxe.h"
#include "grid_encode.h"
#include "grid_sh.h"
#include "light_text.h"
#include "map_file.h"
#include "phase_timer.h"
#include "shader_info.h"
#include "shader_loader.h"
#include "vfs.h"
#include "world_lights_export.h"

namespace q3::light {
namespace {

// Light entities of the .map source (q3map2 re-reads them because -bsp strips them from the BSP),
// and the entities they may target. Returns the line to log.
std::string loadMapLights(LightContext& ctx) {
    std::filesystem::path mapPath = ctx.bspPath;
    mapPath.replace_extension(".map");
    if (!std::filesystem::exists(mapPath)) return strCat("no ", mapPath.string(), ": using the light entities of the BSP only");
    map::MapFile mapFile = map::loadMap(mapPath);
    for (const map::MapEntity& e : mapFile.entities) {
        bsp::Entity entity;
        entity.pairs = e.pairs;
        if (map::isLightEntity(e))
            ctx.mapLights.push_back(std::move(entity));
        else if (e.find("targetname"))
            ctx.mapTargets.push_back(std::move(entity));
    }
    return strCat(ctx.mapLights.size(), " light entities read from ", mapPath.string());
}

}  // namespace

void loadLightInputs(LightContext& ctx, const CommonOptions& common, Log& log) {
    ctx.bspPath = common.mapPath;
    ctx.bspPath.replace_extension(".bsp");
    ctx.commandLine = common.commandLine;
    ctx.threads = common.threads;

    VfsOptions vfsOptions;
    vfsOptions.game = common.game;
    for (const std::string& p : common.basePaths) vfsOptions.basePaths.emplace_back(p);
    if (!common.fsGame.empty()) vfsOptions.gameDirs.push_back(common.fsGame);
    vfsOptions.baseGame = common.baseGame;
    if (!common.homePath.empty()) vfsOptions.homePath = common.homePath;
    vfsOptions.baseGame = common.baseGame;
    vfsOptions.mapPath = ctx.bspPath;

    // The .srf and the BSP are read while the archives are listed, which leaves a core idle while
    // the thread pool starts and while the last archive is listed. A failure of the VFS is still
    // the one reported first.
    std::filesystem::path srfPath = ctx.bspPath;
    srfPath.replace_extension(".srf");
    struct MapFiles {
        SurfaceExtras extras;
        bsp::Bsp bsp;
    };
    std::future<MapFiles> mapFiles =
        std::async(ctx.threads == 1 ? std::launch::deferred : std::launch::async, [&ctx, &common, &srfPath] {
            MapFiles files;
            files.extras = loadSurfaceExtras(srfPath, ctx.options.sampleSize);
            files.bsp = bsp::readBsp(ctx.bspPath, bsp::ReadOptions{common.force, true});
            return files;
        });
    ctx.vfs = std::make_unique<Vfs>(vfsOptions, log);
    MapFiles files = mapFiles.get();
    ctx.extras = std::move(files.extras);
    if (!ctx.extras.loaded) log.info(strCat("no ", srfPath.string(), ": surfaces use default sample sizes"));
    ctx.bsp = std::move(files.bsp);
    ctx.entities = bsp::parseEntities(ctx.bsp.entities, ctx.bspPath.string());
    if (ctx.entities.empty()) throw CompileError(ctx.bspPath.string() + ": entities: no worldspawn entity");
    ctx.world = readWorldLighting(ctx.entities[0]);
    // The shader scripts and the .map source are read side by side (each about a third of the
    // load on the oacmp maps); the .map's line is logged after the shaders' messages, in the
    // order a sequential read gives.
    std::string mapLightsLine;
    tbb::task_arena(ctx.threads > 0 ? ctx.threads : tbb::task_arena::automatic).execute([&] {
        tbb::task_group group;
        if (!ctx.world.keepLights) group.run([&] { mapLightsLine = loadMapLights(ctx); });
        ctx.shaderTable = std::make_unique<ShaderTable>(loadShaderTable(*ctx.vfs, log));
        group.wait();
    });
    if (!mapLightsLine.empty()) log.info(mapLightsLine);

    ctx.shaders = resolveLightingShaders(ctx.bsp, *ctx.shaderTable, ctx.vfs.get(), log, ctx.threads);
    if (ctx.shaders.missingImages > 0)
        log.info(strCat(ctx.shaders.missingImages, " shaders without a light image"));
    ctx.scales = lightScalesFromOptions(ctx.options);
    ctx.color = colorOptionsFromOptions(ctx.options, ctx.world.maxLight);
}

void writeLitBsp(LightContext& ctx, Log& log) {
    // The stage may write more than once (-bounce stores between passes): record the command line once.
    std::vector<bsp::Entity> entities = ctx.entities;
    bsp::injectCommandLine(entities[0], ctx.commandLine);
    if (std::optional<DeluxeSettings> deluxe = deluxeSettings(ctx)) markDeluxeWorldspawn(entities[0], *deluxe);
    ctx.bsp.entities = bsp::unparseEntities(entities);
    bsp::writeBsp(ctx.bspPath, ctx.bsp);
    log.info(strCat("wrote ", ctx.bspPath.string()));
}

int runLightStage(const LightOptions& options, const CommonOptions& common, Log& log, RunStats* stats) {
    auto owned = std::make_unique<LightContext>();
    LightContext& ctx = *owned;
    ctx.options = options;
    PhaseTimer timer;
    auto phase = [&](const char* name) {
        log.info(strCat("--- ", name, " ---"));
        timer.begin(name);
    };

    phase("load");
    loadLightInputs(ctx, common, log);
    phase("scene");
    buildSurfaceGeometry(ctx);
    smoothNormals(ctx, log);
    buildBspQueries(ctx);
    // The lights come before the casters' scene, which needs the pieces only sun rays meet when
    // some light is a sun; their messages keep their place after the scene's.
    Log lightsLog;
    lightsLog.setVerbose(log.verbose());
    lightsLog.holdMessages();
    createLights(ctx, lightsLog);
    const bool sunRays = std::any_of(ctx.lights.begin(), ctx.lights.end(),
                                     [](const Light& l) { return l.type == LightType::Sun; });
    buildScene(ctx, sunRays);
    log.info(strCat(ctx.scene->casterCount(), " shadow-casting surfaces"));
    phase("lights");
    lightsLog.replayInto(log);
    ctx.luxelPasses = prepareLuxelPasses(ctx, log);
    // The grid's points are placed while the lightmaps are lit: the placement's serial search for
    // free nudges then leaves no core idle.
    std::future<GridPlacement> gridPlacement;
    if (!options.noGrid && ctx.threads != 1)
        gridPlacement = std::async(std::launch::async, [&ctx] { return placeLightGrid(ctx); });
    if (!options.noLightmaps) {
        phase("lightmaps");
        lightLightmaps(ctx, log);
    }
    phase("vertex light");
    lightVertexes(ctx, log);  // also from the radiosity emitters, ctx.bounceLights
    // The grids light from ctx.lights: with -bouncegrid it gains the radiosity emitters.
    if (options.bounceGrid)
        for (const std::vector<Light>& pass : ctx.bounceLights) ctx.lights.insert(ctx.lights.end(), pass.begin(), pass.end());
    // The SH grid (SetupGridSH / TraceGridSH) runs beside the legacy grid from the same light list.
    if (!options.noGrid) {
        phase("light grid");
        if (gridPlacement.valid()) {
            const GridPlacement placed = gridPlacement.get();
            lightGrid(ctx, log, &placed);
        } else {
            lightGrid(ctx, log);
        }
    }
    std::optional<GridDimensions> shGrid;
    if (options.sh && !options.noGrid) {
        phase("SH grid");  // SetupGridSH + TraceGridSH (grid_sh.h), stored as lump 18 or BSPX
        const ShTraceStats sh = lightGridSH(ctx, log);
        shGrid = GridDimensions{sh.bounds[0], sh.bounds[1], sh.bounds[2]};
    } else if (!options.noGrid) {
        removeGridSH(ctx.bsp);
    }
    attachWorldLights(ctx, log);  // after the SH grid, whose presence each record states
    phase("write");
    writeLitBsp(ctx, log);
    timer.end();

    log.info(strCat(ctx.stats.lightmaps, " raw lightmaps, ", ctx.stats.luxels, " luxels, ", ctx.stats.vertexes,
                    " vertexes, ", ctx.stats.gridPoints, " grid points, ",
                    ctx.scene ? ctx.scene->raysTraced() : 0, " rays traced"));
    if (ctx.stats.shGatherRays > 0)
        log.info(strCat("SH gather: ", ctx.stats.shGatherRays, " rays in ", ctx.stats.shGatherSeconds, " s, ",
                        uint64_t(double(ctx.stats.shGatherRays) / std::max(1e-9, ctx.stats.shGatherSeconds)),
                        " rays/s"));
    timer.printSummary(log);
    log.info(strCat(log.warningCount(), " warnings"));
    if (stats) {
        stats->recordPhases(timer);
        stats->raysTraced = ctx.scene ? ctx.scene->raysTraced() : 0;
        stats->luxels = ctx.stats.luxels;
        stats->counters["rawLightmaps"] = static_cast<int64_t>(ctx.stats.lightmaps);
        stats->counters["vertexes"] = static_cast<int64_t>(ctx.stats.vertexes);
        stats->counters["gridPointsInSolid"] = static_cast<int64_t>(ctx.stats.gridPointsInSolid);
        if (ctx.stats.shGatherRays > 0) stats->counters["shGatherRays"] = static_cast<int64_t>(ctx.stats.shGatherRays);
        if (!options.noGrid) {
            // The entity lump now holds the grid size the grid was built with.
            const bsp::Entity* worldspawn = ctx.entities.empty() ? nullptr : &ctx.entities.front();
            std::string size = worldspawn ? worldspawn->value("gridsize") : std::string();
            GridLayout layout = computeGridLayout(parseGridSize(size, ctx.bspPath.string()), ctx.bsp);
            stats->legacyGrid = GridDimensions{layout.bounds[0], layout.bounds[1], layout.bounds[2]};
        }
        stats->shGrid = shGrid;
    }
    // Freeing the context piece by piece (the shader table, the archives' listings, Embree's
    // scenes) takes milliseconds that the end of the process does at once.
    if (common.processEndsAfterStage) static_cast<void>(owned.release());
    return 0;
}

}  // namespace q3::light
