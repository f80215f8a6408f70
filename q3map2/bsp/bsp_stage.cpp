#include "bsp_stage.h"

#include <chrono>
#include <filesystem>
#include <set>

#include "bsp_compile.h"
#include "bspfile.h"
#include "fake_map.h"
#include "file_io.h"
#include "log.h"
#include "map_file.h"
#include "script.h"
#include "shader_info.h"
#include "shader_loader.h"
#include "vfs.h"

namespace q3::bspstage {
namespace {

namespace fs = std::filesystem;

std::vector<const ShaderInfo*> brushSideShaders(const LoadedMap& map) {
    std::set<const ShaderInfo*> seen;
    std::vector<const ShaderInfo*> out;
    for (const BspEntity& e : map.entities)
        for (const Brush& b : e.brushes)
            for (const BrushSide& s : b.sides)
                if (s.shader && seen.insert(s.shader).second) out.push_back(s.shader);
    return out;
}

// Shaders of brush sides and patches whose surfaces have flares.
std::vector<const ShaderInfo*> flareShaders(const LoadedMap& map, const ShaderTable& shaders) {
    std::set<const ShaderInfo*> seen;
    std::vector<const ShaderInfo*> out;
    auto add = [&](const ShaderInfo* s) {
        if (s && !s->flareShader.empty() && seen.insert(s).second) out.push_back(s);
    };
    for (const BspEntity& e : map.entities) {
        for (const Brush& b : e.brushes)
            for (const BrushSide& s : b.sides) add(s.shader);
        for (const PatchRef& p : e.patches) add(&shaders.find(map::shaderNameForTexture(p.patch->texture)));
    }
    return out;
}

// The stage's own arguments (after the stage switch) from the recorded command line.
std::vector<std::string> stageArguments(const std::string& commandLine) {
    std::vector<std::string> words;
    size_t pos = commandLine.find(' ');
    while (pos != std::string::npos) {
        const size_t next = commandLine.find(' ', pos + 1);
        std::string word = commandLine.substr(pos + 1, next == std::string::npos ? std::string::npos : next - pos - 1);
        if (!word.empty()) words.push_back(std::move(word));
        pos = next;
    }
    return words;
}

BspCompileOptions compileOptions(const BspOptions& o, const CommonOptions& common) {
    BspCompileOptions c;
    c.world.deep = o.deep;
    c.world.leakTest = o.leakTest;
    c.world.alternateSplit = o.alternateSplit;
    c.classify.sampleSize = o.sampleSize;
    c.classify.minSampleSize = o.minSampleSize;
    c.classify.maxSurfaceVerts = std::max(999, o.maxLightmappedVerts);
    c.emit.maxLightmappedVerts = o.maxLightmappedVerts;
    c.meta.meta = o.meta;
    c.celShader = o.celShader;
    c.meta.patchMeta = o.patchMeta;
    c.meta.maxArea = o.maxArea;
    c.meta.limits.maxLightmappedVerts = o.maxLightmappedVerts;
    c.meta.limits.maxSurfaceVerts = c.classify.maxSurfaceVerts;
    c.meta.limits.maxIndexes = o.maxIndexes;
    c.meta.limits.adequateScore = o.metaAdequateScore;
    c.meta.limits.goodScore = o.metaGoodScore;
    c.meta.limits.npDegrees = o.npDegrees;
    c.meta.limits.maxBBoxDistance = o.metaMaxBBoxDistance;
    c.emit.debugInset = o.debugInset;
    c.emit.debugSurfaces = o.debugSurfaces;
    c.clip = {o.clipDepth, o.debugClip, o.bevelSnap};
    c.brushSnap = !o.noBrushSnap;
    c.fog = !o.noFog;
    c.subdivide = !o.noSubdivide;
    c.tjunctions = !o.noTJunc;
    c.flares = o.flares;
    c.maxArea = o.maxArea;
    c.skyFix = o.skyFix;
    c.renameModelShaders = o.renameModelShaders;
    c.autocaulk = o.autocaulk;
    c.debugPortals = o.debugPortals;
    c.verboseEntities = o.verboseEntities;
    c.maxDrawSurfaces = std::abs(common.maxMapDrawSurfs);
    c.entities.keepLights = o.keepLights;
    c.entities.keepModels = o.keepModels;
    c.entities.version = bsp::kCompilerVersion;
    c.entities.stageArgs = stageArguments(common.commandLine);
    return c;
}

// -onlyents (q3map2 OnlyEnts): the existing BSP keeps every lump but its entities, which are read
// again from the map; worldspawn keeps the BSP's recorded command line, version and gridsize.
void replaceEntities(const fs::path& bspPath, const map::MapFile& file, const ShaderTable& shaders,
                     const BspOptions& options, const CommonOptions& common, Log& log) {
    log.info("--- OnlyEnts ---");
    bsp::Bsp bsp = bsp::readBsp(bspPath, bsp::ReadOptions{common.force, true});
    const std::vector<bsp::Entity> old = bsp::parseEntities(bsp.entities, bspPath.string());
    MapLoadOptions load;
    load.epsilons = {options.normalEpsilon, options.distanceEpsilon};
    load.resolveClones = false;
    load.decals = false;
    const LoadedMap map = loadMapForBsp(file, shaders, load, log);
    EntityLumpOptions entityOptions;
    entityOptions.keepLights = options.keepLights;
    entityOptions.keepModels = options.keepModels;
    entityOptions.recordCommandLine = false;
    std::vector<bsp::Entity> entities = bspEntities(map, entityOptions);
    if (!old.empty() && !entities.empty())
        for (const char* key : {"_q3map2_cmdline", "_q3map2_version", "gridsize"})
            if (const std::string* value = old.front().find(key); value && !value->empty()) entities.front().set(key, *value);
    bsp.entities = bsp::unparseEntities(entities);
    bsp::writeBsp(bspPath, bsp);
    log.info("Writing " + bspPath.string());
}

// A compile error names the map it stopped on; the steps' own messages name only what failed.
[[noreturn]] void rethrowNamingMap(const CompileError& e, const fs::path& map) {
    const std::string message = e.what();
    if (message.find(map.string()) != std::string::npos) throw e;
    throw CompileError(map.string() + ": " + message);
}

}  // namespace

int runBspStage(const BspOptions& options, const CommonOptions& common, Log& log, FeedbackStream* feedback) {
    const auto start = std::chrono::steady_clock::now();
    fs::path bspPath = common.mapPath;
    bspPath.replace_extension(".bsp");
    fs::path mapPath = bspPath;
    mapPath.replace_extension(".map");
    log.info("--- BSP ---");

    // q3map2 deletes the previous portal and leak files before anything else.
    std::error_code ignored;
    fs::remove(fs::path(bspPath).replace_extension(".prt"), ignored);
    fs::remove(fs::path(bspPath).replace_extension(".lin"), ignored);

    VfsOptions vfsOptions;
    vfsOptions.game = common.game;
    for (const std::string& p : common.basePaths) vfsOptions.basePaths.emplace_back(p);
    if (!common.fsGame.empty()) vfsOptions.gameDirs.push_back(common.fsGame);
    if (!common.homePath.empty()) vfsOptions.homePath = common.homePath;
    vfsOptions.baseGame = common.baseGame;
    vfsOptions.mapPath = bspPath;
    Vfs vfs(vfsOptions, log);
    const ShaderTable shaders = loadShaderTable(vfs, log);
    log.info(std::to_string(shaders.size()) + " shaderInfo");

    log.debug("--- LoadMapFile ---");
    fs::path source = options.tempName.empty() ? mapPath : fs::path(options.tempName);
    // A region (.reg) is compiled as named; -onlyents may take its entities from a .ent file.
    const std::string givenExtension = common.mapArgument.extension().string();
    if (options.tempName.empty() &&
        (equalsNoCase(givenExtension, ".reg") || (options.onlyEnts && equalsNoCase(givenExtension, ".ent"))))
        source = common.mapArgument;
    log.info("entering " + source.string());
    const map::MapFile file = map::loadMap(source);
    if (options.onlyEnts) {
        replaceEntities(bspPath, file, shaders, options, common, log);
        return 0;
    }
    MapLoadOptions load;
    load.epsilons = {options.normalEpsilon, options.distanceEpsilon};
    load.noDetail = options.noDetail;
    load.fullDetail = options.fullDetail;
    load.noWater = options.noWater;
    load.noHint = options.noHint;
    load.noCurves = options.noCurves;
    load.flagRules = options.flagRules;
    load.bevelSnap = options.bevelSnap;
    load.keepGroups = options.autocaulk;
    load.feedback = feedback;
    LoadedMap map = loadMapForBsp(file, shaders, load, log);
    log.debug(std::to_string(map.counts.worldBrushes) + " total world brushes");
    log.debug(std::to_string(map.counts.detailBrushes) + " detail brushes");
    log.debug(std::to_string(map.counts.patches) + " patches");
    log.info(std::to_string(map.counts.areaportals) + " areaportals");
    if (options.fakeMap) {
        // q3map2 writes it where it runs, whatever the map's folder.
        log.info("Writing fakemap.map");
        writeFileAtomic("fakemap.map", fakeMapText(map.entities.front().brushes, map.planes));
    }

    const TextureSizes textures = TextureSizes::load(brushSideShaders(map), vfs, log);
    FlareColors flareColors;
    if (options.flares) flareColors = FlareColors::load(flareShaders(map, shaders), &vfs, log);
    CompiledBsp compiled;
    try {
        BspCompileOptions compile = compileOptions(options, common);
        compile.world.feedback = feedback;
        compiled = compileBsp({map, file, shaders, textures, &vfs, &flareColors}, compile, log);
    } catch (const CompileError& e) {
        rethrowNamingMap(e, source);
    }

    if (compiled.stoppedForAutocaulk) {
        // q3map2 stops before the portal file: only a leak line, if any, and the .caulk.
        WorldStructure leakOnly;
        leakOnly.leaked = true;
        leakOnly.leakLine = compiled.world.leakLine;
        writeWorldStructureFiles(leakOnly, bspPath);
        const fs::path caulkPath = fs::path(bspPath).replace_extension(".caulk");
        log.info("writing " + caulkPath.string());
        writeFileAtomic(caulkPath, compiled.autocaulk);
        return 0;
    }
    writeWorldStructureFiles(compiled.world, bspPath);
    if (compiled.stoppedForLeakTest) return 0;
    fs::path srfPath = bspPath;
    srfPath.replace_extension(".srf");
    log.info("Writing " + srfPath.string());
    writeFileAtomic(srfPath, compiled.surfaceExtra);
    log.info("Writing " + bspPath.string());
    bsp::writeBsp(bspPath, compiled.bsp);
    if (!options.tempName.empty()) fs::remove(options.tempName, ignored);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    log.info(std::to_string(int(seconds)) + " seconds elapsed");
    return 0;
}

}  // namespace q3::bspstage
