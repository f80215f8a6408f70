#include "bsp_options.h"

#include <algorithm>

namespace q3::bspstage {
namespace {

using cli::ArgKind;
using cli::ArgValue;
using cli::kImplemented;
using cli::kNotImplemented;
using cli::Range;
using O = BspOptions;

// An option q3map2 has that this build refuses: parsed for its arguments, never applied.
cli::Option<O> refused(std::vector<std::string> names, std::vector<cli::ArgSpec> args, std::string help) {
    const int required = int(args.size());
    return cli::custom<O>(std::move(names), std::move(args), required, "off", std::move(help), kNotImplemented,
                          [](O&, std::span<const ArgValue>) {});
}

cli::Option<O> clampedInt(std::vector<std::string> names, int O::*member, int atLeast, std::string help) {
    return cli::custom<O>(std::move(names), {{ArgKind::Int, "N", Range::any()}}, 1, std::to_string(O{}.*member),
                          std::move(help), kImplemented, [member, atLeast](O& o, std::span<const ArgValue> v) {
                              o.*member = std::max(atLeast, int(v[0].number));
                          });
}

cli::ArgSpec intArg() { return {ArgKind::Int, "N", Range::any()}; }
cli::ArgSpec floatArg() { return {ArgKind::Float, "F", Range::any()}; }
cli::ArgSpec textArg(const char* name) { return {ArgKind::Text, name, Range::any()}; }

cli::OptionTable<O> buildTable() {
    using cli::flag;
    cli::OptionTable<O> t;
    t.push_back(flag<O>({"-onlyents"}, &O::onlyEnts,
                        "Only update entities in the BSP (from the .map, or from a .ent file given instead)",
                        kImplemented));
    t.push_back(cli::textValue<O>({"-tempname"}, &O::tempName,
                                  "Read the MAP file from the given file name (deleted after the compile)", kImplemented,
                                  "filename.map", "none"));
    t.push_back(flag<O>({"-nowater"}, &O::noWater, "Disable water, slime, lava brushes", kImplemented));
    t.push_back(flag<O>({"-keeplights"}, &O::keepLights,
                        "Keep light entities in the BSP file after compile (also writes worldspawn _keepLights 1)",
                        kImplemented));
    t.push_back(flag<O>({"-keepmodels"}, &O::keepModels,
                        "Keep misc_model entities in the BSP file after compile (also writes worldspawn _keepModels 1)",
                        kImplemented));
    t.push_back(flag<O>({"-nodetail"}, &O::noDetail, "Skip detail brushes", kImplemented));
    t.push_back(flag<O>({"-fulldetail"}, &O::fullDetail, "Detail brushes act as structural brushes", kImplemented));
    t.push_back(flag<O>({"-nofog"}, &O::noFog, "Skip creating fog volumes and fogging surfaces", kImplemented));
    t.push_back(flag<O>({"-nosubdivide"}, &O::noSubdivide, "Do not cut faces of shaders with tessSize", kImplemented));
    t.push_back(flag<O>({"-leaktest"}, &O::leakTest, "Abort if a leak is found (after writing the .lin)",
                        kImplemented));
    t.push_back(flag<O>({"-verboseentities"}, &O::verboseEntities, "Keep verbose output for brush entities too",
                        kImplemented));
    t.push_back(flag<O>({"-nocurves"}, &O::noCurves, "Turn off support for patches", kImplemented));
    t.push_back(flag<O>({"-notjunc"}, &O::noTJunc, "Do not fix T-junctions", kImplemented));
    t.push_back(flag<O>({"-fakemap"}, &O::fakeMap,
                        "Write fakemap.map (in the current directory) with all world brushes, bevels included",
                        kImplemented));
    t.push_back(clampedInt({"-samplesize"}, &O::sampleSize, 1, "Default lightmap sample size (at least 1)"));
    t.push_back(clampedInt({"-minsamplesize"}, &O::minSampleSize, 1, "Smallest lightmap sample size (at least 1)"));
    t.push_back(refused({"-custinfoparms"}, {}, "Read scripts/custinfoparms.txt"));
    t.push_back(flag<O>({"-rename"}, &O::renameModelShaders,
                        "Append _BSP (_RMG_BSP with spawnflag 1) to misc_model shader names (SoF2)", kImplemented));
    t.push_back(cli::floatValue<O>({"-ne"}, &O::normalEpsilon, Range::any(), "Normal epsilon for plane snapping",
                                   kImplemented));
    t.push_back(cli::floatValue<O>({"-de"}, &O::distanceEpsilon, Range::any(), "Distance epsilon for plane snapping",
                                   kImplemented));
    t.push_back(clampedInt({"-mv"}, &O::maxLightmappedVerts, 3,
                           "Most vertices of a lightmapped surface; larger ones become triangle soup (at least 3)"));
    t.push_back(clampedInt({"-mi"}, &O::maxIndexes, 3, "Most indexes of a meta surface (at least 3)"));
    t.push_back(cli::custom<O>({"-np"}, {floatArg()}, 1, "0",
                               "Smooth meta triangle normals with this shade angle and let meta surfaces leave "
                               "their plane",
                               kImplemented, [](O& o, std::span<const ArgValue> v) {
                                   o.npDegrees = std::max(0.0f, float(v[0].number));
                               }));
    t.push_back(clampedInt({"-snap"}, &O::bevelSnap, 0, "Snap added axial bevel planes inwards to multiples of N"));
    t.push_back(flag<O>({"-nobrushsnap"}, &O::noBrushSnap, "Do not round brush face vertices to 1/8 unit",
                        kImplemented));
    t.push_back(flag<O>({"-nohint"}, &O::noHint, "Disable hint brushes", kImplemented));
    t.push_back(refused({"-flat"}, {}, "Flat shading: one texture coordinate per shader"));
    t.push_back(cli::custom<O>({"-celshader"}, {textArg("shader")}, 1, "none",
                               "Cel shade every surface with this shader (textures/ is put in front)", kImplemented,
                               [](O& o, std::span<const ArgValue> v) { o.celShader = "textures/" + v[0].text; }));
    t.push_back(flag<O>({"-meta"}, &O::meta, "Combine brush faces into meta triangle surfaces", kImplemented));
    t.push_back(cli::custom<O>({"-metaadequatescore"}, {intArg()}, 1, "110000",
                               "Adequate score for adding triangles to meta surfaces (negative: the default)",
                               kImplemented, [](O& o, std::span<const ArgValue> v) {
                                   o.metaAdequateScore = std::max(-1, int(v[0].number));
                               }));
    t.push_back(cli::custom<O>({"-metagoodscore"}, {intArg()}, 1, "120200",
                               "Good score for adding triangles to meta surfaces (negative: the default)",
                               kImplemented, [](O& o, std::span<const ArgValue> v) {
                                   o.metaGoodScore = std::max(-1, int(v[0].number));
                               }));
    t.push_back(cli::custom<O>({"-metamaxbboxdistance"}, {floatArg()}, 1, "off",
                               "A triangle joins a meta surface only with a corner this close to its bounds "
                               "(negative: off)",
                               kImplemented, [](O& o, std::span<const ArgValue> v) {
                                   o.metaMaxBBoxDistance = v[0].number < 0 ? -1.0f : float(v[0].number);
                               }));
    t.push_back(flag<O>({"-patchmeta"}, &O::patchMeta,
                        "Turn patches into triangle meta surfaces (the patch stays, nodraw, for collision)",
                        kImplemented));
    t.push_back(flag<O>({"-flares"}, &O::flares,
                        "Emit flare surfaces (q3map_flare shaders, light entities with _flare or _flareshader)",
                        kImplemented));
    t.push_back(flag<O>({"-noflares"}, &O::flares, "Do not emit flare surfaces (the quake3 default)", kImplemented,
                        false));
    t.push_back(flag<O>({"-skyfix"}, &O::skyFix,
                        "Add shader-only surfaces for the six sky box images (GL_CLAMP border workaround)",
                        kImplemented));
    t.push_back(flag<O>({"-debugsurfaces"}, &O::debugSurfaces,
                        "Colour the vertices of each surface by its number (shader debugsurfaces)", kImplemented));
    t.push_back(flag<O>({"-debuginset"}, &O::debugInset, "Push triangle vertices one unit to the triangle centre",
                        kImplemented));
    t.push_back(flag<O>({"-debugportals"}, &O::debugPortals,
                        "Make surfaces (shader debugportals) of the world tree's passable portals", kImplemented));
    t.push_back(flag<O>({"-debugclip"}, &O::debugClip,
                        "Make misc_model autoclip brushes visible (shaders debugclip2 and debugclip)", kImplemented));
    t.push_back(cli::floatValue<O>({"-clipdepth"}, &O::clipDepth, Range::any(),
                                   "Thickness of misc_model autoclip brushes (misc_model _clipdepth overrides it)",
                                   kImplemented));
    for (const char* colour : {"-sRGBtex", "-nosRGBtex", "-sRGBcolor", "-nosRGBcolor", "-nosRGB"})
        t.push_back(refused({colour}, {}, "Colour space of textures and colours (they only change flare colours)"));
    t.push_back(flag<O>({"-altsplit"}, &O::alternateSplit, "Alternative split plane score", kImplemented));
    t.push_back(flag<O>({"-deep"}, &O::deep, "Detail faces split the tree too (at the lowest priority)",
                        kImplemented));
    t.push_back(flag<O>({"-maxarea"}, &O::maxArea, "Triangulate faces by largest area instead of strips",
                        kImplemented));
    t.push_back(cli::custom<O>({"-noob"}, {}, 0, "off", "Add the noob surface flag to every shader without surfaceparm ob",
                               kImplemented, [](O& o, std::span<const ArgValue>) { o.flagRules.noOb = true; }));
    t.push_back(cli::custom<O>({"-globalflag"}, {textArg("surfaceparm")}, 1, "none",
                               "Add a surfaceparm's surface flags to every shader (repeatable)", kImplemented,
                               [](O& o, std::span<const ArgValue> v) {
                                   if (!o.flagRules.addGlobalFlag(v[0].text))
                                       throw cli::UsageError("-globalflag: '" + v[0].text + "' is not a surfaceparm");
                               }));
    t.push_back(flag<O>({"-autocaulk"}, &O::autocaulk,
                        "Only write <map>.caulk (what each world brush side could become) for the editor", kImplemented));
    t.push_back(refused({"-texrange"}, {intArg()},
                        "Limit the texture range of meta surfaces (older q3map2; 2.5.17n has no such limit)"));
    return t;
}

}  // namespace

const cli::OptionTable<BspOptions>& bspOptionTable() {
    static const cli::OptionTable<BspOptions> table = buildTable();
    return table;
}

}  // namespace q3::bspstage
