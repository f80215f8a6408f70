#include "bsp_compile.h"

#include <cstdio>
#include <cstring>
#include <memory>

#include "autocaulk.h"
#include "brush_filter.h"
#include "count_line.h"
#include "debug_portals.h"
#include "decals/decals.h"
#include "face_subdivide.h"
#include "fog_hull.h"
#include "fog_volumes.h"
#include "index_map.h"
#include "log.h"
#include "max_area_triangles.h"
#include "model_surfaces.h"
#include "skybox.h"
#include "patch_surfaces.h"
#include "script.h"
#include "shader_info.h"
#include "shaping/finish_surfaces.h"
#include "shaping/foliage.h"
#include "srf_writer.h"
#include "structure_emit.h"
#include "surface_filter.h"
#include "surface_triangles.h"
#include "terrain_shaders.h"
#include "tjunctions.h"
#include "visible_hull.h"

namespace q3::bspstage {
namespace {


struct ModelContext {
    const CompileInputs& in;
    const BspCompileOptions& options;
    const FaceContext& faces;
    const std::vector<EntitySurfaceParams>& params;
    const MapFogs& fogs;
    BspBuilder& builder;
    std::vector<int>& brushOutputs;
    std::vector<std::unique_ptr<DrawSurface>>& written;  // every written surface, in BSP order
    LibcRandom& random;  // -maxarea retries, drawn in surface order
    const std::vector<DecalProjector>& decals;
    const ModelInputs& models;  // misc_models, and the models q3map_foliage places
    Log& log;
    int mapSurfacesBefore = 0;  // draw surfaces of the models already written (q3map2 numbers them on)
};

// q3map_remapShader: the BSP names a shader by its remap, keeping the original shader's flags (q3map2
// renames the entries as it writes the file).
void remapShaderNames(bsp::Bsp& bsp, const ShaderTable& shaders) {
    for (bsp::Shader& s : bsp.shaders) {
        const ShaderInfo& si = shaders.find(std::string(s.name, strnlen(s.name, sizeof s.name)));
        if (si.remapShader.empty()) continue;
        std::memset(s.name, 0, sizeof s.name);
        std::strncpy(s.name, si.remapShader.c_str(), sizeof s.name - 1);
    }
}

void debugCounts(Log& log, std::initializer_list<std::pair<int, const char*>> counts) {
    for (const auto& [value, what] : counts) log.debug(countLine(value, what));
}

// -meta and forced-meta shaders (q3map2 MakeEntityMetaTriangles ... MergeMetaTriangles), and the
// collision patches -patchmeta leaves.
void makeMeta(ModelContext& c, const BspEntity& entity, std::vector<DrawSurface>& surfaces) {
    const meta::MetaInputs inputs{*entity.source, c.in.map.planes, c.faces.textures, c.options.classify, c.random,
                                  &c.in.shaders};
    const meta::MetaCounts m = meta::makeMetaSurfaces(surfaces, inputs, c.options.meta, c.log);
    if (m.metaSurfaces > 0 || m.patchMeta > 0) {
        c.log.debug("--- MakeEntityMetaTriangles ---");
        debugCounts(c.log, {{m.metaSurfaces, "total meta surfaces"}, {m.stripped, "stripped surfaces"},
                            {m.fanned, "fanned surfaces"}, {m.maxArea, "maxarea'd surfaces"},
                            {m.patchMeta, "patch meta surfaces"}, {m.metaVerts, "meta verts"},
                            {m.metaTriangles, "meta triangles"}});
        c.log.debug("--- SmoothMetaTriangles ---");
        c.log.debug(countLine(m.smoothed, "smoothed vertexes"));
        c.log.debug("--- MergeMetaTriangles ---");
        debugCounts(c.log, {{m.merged.surfaces, "surfaces merged"}, {m.merged.mergedVerts, "vertexes merged"}});
    }
    meta::markPatchCollision(surfaces, *entity.source, c.options.meta);
}

// The steps both kinds of model share once their faces exist: tessellation, classification,
// filtering into the tree and writing (q3map2 SubdivideFaceSurfaces ... FilterDrawsurfsIntoTree,
// FixBrushSides, EndModel).
void finishModel(ModelContext& c, size_t entityIndex, std::vector<DrawSurface>& surfaces, Tree& tree) {
    const BspEntity& entity = c.in.map.entities[entityIndex];
    if (c.options.subdivide) subdivideFaceSurfaces(surfaces, entity, c.faces, c.params);
    if (c.options.tjunctions) {
        c.log.debug("--- FixTJunctions ---");
        const TJunctionCounts t = fixTJunctions(surfaces);
        debugCounts(c.log, {{t.axialLines, "axial edge lines"}, {t.nonAxialLines, "non-axial edge lines"},
                            {t.degenerateEdges, "degenerate edges"}, {t.addedVerts, "verts added for T-junctions"},
                            {t.totalVerts, "total verts"}, {t.natural, "naturally ordered"},
                            {t.rotated, "rotated orders"}, {t.cantOrder, "can't order"},
                            {t.broken, "broken (degenerate) surfaces removed"}});
    }
    c.log.debug("--- ClassifyEntitySurfaces ---");
    finishSurfaces(surfaces, {c.in.file, c.in.shaders, c.options.celShader, c.options.maxDrawSurfaces});
    for (DrawSurface& ds : surfaces) classifySurface(ds, c.in.map.planes, c.options.classify);
    c.log.debug(countLine(tidySurfaces(surfaces), "empty or malformed surfaces deleted"));
    if (!c.decals.empty()) {
        c.log.debug("--- MakeEntityDecals ---");
        const int made = makeEntityDecals({c.decals, c.in.map.planes, entity.origin, c.options.meta.patchSubdivisions},
                                          surfaces);
        c.log.debug(countLine(made, "decal surfaces"));
    }
    makeMeta(c, entity, surfaces);
    if (c.options.debugPortals && entityIndex == 0) {
        c.log.debug("--- MakeDebugPortalSurfs ---");
        for (DrawSurface& ds : debugPortalSurfaces(tree, c.in.map.planes, c.in.shaders)) surfaces.push_back(std::move(ds));
    }
    if (entityIndex == 0)
        if (std::optional<DrawSurface> hull =
                fogHullSurface(entity.source->value("_foghull"), c.in.map.worldBounds, c.in.shaders))
            surfaces.push_back(std::move(*hull));
    if (c.options.flares && entityIndex == 0)
        for (DrawSurface& f : lightFlares(c.in.file, c.in.shaders)) surfaces.push_back(std::move(f));
    if (int(c.written.size() + surfaces.size()) > c.options.maxDrawSurfaces)
        throw CompileError("max_map_draw_surfs (" + std::to_string(c.options.maxDrawSurfaces) +
                           ") exceeded, consider -maxmapdrawsurfs to increase");

    c.log.debug("--- FilterDrawsurfsIntoTree ---");
    TriangulationCounts triangles;
    int references = 0, emitted = 0;
    const FlareColors noColors;
    // Surface flares and _skybox copies are appended while the list is walked, and filtered after
    // the others; a copy skips what its original went through before filtering.
    const std::optional<ModelTransform> skybox = entityIndex == 0 ? skyboxTransform(c.in.map.entities) : std::nullopt;
    const std::vector<const Brush*> volumes = colorModVolumes(entity);
    for (size_t i = 0; i < surfaces.size(); ++i) {
        const bool shaderOnly = surfaces[i].kind == SurfaceKind::Shader;
        const bool isSkyCopy = surfaces[i].skyboxCopy;
        if (surfaces[i].verts.empty() && surfaces[i].kind != SurfaceKind::Flare && !shaderOnly) continue;
        if (!isSkyCopy) {
            applyTcMod(surfaces[i]);
            applyColorMods(surfaces[i]);
            applyVolumeColorMods(surfaces[i], volumes, c.in.map.planes);
            FoliageInputs foliage{c.models, c.in.map, c.random, entity.mapEntityNum};
            std::vector<DrawSurface> scattered;
            addFoliage(surfaces[i], foliage, scattered, c.log);
            for (DrawSurface& f : scattered) surfaces.push_back(std::move(f));
        }
        if (c.options.flares && !isSkyCopy)
            if (std::optional<DrawSurface> f = surfaceFlare(surfaces[i], entity.origin, c.in.shaders,
                                                            c.in.flareColors ? *c.in.flareColors : noColors))
                surfaces.push_back(std::move(*f));
        DrawSurface& ds = surfaces[i];
        if (!isSkyCopy) {
            if (ds.shader->isNoDraw() && ds.kind != SurfaceKind::Patch) continue;
            biasSurfaceTextures(ds);
            if (entityIndex != 0 && !ds.shader->noFog && ds.kind != SurfaceKind::Flare && !shaderOnly) {
                DBounds bounds;
                for (const bsp::DrawVert& v : ds.verts) bounds.add(DVec3(Vec3::fromArray(v.xyz)) + entity.origin);
                ds.fogNum = fogForBounds(bounds, c.fogs, c.in.map, 1.0);
            }
        }
        // A shader-only surface is written without being referenced by any leaf; a sky copy goes to
        // the leaves that draw sky, or where it lies when there are none.
        int refs = isSkyCopy ? addSkyboxReferences(ds, tree, c.builder.nextSurface()) : 0;
        if (refs == 0) refs = shaderOnly ? 1 : filterSurfaceIntoTree(ds, tree, c.in.map.planes, c.builder.nextSurface());
        if (refs == 0) continue;
        if (ds.kind == SurfaceKind::Face || ds.kind == SurfaceKind::Decal) {
            if (c.options.maxArea)
                triangulateFaceByMaxArea(ds, c.random, &triangles);
            else
                triangulateFace(ds, &triangles);
            classifySurface(ds, c.in.map.planes, c.options.classify);
        }
        c.builder.emitSurface(ds, c.options.emit, c.mapSurfacesBefore + int(i));
        for (const std::string& w : c.builder.takeWarnings()) c.log.warning(w);
        references += refs;
        ++emitted;
        c.written.push_back(std::make_unique<DrawSurface>(ds));
        if (ds.skybox && !isSkyCopy && skybox) surfaces.push_back(skyboxCopy(ds, *skybox));
    }
    c.log.debug(countLine(references, "references"));
    c.log.debug(countLine(emitted, "emitted drawsurfs"));
    c.log.debug(countLine(triangles.strips, "stripped face surfaces"));
    c.log.debug(countLine(triangles.fans, "fanned face surfaces"));
    if (c.options.maxArea) c.log.debug(countLine(triangles.maxArea, "maxarea'd face surfaces"));
    c.builder.fixBrushSides(surfaces);
    c.builder.endModel(tree);
    c.mapSurfacesBefore += int(surfaces.size());
}

}  // namespace

CompiledBsp compileBsp(const CompileInputs& in, const BspCompileOptions& options, Log& log) {
    CompiledBsp out;
    LoadedMap& map = in.map;
    // q3map2 would write a BSP without a world model, which no engine loads.
    if (map.entities.front().brushes.empty() && map.entities.front().patches.empty())
        throw CompileError(in.file.name + ": the world has no brushes or patches, nothing to compile");
    std::vector<EntitySurfaceParams> params = entitySurfaceParams(in.file);
    const std::vector<std::unique_ptr<IndexMap>> indexMaps = loadIndexMaps(in.file, map, in.vfs, log);
    for (size_t i = 0; i < indexMaps.size() && i < params.size(); ++i) params[i].indexMap = indexMaps[i].get();
    // Layer shaders of index-mapped terrain are found while faces are made; their sizes join these.
    TextureSizes textures = in.textures;
    TerrainShaders terrain(in.shaders, textures, in.vfs, map, log);
    std::vector<std::unique_ptr<DrawSurface>> written;
    const FaceContext faces{map.planes, textures, options.brushSnap, options.skyFix ? &in.shaders : nullptr,
                            &written, &terrain};
    BspBuilder builder(map, in.shaders);
    MapFogs fogs;
    if (options.fog) {
        log.debug("--- CreateMapFogs ---");
        fogs = createMapFogs(map, in.shaders, log);
    }
    std::vector<int> brushOutputs(map.entities.size(), -1);
    LibcRandom random;
    const std::vector<DecalProjector> decals =
        makeDecalProjectors(map, in.shaders, options.meta.patchSubdivisions, log);
    const ModelInputs modelInputs{in.file, in.shaders, in.vfs, options.renameModelShaders,
                                  options.classify.maxSurfaceVerts, options.clip};
    ModelContext c{in, options, faces, params, fogs, builder, brushOutputs, written, random, decals, modelInputs, log};

    for (size_t i = 0; i < map.entities.size(); ++i) {
        BspEntity& e = map.entities[i];
        if (e.brushes.empty() && e.patches.empty()) continue;
        log.debug("############### model " + std::to_string(builder.bsp().models.size()) + " ###############");
        builder.beginModel(e);
        PatchCounts patchCounts;
        std::vector<DrawSurface> surfaces = patchSurfaces(e, in.shaders, map.planes, params, log, &patchCounts, &terrain);
        log.debug(countLine(patchCounts.patches, "patches"));
        log.debug(countLine(patchCounts.lodGroups, "patch LOD groups"));
        if (i == 0) {
            // With -debugclip q3map2 adds the world's models before building its tree, so that the
            // clip brushes' sides are clipped into it and drawn like brush faces.
            const bool modelsFirst = options.clip.debugClip;
            if (modelsFirst) {
                std::vector<Brush> clip;
                addModelSurfaces(e, true, map, modelInputs, surfaces, clip, log);
                Tree noTreeYet;
                prependClipBrushes(e, std::move(clip), surfaces, noTreeYet);
            }
            out.world = buildWorldStructure(map, options.world, log);
            if (out.world.stoppedForLeakTest) {
                out.stoppedForLeakTest = true;
                return out;
            }
            // Without an entity in open space q3map2 never clips the sides: the world has no faces.
            if (options.autocaulk && out.world.flood != FloodResult::Empty) {
                out.autocaulk = autocaulkText(e.brushes, in.shaders);
                out.stoppedForAutocaulk = true;
                return out;
            }
            if (out.world.flood != FloodResult::Empty) {
                const CullCounts culled = cullSides(e.brushes, map.planes);
                log.debug(countLine(culled.hidden, "hidden faces culled"));
                log.debug(countLine(culled.coincident, "coincident faces culled"));
                addFaceSurfaces(e, faces, params, surfaces);
            }
            if (!modelsFirst) {
                std::vector<Brush> clip;
                addModelSurfaces(e, true, map, modelInputs, surfaces, clip, log);
                prependClipBrushes(e, std::move(clip), surfaces, out.world.tree);
            }
            builder.emitBrushes(e.brushes);
            brushOutputs[i] = builder.brushOutput(0);
            filterDetailBrushesIntoTree(e.brushes, out.world.tree, map.planes);
            if (options.fog) {
                const FogCounts fogged = fogWorldSurfaces(surfaces, fogs, map, faces, params);
                log.debug(countLine(fogged.faceFragments, "fog polygon fragments"));
                log.debug(countLine(fogged.patchFragments, "fog patch fragments"));
                log.debug(countLine(fogged.fogged, "fogged drawsurfs"));
            }
            finishModel(c, i, surfaces, out.world.tree);
        } else {
            const bool verbose = log.verbose();
            if (!options.verboseEntities) log.setVerbose(false);
            Tree tree = singleLeafTree(e);
            cullSides(e.brushes, map.planes);
            clipSidesIntoTree(e.brushes, tree, map.planes);
            addFaceSurfaces(e, faces, params, surfaces);
            std::vector<Brush> clip;
            addModelSurfaces(e, false, map, modelInputs, surfaces, clip, log);
            prependClipBrushes(e, std::move(clip), surfaces, tree);
            builder.emitBrushes(e.brushes);
            brushOutputs[i] = builder.brushOutput(0);
            finishModel(c, i, surfaces, tree);
            log.setVerbose(verbose);
        }
    }
    log.debug(countLine(int(builder.bsp().models.size()), "bspModels in total"));
    emitFogs(fogs, map, brushOutputs, builder, log);
    builder.emitPlanes(map.planes);
    remapShaderNames(builder.bsp(), in.shaders);
    builder.bsp().entities = bsp::unparseEntities(bspEntities(map, options.entities));

    std::vector<const DrawSurface*> order;
    for (const auto& ds : written) order.push_back(ds.get());
    out.surfaceExtra = surfaceExtraText(order, options.classify.sampleSize, map, params);
    out.bsp = std::move(builder.bsp());
    return out;
}

}  // namespace q3::bspstage
