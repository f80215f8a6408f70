// The -bsp pipeline after loading (q3map2 bsp.cpp ProcessModels, ProcessWorldModel,
// ProcessSubModel): the world gets its tree, portals and areas; every model gets its patch and face
// surfaces, fog, tessellation, classification, filtering into its leaves and the written lumps.
#pragma once

#include <string>

#include "bsp_builder.h"
#include "entity_lump.h"
#include "face_surfaces.h"
#include "flares.h"
#include "meta/meta_surfaces.h"
#include "surface_classify.h"
#include "model_clip.h"
#include "world_structure.h"

namespace q3 {
class Log;
class ShaderTable;
class Vfs;
}  // namespace q3

namespace q3::bspstage {

struct BspCompileOptions {
    WorldStructureOptions world;
    ClassifyOptions classify;
    SurfaceEmitOptions emit;
    EntityLumpOptions entities;
    bool brushSnap = true;      // off with -nobrushsnap
    bool fog = true;            // off with -nofog
    bool subdivide = true;      // off with -nosubdivide: tessSize ignored
    bool tjunctions = true;     // off with -notjunc
    bool flares = false;        // -flares
    bool maxArea = false;       // -maxarea: faces triangulated by largest area instead of strips
    bool skyFix = false;        // -skyfix: shader-only surfaces for the sky box images
    bool renameModelShaders = false;  // -rename: misc_model shaders get _BSP / _RMG_BSP
    bool autocaulk = false;     // -autocaulk: stop after the world's visible hulls with the .caulk text
    bool debugPortals = false;  // -debugportals: a face for every passable portal of the world tree
    meta::MetaOptions meta;     // -meta, -patchmeta and their limits
    std::string celShader;      // -celshader, "textures/" in front; empty: none
    bool verboseEntities = false;  // -verboseentities: keep -v output for brush models
    int maxDrawSurfaces = 0x20000;  // -maxmapdrawsurfs
    ClipOptions clip;               // -clipdepth, -debugclip, -snap for misc_model clip brushes
};

struct CompiledBsp {
    bsp::Bsp bsp;
    WorldStructure world;     // .prt or .lin text
    std::string surfaceExtra;  // .srf text
    bool stoppedForLeakTest = false;  // -leaktest on a leaking map: nothing else to write
    bool stoppedForAutocaulk = false;  // -autocaulk: only the .caulk (and a .lin) to write
    std::string autocaulk;             // .caulk text
};

struct CompileInputs {
    LoadedMap& map;
    const map::MapFile& file;
    const ShaderTable& shaders;
    const TextureSizes& textures;
    const Vfs* vfs = nullptr;  // misc_model files; nullptr: models are skipped with a warning
    const FlareColors* flareColors = nullptr;  // with -flares: the colour of surface flares (white without)
};

CompiledBsp compileBsp(const CompileInputs& inputs, const BspCompileOptions& options, Log& log);

}  // namespace q3::bspstage
