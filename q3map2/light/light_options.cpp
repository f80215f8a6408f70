#include "light_options.h"

#include <charconv>
#include <string>

namespace q3::light {

namespace {

using cli::ArgKind;
using cli::ArgSpec;
using cli::ArgValue;
using cli::kImplemented;
using cli::kNotImplemented;
using cli::Range;
using O = LightOptions;
using Values = std::span<const ArgValue>;

bool isPowerOfTwo(int v) { return v > 0 && (v & (v - 1)) == 0; }

// -lightmapsize / -extlmhacksize: N [N], each a power of two.
void storePageSize(const char* option, int& width, int& height, Values v) {
    for (const ArgValue& value : v)
        if (!isPowerOfTwo(static_cast<int>(value.number)))
            throw cli::UsageError(std::string(option) + ": " + value.text + " is not a power of two");
    width = static_cast<int>(v[0].number);
    height = v.size() > 1 ? static_cast<int>(v[1].number) : width;
}

// -samples N or +N (the + keeps N even when -randomsamples would pick its own count).
void storeSamples(O& o, Values v) {
    std::string text = v[0].text;
    bool insist = !text.empty() && text[0] == '+';
    std::string digits = insist ? text.substr(1) : text;
    int n = 0;
    auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), n);
    if (digits.empty() || ec != std::errc() || end != digits.data() + digits.size())
        throw cli::UsageError("-samples: '" + text + "' is not an integer (-samples <N|+N>)");
    if (n < 1 || n > 16) throw cli::UsageError("-samples: " + text + " is out of range (must be between 1 and 16)");
    o.lightSamples = n;
    o.lightSamplesInsist = insist;
}

void setColourSpaces(O& o, bool lightmaps, bool textures, bool colors, bool value) {
    if (lightmaps) o.lightmapsRGB = value;
    if (textures) o.texturesRGB = value;
    if (colors) o.colorsRGB = value;
}

cli::OptionTable<O> buildLightTable() {
    cli::OptionTable<O> t;
    auto flag = [&t](std::vector<std::string> names, bool O::*m, std::string help, bool impl, bool value = true) {
        t.push_back(cli::flag<O>(std::move(names), m, std::move(help), impl, value));
    };
    auto real = [&t](std::vector<std::string> names, float O::*m, Range r, std::string help, bool impl) {
        t.push_back(cli::floatValue<O>(std::move(names), m, r, std::move(help), impl));
    };
    auto integer = [&t](std::vector<std::string> names, int O::*m, Range r, std::string help, bool impl) {
        t.push_back(cli::intValue<O>(std::move(names), m, r, std::move(help), impl));
    };
    auto action = [&t](std::vector<std::string> names, std::vector<ArgSpec> args, int required, std::string def,
                       std::string help, bool impl, std::function<void(O&, Values)> apply) {
        t.push_back(cli::custom<O>(std::move(names), std::move(args), required, std::move(def), std::move(help), impl,
                                   std::move(apply)));
    };
    const O defaults;
    const ArgSpec scaleArg{ArgKind::Float, "F", Range::atLeast(0)};

    integer({"-approx"}, &O::approximateTolerance, Range::between(0, 255),
            "Replace a lightmap by vertex light when it is within N byte values of it", kNotImplemented);
    real({"-areascale", "-area"}, &O::areaScale, Range::atLeast(0), "Scale of area lights (q3map_surfacelight)",
         kImplemented);
    action({"-backsplash"},
           {{ArgKind::Float, "Fscale", Range::atLeast(0)}, {ArgKind::Float, "Fdistance", Range::any()}}, 2,
           cli::formatNumber(defaults.backsplashFractionScale) + " " + cli::formatNumber(defaults.backsplashDistance),
           "Scale the back-splash fraction of area lights and set their distance globally (a distance below -900 "
           "keeps the default)",
           kImplemented, [](O& o, Values v) {
               o.backsplashFractionScale = static_cast<float>(v[0].number);
               if (v[1].number >= -900) o.backsplashDistance = static_cast<float>(v[1].number);
           });
    flag({"-border"}, &O::debugBorder, "Add a red border to lightmaps for debugging", kNotImplemented);
    real({"-bouncecolorratio"}, &O::bounceColorRatio, Range::between(0, 1),
         "How much the texture colour tints bounced light (0..1)", kImplemented);
    flag({"-bouncegrid"}, &O::bounceGrid, "Also add radiosity to the light grid and the SH grid", kImplemented);
    flag({"-bounceonly"}, &O::bounceOnly, "Store only the bounced light", kImplemented);
    action({"-bouncescale"}, {{ArgKind::Float, "F", Range::atLeast(0)}}, 1, "0.25",
           "Multiply the scale of radiosity (default 0.25) by F", kImplemented,
           [](O& o, Values v) { o.bounceScale *= static_cast<float>(v[0].number); });
    integer({"-bounce"}, &O::bounce, Range::between(0, 1000), "Number of radiosity bounces", kImplemented);
    real({"-brightness"}, &O::brightness, Range::atLeast(0), "Scale of the resulting lightmap brightness",
         kImplemented);
    flag({"-cheapgrid"}, &O::cheapGrid, "Use -cheap style lighting for the light grid", kImplemented);
    flag({"-cheap"}, &O::cheap, "Stop adding lights to a sample once it is white", kImplemented);
    real({"-compensate"}, &O::compensate, Range::positive(),
         "Lightmap compensation (darkening divisor applied after everything else)", kImplemented);
    real({"-contrast"}, &O::contrast, Range::between(-255, 255), "Lighting contrast (-255..255)", kImplemented);
    flag({"-cpma"}, &O::cpma, "CPMA vertex lighting mode", kNotImplemented);
    flag({"-custinfoparms"}, &O::custInfoParms, "Read scripts/custinfoparms.txt", kNotImplemented);
    flag({"-dark"}, &O::dark, "Darken lightmap seams", kNotImplemented);
    flag({"-debugaxis"}, &O::debugAxis, "Colour lightmaps by their projection axis", kNotImplemented);
    flag({"-debugcluster"}, &O::debugCluster, "Colour lightmaps by the cluster of each luxel", kNotImplemented);
    flag({"-debugdeluxe"}, &O::debugDeluxe, "Show deluxemaps in place of lightmaps", kImplemented);
    flag({"-debugnormals"}, &O::debugNormals, "Colour lightmaps by the surface normal", kNotImplemented);
    flag({"-debugorigin"}, &O::debugOrigin, "Colour lightmaps by luxel origin", kNotImplemented);
    flag({"-debugsamplesize"}, &O::debugSampleSize, "Print every 'surface too large for sample size' warning",
         kNotImplemented);
    flag({"-debugsurfaces", "-debugsurface"}, &O::debugSurfaces, "Colour lightmaps by surface index", kNotImplemented);
    flag({"-debug"}, &O::debug, "Mark lightmaps by the cluster state of each luxel", kNotImplemented);
    integer({"-deluxemode"}, &O::deluxeMode, Range::between(0, 1), "Deluxemap space: 0 model space, 1 tangent space",
            kImplemented);
    flag({"-deluxe", "-deluxemap"}, &O::deluxe, "Write light direction maps (deluxemaps)", kImplemented);
    flag({"-dirtdebug", "-debugdirt"}, &O::dirtDebug, "Store the dirt maps as lightmaps", kImplemented);
    real({"-dirtdepth"}, &O::dirtDepth, Range::positive(), "Dirt mapping ray length", kImplemented);
    real({"-dirtgain"}, &O::dirtGain, Range::positive(), "Dirt mapping exponent", kImplemented);
    integer({"-dirtmode"}, &O::dirtMode, Range::between(0, 1), "Dirt ray directions: 0 ordered, 1 random",
            kImplemented);
    real({"-dirtscale"}, &O::dirtScale, Range::atLeast(0), "Dirt mapping scale", kImplemented);
    flag({"-dirty"}, &O::dirty, "Enable dirt mapping (ambient occlusion)", kImplemented);
    flag({"-dump"}, &O::dump, "Write radiosity lights as numbered .map prefabs", kImplemented);
    flag({"-export"}, &O::exportLightmaps, "Also export the lightmaps as images when done", kImplemented);
    real({"-exposure"}, &O::exposure, Range::atLeast(0), "Lightmap exposure for overbright spots (0 = off)",
         kImplemented);
    flag({"-external"}, &O::externalLightmaps, "Write external lightmaps even at the internal size", kImplemented);
    action({"-extlmhacksize"}, {{ArgKind::Int, "N", Range::between(2, 16384)}, {ArgKind::Int, "N", Range::between(2, 16384)}},
           1, "off", "External lightmap size referenced through a generated shader (power of two)", kNotImplemented,
           [](O& o, Values v) { storePageSize("-extlmhacksize", o.extLmHackWidth, o.extLmHackHeight, v); });
    real({"-extradist"}, &O::extraDist, Range::atLeast(0), "Extra distance added to point and area lights",
         kImplemented);
    flag({"-extravisnudge"}, &O::extraVisNudge, "Nudge luxel origins towards a better vis cluster", kNotImplemented);
    flag({"-fastbounce"}, &O::fastBounce, "Use -fast style lighting for radiosity", kImplemented);
    action({"-faster"}, {}, 0, "off", "Faster falloff for area lights; implies -fast", kImplemented,
           [](O& o, Values) { o.faster = o.fast = true; });
    flag({"-fastgrid"}, &O::fastGrid, "Use -fast style lighting for the light grid", kImplemented);
    flag({"-fast"}, &O::fast, "Ignore tiny light contributions", kImplemented);
    flag({"-fill"}, &O::fill, "Fill unused lightmap texels from their neighbours", kNotImplemented);
    flag({"-fillpink"}, &O::fillPink, "Fill unused lightmap texels with pink", kNotImplemented);
    flag({"-filter"}, &O::filter, "Box-filter lightmaps", kImplemented);
    flag({"-floodlight"}, &O::floodlight, "Enable floodlight", kImplemented);
    real({"-gamma"}, &O::gamma, Range::positive(), "Lightmap gamma", kImplemented);
    real({"-gridambientdirectionality"}, &O::gridAmbientDirectionality, Range::between(-1, 1),
         "Ambient directional lighting received by the grid", kImplemented);
    real({"-gridambientscale"}, &O::gridAmbientScale, Range::atLeast(0),
         "Scale of the light grid's ambient part only", kImplemented);
    real({"-griddirectionality"}, &O::gridDirectionality, Range::between(0, 1),
         "Directional lighting received by the grid", kImplemented);
    real({"-gridscale"}, &O::gridScale, Range::atLeast(0), "Scale of the light grid", kImplemented);
    real({"-gridscalesh"}, &O::gridScaleSH, Range::positive(),
         "SH grid density: SH cell size = legacy cell size / F per axis", kImplemented);
    action({"-gridsh"},
           {{ArgKind::Float, "X", Range::positive()}, {ArgKind::Float, "Y", Range::positive()},
            {ArgKind::Float, "Z", Range::positive()}},
           3, "derived from -gridscalesh",
           "Explicit SH grid cell size in world units (each axis at least 8); overrides -gridscalesh", kImplemented,
           [](O& o, Values v) {
               for (int i = 0; i < 3; ++i) o.gridSizeSH[i] = static_cast<float>(v[static_cast<size_t>(i)].number);
           });
    action({"-lightanglehl"}, {{ArgKind::Int, "0|1", Range::between(0, 1)}}, 1, defaults.lightAngleHL ? "1" : "0",
           "Half-Lambert angle attenuation off (0) or on (1)", kNotImplemented,
           [](O& o, Values v) { o.lightAngleHL = v[0].number != 0; });
    action({"-lightmapdir"}, {{ArgKind::Text, "directory", {}}}, 1, "maps/<map>/",
           "Folder of external lightmaps; implies -external", kNotImplemented, [](O& o, Values v) {
               o.lightmapDir = v[0].text;
               o.externalLightmaps = true;
           });
    action({"-lightmapatlas"}, {{ArgKind::Text, "FILE.png", {}}}, 1, "off",
           "Also write the packed lightmap pages side by side as one PNG picture", kImplemented,
           [](O& o, Values v) { o.lightmapAtlas = v[0].text; });
    integer({"-lightmapsearchblocksize"}, &O::lightmapSearchBlockSize, Range::atLeast(0),
            "Restricted lightmap page search: block size", kNotImplemented);
    integer({"-lightmapsearchpower"}, &O::lightmapSearchPower, Range::atLeast(0),
            "Restricted lightmap page search: merge power", kNotImplemented);
    action({"-lightmapsize"},
           {{ArgKind::Int, "N", Range::between(2, 16384)}, {ArgKind::Int, "N", Range::between(2, 16384)}}, 1,
           std::to_string(defaults.lightmapWidth),
           "Lightmap page size (power of two; a second value sets the height)", kImplemented,
           [](O& o, Values v) { storePageSize("-lightmapsize", o.lightmapWidth, o.lightmapHeight, v); });
    flag({"-lomem"}, &O::loMem, "Low memory but slower lighting mode", kNotImplemented);
    flag({"-lowquality"}, &O::lowQuality, "Low quality floodlight: one ray in ten", kImplemented);
    integer({"-minsamplesize"}, &O::minSampleSize, Range::atLeast(1), "Minimum lightmap resolution in units per luxel",
            kNotImplemented);
    flag({"-nobouncestore"}, &O::noBounceStore, "Write the BSP and lightmaps only after the last bounce",
         kImplemented);
    flag({"-nocollapse"}, &O::noCollapse, "Do not merge identical lightmaps", kImplemented);
    flag({"-nodeluxe", "-nodeluxemap"}, &O::deluxe, "Disable deluxemaps", kImplemented, false);
    flag({"-nofastpoint"}, &O::fastPoint, "Disable the fast falloff envelope of point lights", kNotImplemented, false);
    flag({"-nogrid"}, &O::noGrid, "Do not compute the light grid", kImplemented);
    flag({"-nolightmapsearch"}, &O::noLightmapSearch, "Place lightmaps in page order without searching",
         kNotImplemented);
    flag({"-nolm"}, &O::noLightmaps, "Skip lightmaps (vertex light only)", kImplemented);
    flag({"-normalmap"}, &O::normalmap, "Colour lightmaps by the surface normal", kNotImplemented);
    action({"-nosRGB"}, {}, 0, "off", "Treat colours, textures and lightmaps as linear", kNotImplemented,
           [](O& o, Values) { setColourSpaces(o, true, true, true, false); });
    action({"-nosRGBcolor"}, {}, 0, "off", "Treat shader and light colours as linear", kNotImplemented,
           [](O& o, Values) { setColourSpaces(o, false, false, true, false); });
    action({"-nosRGBlight"}, {}, 0, "off", "Write lightmaps as linear", kNotImplemented,
           [](O& o, Values) { setColourSpaces(o, true, false, false, false); });
    action({"-nosRGBtex"}, {}, 0, "off", "Treat textures as linear", kNotImplemented,
           [](O& o, Values) { setColourSpaces(o, false, true, false, false); });
    flag({"-nostyle", "-nostyles"}, &O::noStyles, "Disable light styles", kImplemented);
    flag({"-nosurf"}, &O::noSurf, "Trace only against the BSP tree, not surfaces", kNotImplemented);
    flag({"-notrace"}, &O::noTrace, "Disable shadows", kImplemented);
    action({"-novertex"}, {{ArgKind::Float, "F", Range::between(0, 1)}}, 0, "off",
           "Disable vertex lighting; an optional value (0..1) sets a constant vertex light", kImplemented,
           [](O& o, Values v) {
               o.noVertexLight = true;
               o.vertexLightValue = v.empty() ? -1.0f : static_cast<float>(v[0].number);
           });
    flag({"-onesky"}, &O::oneSky, "Any sky passes every sun (no per-sky-shader sun masks)", kImplemented);
    flag({"-patchshadows"}, &O::patchShadows, "Patches cast shadows", kImplemented);
    action({"-pointscale", "-point"}, {scaleArg}, 1, cli::formatNumber(defaults.pointScale),
           "Scale of point and spot light entities", kImplemented, [](O& o, Values v) {
               o.pointScale = o.spotScale = static_cast<float>(v[0].number);
           });
    flag({"-q3"}, &O::wolfLight, "Inverse-square falloff by default (Quake III)", kNotImplemented, false);
    flag({"-randomsamples"}, &O::randomSamples, "Random sampling for lightmaps", kNotImplemented);
    integer({"-rawlightmapsizelimit"}, &O::rawLightmapSizeLimit, Range::atLeast(0),
            "Maximum raw lightmap size in luxels", kNotImplemented);
    integer({"-samplescale"}, &O::sampleScale, Range::atLeast(1), "Multiply every lightmap sample size (0 = unset)",
            kImplemented);
    integer({"-samplesize"}, &O::sampleSize, Range::atLeast(1), "Default lightmap resolution in units per luxel",
            kImplemented);
    integer({"-samplessearchboxsize"}, &O::samplesSearchBoxSize, Range::between(1, 4),
            "Search box size (1..4) for adaptive supersampling", kNotImplemented);
    action({"-samples"}, {{ArgKind::Text, "N|+N", {}}}, 1, std::to_string(defaults.lightSamples),
           "Adaptive supersampling depth at light and shadow edges (1..16)", kImplemented, storeSamples);
    real({"-saturation"}, &O::saturation, Range::any(), "Lighting saturation (0 grey, > 1 saturate)", kImplemented);
    action({"-scale"}, {scaleArg}, 1, "1", "Scale of every light type (point, spot, area, sky)", kImplemented,
           [](O& o, Values v) {
               float s = static_cast<float>(v[0].number);
               o.pointScale *= s;
               o.spotScale *= s;
               o.areaScale *= s;
               o.skyScale *= s;
           });
    action({"-shadeangle"}, {{ArgKind::Float, "A", Range::between(0, 360)}}, 1, "off",
           "Phong shading: smooth vertex normals meeting at less than A degrees on every surface "
           "(shader q3map_shadeAngle and entity _shadeangle win); 0 sets no default",
           kImplemented, [](O& o, Values v) {
               // As q3map2: a positive angle also switches phong shading on.
               o.shadeAngle = static_cast<float>(v[0].number);
               if (o.shadeAngle > 0) o.shade = true;
           });
    flag({"-shade"}, &O::shade,
         "Phong shading on surfaces whose shader (q3map_shadeAngle) or entity (_shadeangle) sets an angle; "
         "with -shadeangle A, on every surface",
         kImplemented);
    action({"-shbspx"}, {}, 0, "off",
           "Store the SH grid as the BSPX lump LIGHTGRID_SH of a version 46 file instead of lump 18; implies -sh",
           kImplemented, [](O& o, Values) { o.sh = o.shBspx = true; });
    flag({"-sh"}, &O::sh, "Compute the L2 spherical-harmonics light grid (lump 18, BSP version 47)", kImplemented);
    action({"-shgather"}, {}, 0, "off",
           "Add to the SH grid the indirect light each probe sees by tracing rays into the lit map (lightmap "
           "light times texture colour); implies -sh",
           kImplemented, [](O& o, Values) { o.sh = o.shGather = true; });
    flag({"-shexact"}, &O::shExact,
         "Light and trace every light at every SH probe instead of first at a block's corner probes, then "
         "interpolating far lights between them and sparing near ones their rays where the corners agree",
         kImplemented);
    integer({"-shgathersamples"}, &O::shGatherSamples, Range::between(16, 65536),
            "Rays per SH probe of -shgather (a fixed spherical Fibonacci set)", kImplemented);
    integer({"-shgatherstep"}, &O::shGatherStep, Range::between(1, 8),
            "Gather from every Nth SH probe per axis only and interpolate the others (1: every probe)",
            kImplemented);
    real({"-skyscale", "-sky"}, &O::skyScale, Range::atLeast(0), "Scale of sky and sun light", kImplemented);
    flag({"-slowallocate"}, &O::slowAllocate, "Older, slower lightmap packing", kNotImplemented);
    action({"-sphericalscale", "-spherical"}, {scaleArg}, 1, cli::formatNumber(defaults.pointScale),
           "Scale of spherical point light entities only", kNotImplemented,
           [](O& o, Values v) { o.pointScale = static_cast<float>(v[0].number); });
    real({"-spotscale", "-spot"}, &O::spotScale, Range::atLeast(0), "Scale of spot light entities", kImplemented);
    action({"-sRGB"}, {}, 0, "off", "Treat colours, textures and lightmaps as sRGB", kNotImplemented,
           [](O& o, Values) { setColourSpaces(o, true, true, true, true); });
    action({"-sRGBcolor"}, {}, 0, "off", "Treat shader and light colours as sRGB", kNotImplemented,
           [](O& o, Values) { setColourSpaces(o, false, false, true, true); });
    action({"-sRGBlight"}, {}, 0, "off", "Write lightmaps as sRGB", kNotImplemented,
           [](O& o, Values) { setColourSpaces(o, true, false, false, true); });
    action({"-sRGBtex"}, {}, 0, "off", "Treat textures as sRGB", kNotImplemented,
           [](O& o, Values) { setColourSpaces(o, false, true, false, true); });
    flag({"-style", "-styles"}, &O::noStyles, "Enable light styles", kImplemented, false);
    flag({"-sunonly"}, &O::sunOnly, "Compute only sun light", kImplemented);
    integer({"-super", "-supersample"}, &O::superSample, Range::between(1, 8), "Ordered N x N supersampling",
            kImplemented);
    real({"-thresh"}, &O::subdivideThreshold, Range::positive(), "Triangle subdivision threshold", kNotImplemented);
    flag({"-trianglecheck"}, &O::triangleCheck, "Clamp luxels to their triangle", kNotImplemented);
    flag({"-trisoup"}, &O::triSoup, "Convert brush faces to triangle soup", kNotImplemented);
    real({"-vertexscale"}, &O::vertexScale, Range::atLeast(0), "Scale of the resulting vertex light", kNotImplemented);
    flag({"-wolf"}, &O::wolfLight, "Linear falloff by default (Wolfenstein: ET)", kNotImplemented);
    flag({"-worldlights"}, &O::worldLights,
         "Write the BSPX lump WORLDLIGHTS: the point, spot and sun lights (origin, intensity in SH grid units, "
         "falloff, cone, cluster, whether the SH grid holds their direct light) for engines that light models "
         "with the strongest of them directly (docs/world-lights-format.md)",
         kImplemented);
    action({"-shnoworldlights"}, {}, 0, "off",
           "Leave the direct light of the lights WORLDLIGHTS lists out of the SH grid, for engines that add it "
           "back per model from the lump (indirect light, sky domes and area lights stay in the grid); implies "
           "-sh and -worldlights",
           kImplemented, [](O& o, Values) { o.sh = o.worldLights = o.shNoWorldLights = true; });
    return t;
}

}  // namespace

const cli::OptionTable<LightOptions>& lightOptionTable() {
    static const cli::OptionTable<LightOptions> table = buildLightTable();
    return table;
}

}  // namespace q3::light
