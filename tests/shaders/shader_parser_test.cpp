// Directive parsing on hand-written scripts: surfaceparm flags, every lighting directive, stage
// images, implicit shaders, the table's look-up rules.
#include <gtest/gtest.h>

#include <cmath>
#include <thread>

#include "script.h"
#include "shader_info.h"
#include "shader_math.h"
#include "shader_parser.h"
#include "shader_test_util.h"

namespace q3 {
namespace {

using test::CapturedLog;

std::vector<ShaderInfo> parse(std::string_view text, CapturedLog& cap) {
    return parseShaderScript(text, "scripts/test.shader", cap.log);
}

ShaderInfo parseOne(std::string_view text) {
    CapturedLog cap;
    std::vector<ShaderInfo> shaders = parse(text, cap);
    EXPECT_EQ(shaders.size(), 1u);
    EXPECT_TRUE(cap.warnings.empty()) << cap.all();
    return shaders.empty() ? ShaderInfo{} : shaders[0];
}

void expectVec(Vec3 v, Vec3 expected, float tol = 1e-5f) {
    EXPECT_NEAR(v.x, expected.x, tol);
    EXPECT_NEAR(v.y, expected.y, tol);
    EXPECT_NEAR(v.z, expected.z, tol);
}

TEST(ShaderMath, SunDirectionFollowsYawAndElevation) {
    expectVec(sunDirectionFromAngles(0, 0), {1, 0, 0});
    expectVec(sunDirectionFromAngles(90, 0), {0, 1, 0});
    expectVec(sunDirectionFromAngles(180, 0), {-1, 0, 0});
    expectVec(sunDirectionFromAngles(123, 90), {0, 0, 1});
    const float c = std::cos(degToRad(45)) * std::cos(degToRad(60));
    expectVec(sunDirectionFromAngles(45, 60), {c, c, std::sin(degToRad(60))});
    EXPECT_NEAR(length(sunDirectionFromAngles(305, 70)), 1.0f, 1e-6f);
}

TEST(ShaderMath, ColourNormalisedToLargestComponent) {
    expectVec(normalizeShaderColor({0.5f, 0.1f, 0.1f}), {1, 0.2f, 0.2f});
    expectVec(normalizeShaderColor({2, 4, 1}), {0.5f, 1, 0.25f});
    expectVec(normalizeShaderColor({0, 0, 0}), {1, 1, 1});
}

TEST(SurfaceParms, QuakeThreeFlagValues) {
    ShaderInfo s = parseOne(R"(textures/a/b
{
    surfaceparm nonsolid
    surfaceparm trans
    surfaceparm nomarks
    surfaceparm noimpact
    surfaceparm nodlight
    surfaceparm alphashadow
    surfaceparm lightfilter
    surfaceparm nodraw
})");
    EXPECT_EQ(s.contentFlags, contents::Translucent);  // nonsolid clears solid
    EXPECT_EQ(s.surfaceFlags, 0x4000u | 0x20u | 0x10u | 0x20000u | 0x10000u | 0x8000u | 0x80u);
    EXPECT_TRUE(s.isTranslucent());
    EXPECT_TRUE(s.isAlphaShadow());
    EXPECT_TRUE(s.isLightFilter());
    EXPECT_TRUE(s.isNoDraw());
    EXPECT_FALSE(s.compileFlags & compileflags::Solid);
}

TEST(SurfaceParms, ContentsOfLiquidsClipsAndPortals) {
    struct Case {
        const char* parm;
        uint32_t contents;
        uint32_t surface;
    };
    const Case cases[] = {
        {"water", 0x20, 0},           {"slime", 0x10, 0},          {"lava", 0x8, 0},
        {"fog", 0x40, 0},             {"playerclip", 0x10000, 0},  {"botclip", 0x400000, 0},
        {"areaportal", 0x8000, 0},    {"clusterportal", 0x100000, 0}, {"donotenter", 0x200000, 0},
        {"origin", 0x1000000, 0},     {"detail", 0x1 | 0x8000000, 0}, {"structural", 0x1 | 0x10000000, 0},
        {"sky", 0x1, 0x4},            {"hint", 0x1, 0x100},        {"nolightmap", 0x1, 0xC00},
        {"pointlight", 0x1, 0xC00},   {"lightgrid", 0x1, 0},       {"antiportal", 0x1, 0},
        {"metalsteps", 0x1, 0x1000},  {"slick", 0x1, 0x2},         {"ladder", 0x1, 0x8},
    };
    for (const Case& c : cases) {
        ShaderInfo s = parseOne(std::string("x\n{\n surfaceparm ") + c.parm + "\n}\n");
        EXPECT_EQ(s.contentFlags, c.contents) << c.parm;
        EXPECT_EQ(s.surfaceFlags, c.surface) << c.parm;
    }
    EXPECT_TRUE(parseOne("x { surfaceparm lightgrid\n }").compileFlags & compileflags::LightGrid);
    EXPECT_TRUE(parseOne("x { surfaceparm antiportal\n }").compileFlags & compileflags::AntiPortal);
    EXPECT_TRUE(parseOne("x { surfaceparm nolightmap\n }").isVertexLit());
    EXPECT_TRUE(parseOne("x { surfaceparm fog\n }").isFog());
}

TEST(SurfaceParms, Q3mapPrefixedParmAndOnlyVertexLighting) {
    ShaderInfo s = parseOne("x\n{\n q3map_nolightmap\n q3map_trans\n}\n");
    EXPECT_TRUE(s.isVertexLit());
    EXPECT_TRUE(s.isTranslucent());
    ShaderInfo v = parseOne("x\n{\n q3map_onlyVertexLighting\n}\n");
    EXPECT_EQ(v.surfaceFlags, surfaceflags::VertexLit);
}

TEST(ShaderParser, SunDirectives) {
    ShaderInfo s = parseOne(R"(textures/skies/test
{
    q3map_lightStyle 3
    q3map_lightmapFilterRadius 0 8
    q3map_sun .5 .1 .1 50 65 35
    q3map_sunExt 1 0.95 0.9 400 315 50 2 16 // trailing comment
    sun 0 0 0 10 0 90
})");
    ASSERT_EQ(s.suns.size(), 3u);
    EXPECT_TRUE(s.isSky());
    EXPECT_EQ(s.surfaceFlags & surfaceflags::Sky, surfaceflags::Sky);
    const ShaderSun& a = s.suns[0];
    expectVec(a.color, {1, 0.2f, 0.2f});
    EXPECT_FLOAT_EQ(a.intensity, 50);
    EXPECT_FLOAT_EQ(a.yawDegrees, 65);
    EXPECT_FLOAT_EQ(a.elevationDegrees, 35);
    expectVec(a.direction, sunDirectionFromAngles(65, 35));
    EXPECT_EQ(a.samples, 1);
    EXPECT_FLOAT_EQ(a.devianceDegrees, 0);
    EXPECT_EQ(a.style, 3);
    EXPECT_FLOAT_EQ(a.filterRadius, 8);
    const ShaderSun& b = s.suns[1];
    expectVec(b.color, {1, 0.95f, 0.9f});
    EXPECT_FLOAT_EQ(b.devianceDegrees, 2);
    EXPECT_EQ(b.samples, 16);
    expectVec(s.suns[2].color, {1, 1, 1});
    expectVec(s.suns[2].direction, {0, 0, 1});
}

TEST(ShaderParser, SunExtWithoutJitterKeepsOneSample) {
    ShaderInfo s = parseOne("x\n{\n q3map_sunExt 1 1 1 100 0 45\n}\n");
    ASSERT_EQ(s.suns.size(), 1u);
    EXPECT_EQ(s.suns[0].samples, 1);
}

TEST(ShaderParser, SkyLightWithOptionalHorizon) {
    ShaderInfo s = parseOne("x\n{\n q3map_skyLight 125 3\n q3map_skylight 80 1 -30 120 0\n}\n");
    ASSERT_EQ(s.skyLights.size(), 2u);
    EXPECT_FLOAT_EQ(s.skyLights[0].value, 125);
    EXPECT_EQ(s.skyLights[0].iterations, 3);
    EXPECT_EQ(s.skyLights[0].horizonMin, 0);
    EXPECT_EQ(s.skyLights[0].horizonMax, 90);
    EXPECT_TRUE(s.skyLights[0].sampleColor);
    EXPECT_EQ(s.skyLights[1].iterations, 2);  // clamped up
    EXPECT_EQ(s.skyLights[1].horizonMin, -30);
    EXPECT_EQ(s.skyLights[1].horizonMax, 90);  // clamped down
    EXPECT_FALSE(s.skyLights[1].sampleColor);
}

TEST(ShaderParser, SurfaceLightDirectives) {
    ShaderInfo s = parseOne(R"(textures/base_light/x
{
    q3map_surfacelight 2000
    q3map_lightRGB 255 128 0
    q3map_lightSubdivide 64
    q3map_backsplash 10 16
    q3map_bounceScale 0.5
    q3map_noFast
    q3map_lightImage textures/base_light/x.blend.jpg
    deformVertexes autosprite2
})");
    EXPECT_FLOAT_EQ(s.surfaceLight, 2000);
    ASSERT_TRUE(s.lightRGB.has_value());
    expectVec(*s.lightRGB, {1, 128.0f / 255.0f, 0});
    EXPECT_EQ(s.lightSubdivide, 64);
    EXPECT_FLOAT_EQ(s.backsplashFraction, 0.1f);
    EXPECT_FLOAT_EQ(s.backsplashDistance, 16);
    EXPECT_TRUE(s.backsplashSet);
    EXPECT_FLOAT_EQ(s.bounceScale, 0.5f);
    EXPECT_TRUE(s.noFast);
    EXPECT_EQ(s.lightImage, "textures/base_light/x.blend.jpg");
    EXPECT_TRUE(s.autosprite);
    EXPECT_TRUE(s.contentFlags & contents::Detail);
}

TEST(ShaderParser, DefaultsMatchQ3map2) {
    ShaderInfo s = parseOne("x\n{\n}\n");
    EXPECT_EQ(s.contentFlags, contents::Solid);
    EXPECT_EQ(s.surfaceFlags, 0u);
    EXPECT_FLOAT_EQ(s.backsplashFraction, 0.05f);
    EXPECT_FLOAT_EQ(s.backsplashDistance, 23);
    EXPECT_FALSE(s.backsplashSet);
    EXPECT_FLOAT_EQ(s.bounceScale, 1);
    EXPECT_FLOAT_EQ(s.lightmapSampleOffset, 1);
    EXPECT_EQ(s.lightmapAxis, -1);
    EXPECT_FLOAT_EQ(s.lightmapBrightness, 1);
    EXPECT_FLOAT_EQ(s.vertexScale, 1);
    EXPECT_FALSE(s.hasStages);
    EXPECT_TRUE(s.explicitScript);
    EXPECT_EQ(s.sourceFile, "scripts/test.shader");
    EXPECT_EQ(s.sourceLine, 1);
}

TEST(ShaderParser, LightmapAndVertexDirectives) {
    ShaderInfo s = parseOne(R"(x
{
    q3map_lightmapSampleSize 8
    q3map_lightmapSampleOffset 2.5
    q3map_lightmapFilterRadius 4 6
    q3map_lightmapAxis z
    q3map_lightmapSize 512 256
    q3map_lightmapBrightness 2
    q3map_lightmapGamma 1.5
    q3map_lightmapMergable
    q3map_shadeAngle 120
    q3map_normalImage textures/x_n.tga
    q3map_vertexScale 0.5
    q3map_vertexScale 0.5
    q3map_noVertexLight
    q3map_forceSunlight
    q3map_splotchFix
    q3map_noDirty
    q3map_floodLight 255 0 0 1024 128 0.5
    q3map_styleMarker2
    q3map_nonplanar
    cull twosided
})");
    EXPECT_EQ(s.lightmapSampleSize, 8);
    EXPECT_FLOAT_EQ(s.lightmapSampleOffset, 2.5f);
    EXPECT_FLOAT_EQ(s.lightmapFilterRadius, 4);
    EXPECT_FLOAT_EQ(s.lightFilterRadius, 6);
    EXPECT_EQ(s.lightmapAxis, 2);
    EXPECT_EQ(s.lightmapWidth, 512);
    EXPECT_EQ(s.lightmapHeight, 256);
    EXPECT_FLOAT_EQ(s.lightmapBrightness, 3);
    EXPECT_TRUE(s.lightmapMergable);
    EXPECT_FLOAT_EQ(s.shadeAngleDegrees, 120);
    EXPECT_EQ(s.normalImage, "textures/x_n.tga");
    EXPECT_FLOAT_EQ(s.vertexScale, 0.25f);
    EXPECT_TRUE(s.noVertexLight);
    EXPECT_TRUE(s.forceSunlight);
    EXPECT_TRUE(s.splotchFix);
    EXPECT_TRUE(s.noDirty);
    ASSERT_TRUE(s.floodLight.has_value());
    expectVec(s.floodLight->color, {1, 0, 0});
    EXPECT_FLOAT_EQ(s.floodLight->distance, 1024);
    EXPECT_FLOAT_EQ(s.floodLight->intensity, 128);
    EXPECT_FLOAT_EQ(s.floodLight->directionScale, 0.5f);
    EXPECT_EQ(s.styleMarker, 2);
    EXPECT_TRUE(s.nonplanar);
    EXPECT_TRUE(s.twoSided);
    EXPECT_TRUE(parseOne("x { cull none\n }").twoSided);
    EXPECT_TRUE(parseOne("x { cull disable\n }").twoSided);
    EXPECT_FALSE(parseOne("x { cull front\n }").twoSided);
    EXPECT_EQ(parseOne("x { q3map_styleMarker\n }").styleMarker, 1);
}

// q3map2: q3map_terrain makes indexed, unclipped, T-junction-free, non-planar forced meta surfaces
// smoothed over 179 degrees; q3map_indexed alone only marks the shader for index maps.
TEST(ShaderParser, TerrainAndIndexedShaders) {
    const ShaderInfo terrain = parseOne("t { q3map_terrain\n }");
    EXPECT_TRUE(terrain.legacyTerrain);
    EXPECT_TRUE(terrain.indexed);
    EXPECT_TRUE(terrain.noClip);
    EXPECT_TRUE(terrain.noTJunc);
    EXPECT_TRUE(terrain.nonplanar);
    EXPECT_TRUE(terrain.forceMeta);
    EXPECT_FLOAT_EQ(terrain.shadeAngleDegrees, 179);
    const ShaderInfo indexed = parseOne("i { q3map_indexed\n }");
    EXPECT_TRUE(indexed.indexed);
    EXPECT_FALSE(indexed.legacyTerrain);
    EXPECT_FALSE(indexed.noClip);
    EXPECT_FALSE(indexed.forceMeta);
}

TEST(ShaderParser, FirstStageImageIsTheDefaultLightImage) {
    ShaderInfo s = parseOne(R"(textures/a/wall
{
    {
        map $lightmap
        rgbGen identity
    }
    {
        animMap 5 textures/a/frame1.tga textures/a/frame2.tga
        blendFunc GL_DST_COLOR GL_ZERO
    }
    {
        clampMap textures/a/other.tga
    }
})");
    EXPECT_TRUE(s.hasStages);
    EXPECT_EQ(s.firstStageImage, "textures/a/frame1.tga");
    EXPECT_EQ(s.lightImage, "textures/a/frame1.tga");
    EXPECT_EQ(s.lightImageCandidates(), (std::vector<std::string>{"textures/a/frame1.tga", "textures/a/wall"}));

    ShaderInfo c = parseOne("x\n{\n {\n clampMap textures/c.jpg\n }\n}\n");
    EXPECT_EQ(c.lightImage, "textures/c.jpg");
}

TEST(ShaderParser, LightImageOrderFollowsQ3map2) {
    // An explicit q3map_lightImage wins even after a stage.
    ShaderInfo a = parseOne("x\n{\n { map textures/stage.tga\n }\n q3map_lightImage textures/light.tga\n}\n");
    EXPECT_EQ(a.lightImage, "textures/light.tga");
    EXPECT_EQ(a.firstStageImage, "textures/stage.tga");
    // An editor image before the stages keeps the stage image out of the light image.
    ShaderInfo b = parseOne("x\n{\n qer_editorImage textures/ed.tga\n { map textures/stage.tga\n }\n}\n");
    EXPECT_EQ(b.lightImage, "");
    EXPECT_EQ(b.firstStageImage, "textures/stage.tga");
    EXPECT_EQ(b.lightImageCandidates(), (std::vector<std::string>{"textures/ed.tga", "x"}));
    // An editor image that is the shader's own name with an extension is one candidate, not two;
    // "x.blend.tga" is another image than "x".
    EXPECT_EQ(parseOne("textures/a/w\n{\n qer_editorImage textures/a/w.tga\n}\n").lightImageCandidates(),
              std::vector<std::string>{"textures/a/w.tga"});
    EXPECT_EQ(parseOne("textures/a/w\n{\n q3map_lightImage textures/a/w.blend.tga\n}\n").lightImageCandidates(),
              (std::vector<std::string>{"textures/a/w.blend.tga", "textures/a/w"}));
    // skyParms gives <env>_up; "-" and "full" give nothing.
    ShaderInfo c = parseOne("x\n{\n skyparms env/desert/desert - -\n}\n");
    EXPECT_EQ(c.skyParmsEnv, "env/desert/desert");
    EXPECT_EQ(c.lightImage, "env/desert/desert_up");
    ShaderInfo d = parseOne("x\n{\n skyParms full 512 -\n}\n");
    EXPECT_EQ(d.skyParmsEnv, "");
    EXPECT_EQ(d.lightImage, "");
    // nodraw shaders have no light image.
    EXPECT_TRUE(parseOne("x\n{\n surfaceparm nodraw\n}\n").lightImageCandidates().empty());
}

TEST(ShaderParser, Q3mapSuffixAndUnknownDirectivesIgnored) {
    CapturedLog cap;
    auto shaders = parse(R"(textures/a/b:q3map
{
    nopicmip
    tessSize 128
    q3map_globaltexture
    q3map_tcGen ivector ( 256 0 0 ) ( 0 256 0 )
    fogparms ( 0.5 0.5 0.5 ) 512
    someEngineDirective with args
    { map textures/a/b.tga
      tcMod scroll 1 1 }
}
textures/c/d { q3map_surfacelight 10
}
)",
                         cap);
    ASSERT_EQ(shaders.size(), 2u);
    EXPECT_EQ(shaders[0].name, "textures/a/b");
    EXPECT_EQ(shaders[0].firstStageImage, "textures/a/b.tga");
    EXPECT_EQ(shaders[1].name, "textures/c/d");
    EXPECT_FLOAT_EQ(shaders[1].surfaceLight, 10);
    EXPECT_EQ(shaders[1].sourceLine, 12);
    EXPECT_TRUE(cap.warnings.empty()) << cap.all();
}

// q3map_tcMod steps compose in script order into one matrix (a rotation applies before what came
// earlier, as q3map2 multiplies); q3map_remapShader keeps its target's name.
TEST(ShaderParser, TcModComposesInScriptOrderAndRemapKeepsItsTarget) {
    const ShaderInfo si = parseOne(R"(x
{
    q3map_tcMod scale 2 0.5
    q3map_tcMod rotate 90
    q3map_tcMod translate 0.25 0.5
    q3map_remapShader textures/other/target
}
)");
    const auto& m = si.tcMod;
    // scale, then rotate: [[2 0 0] [0 .5 0]] * [[c -s 0] [s c 0]] with c = 0, s = 1.
    EXPECT_NEAR(m[0][0], 0, 1e-6f);
    EXPECT_NEAR(m[0][1], -2, 1e-6f);
    EXPECT_NEAR(m[1][0], 0.5f, 1e-6f);
    EXPECT_NEAR(m[1][1], 0, 1e-6f);
    EXPECT_FLOAT_EQ(m[0][2], 0.25f);
    EXPECT_FLOAT_EQ(m[1][2], 0.5f);
    EXPECT_EQ(si.remapShader, "textures/other/target");
    EXPECT_EQ(parseOne("y\n{\n}\n").tcMod[0][0], 1);  // identity without directives
    CapturedLog cap;
    parse("z\n{\n q3map_tcMod wobble 1 2\n}\n", cap);
    EXPECT_NE(cap.all().find("unknown q3map_tcMod method 'wobble'"), std::string::npos) << cap.all();
}

// q3map_[color|rgb|alpha][Gen|Mod] steps keep script order with their arguments; `volume` first marks
// the shader's brushes as colorMod volumes; an unknown method warns and stays as a step that does nothing.
TEST(ShaderParser, ColorModStepsInScriptOrder) {
    using Kind = ShaderColorMod::Kind;
    const ShaderInfo si = parseOne(R"(x
{
    q3map_alphaMod volume
    q3map_alphaGen const 0.25
    q3map_rgbGen set ( 0.2 0.4 0.6 )
    q3map_colorMod scale ( 1 0.5 0.25 )
    q3map_alphaMod dotProduct2 ( 0 0 0.95 )
    q3map_rgbMod dotProductScale ( 1 0 0 -1 1 )
    q3map_alphaMod dotproduct2scale ( 0 1 0 0.25 1 )
}
)");
    ASSERT_EQ(si.colorMods.size(), 7u);
    EXPECT_TRUE(si.isColorModVolume());
    const std::vector<Kind> kinds = {Kind::Volume, Kind::AlphaSet, Kind::ColorSet, Kind::ColorScale,
                                     Kind::AlphaDotProduct2, Kind::ColorDotProductScale, Kind::AlphaDotProduct2Scale};
    for (size_t i = 0; i < kinds.size(); ++i) EXPECT_EQ(si.colorMods[i].kind, kinds[i]) << i;
    EXPECT_FLOAT_EQ(si.colorMods[1].value, 0.25f);
    EXPECT_FLOAT_EQ(si.colorMods[2].vector.y, 0.4f);
    EXPECT_FLOAT_EQ(si.colorMods[4].vector.z, 0.95f);
    EXPECT_FLOAT_EQ(si.colorMods[5].lo, -1);
    EXPECT_FLOAT_EQ(si.colorMods[6].lo, 0.25f);
    EXPECT_FLOAT_EQ(si.colorMods[6].hi, 1);
    EXPECT_FALSE(parseOne("y\n{\n q3map_alphaMod set 0\n q3map_alphaMod volume\n}\n").isColorModVolume());
    CapturedLog cap;
    parse("z\n{\n q3map_colorMod wobble\n}\n", cap);
    EXPECT_NE(cap.all().find("unknown q3map_colorMod method 'wobble'"), std::string::npos) << cap.all();
}

// q3map_foliage may appear several times; each keeps its model, scale, density, odds and alpha mode.
TEST(ShaderParser, FoliageDirectivesInScriptOrder) {
    const ShaderInfo si = parseOne(R"(x
{
    q3map_foliage models/mapobjects/grass.md3 0.75 32 0.1 1
    q3map_foliage models/mapobjects/rock.md3 2 128 0.02 2
}
)");
    ASSERT_EQ(si.foliage.size(), 2u);
    EXPECT_EQ(si.foliage[0].model, "models/mapobjects/grass.md3");
    EXPECT_FLOAT_EQ(si.foliage[0].scale, 0.75f);
    EXPECT_FLOAT_EQ(si.foliage[0].density, 32);
    EXPECT_FLOAT_EQ(si.foliage[0].odds, 0.1f);
    EXPECT_EQ(si.foliage[0].inverseAlpha, 1);
    EXPECT_EQ(si.foliage[1].model, "models/mapobjects/rock.md3");
    EXPECT_EQ(si.foliage[1].inverseAlpha, 2);
    EXPECT_TRUE(parseOne("y\n{\n}\n").foliage.empty());
}

TEST(ShaderParser, BaseShaderInheritsEarlierDefinition) {
    CapturedLog cap;
    auto shaders = parse(R"(base/light
{
    surfaceparm nomarks
    q3map_surfacelight 500
    q3map_lightRGB 1 0.5 0.5
}
derived/light
{
    q3map_baseShader base/light
    q3map_surfacelight 900
})",
                         cap);
    ASSERT_EQ(shaders.size(), 2u);
    const ShaderInfo& d = shaders[1];
    EXPECT_EQ(d.name, "derived/light");
    EXPECT_FLOAT_EQ(d.surfaceLight, 900);
    ASSERT_TRUE(d.lightRGB.has_value());
    expectVec(*d.lightRGB, {1, 0.5f, 0.5f});
    EXPECT_TRUE(d.surfaceFlags & surfaceflags::NoMarks);
    EXPECT_EQ(d.sourceLine, 7);
}

TEST(ShaderTable, CaseInsensitiveLookupAndImplicitShaders) {
    CapturedLog cap;
    ShaderTable table;
    for (ShaderInfo& s : parse("textures/Base/Light\n{\n q3map_surfacelight 300\n}\n", cap)) table.add(std::move(s));
    ASSERT_EQ(table.size(), 1u);
    const ShaderInfo* found = table.findExplicit("TEXTURES/base/light.tga");
    ASSERT_NE(found, nullptr);
    EXPECT_FLOAT_EQ(found->surfaceLight, 300);
    EXPECT_EQ(&table.find("textures/base/LIGHT"), found);

    EXPECT_EQ(table.findExplicit("textures/base/floor"), nullptr);
    const ShaderInfo& implicit = table.find("textures/Base/Floor.jpg");
    EXPECT_FALSE(implicit.explicitScript);
    EXPECT_EQ(implicit.name, "textures/base/floor");
    EXPECT_EQ(implicit.contentFlags, contents::Solid);
    EXPECT_EQ(implicit.surfaceFlags, 0u);
    EXPECT_EQ(implicit.compileFlags, compileflags::Solid);
    EXPECT_TRUE(implicit.suns.empty());
    EXPECT_FLOAT_EQ(implicit.surfaceLight, 0);
    EXPECT_EQ(implicit.lightImageCandidates(), std::vector<std::string>{"textures/base/floor"});
    // The same object every time, whatever the spelling.
    EXPECT_EQ(&table.find("TEXTURES/BASE/FLOOR"), &implicit);
    EXPECT_EQ(table.size(), 1u);
}

TEST(ShaderTable, ImplicitLookupsFromManyThreads) {
    ShaderTable table;
    std::vector<const ShaderInfo*> seen(8);
    std::vector<std::thread> threads;
    for (int t = 0; t < 8; ++t)
        threads.emplace_back([&, t] {
            for (int i = 0; i < 200; ++i) table.find("textures/t/" + std::to_string(i));
            seen[t] = &table.find("textures/t/7");
        });
    for (std::thread& th : threads) th.join();
    for (const ShaderInfo* p : seen) EXPECT_EQ(p, seen[0]);
}

TEST(ShaderTable, FirstDefinitionWins) {
    CapturedLog cap;
    ShaderTable table;
    auto first = parse("textures/x/y\n{\n q3map_surfacelight 100\n}\n", cap);
    auto second = parse("TEXTURES/X/Y\n{\n q3map_surfacelight 999\n}\ntextures/x/z\n{\n}\n", cap);
    for (ShaderInfo& s : first) EXPECT_TRUE(table.add(std::move(s)));
    EXPECT_FALSE(table.add(second[0]));
    EXPECT_TRUE(table.add(second[1]));
    EXPECT_EQ(table.duplicateCount(), 1);
    EXPECT_EQ(table.size(), 2u);
    EXPECT_FLOAT_EQ(table.find("textures/x/y").surfaceLight, 100);
}

TEST(ShaderTable, DeprecatedShadersLeadToTheirReplacement) {
    CapturedLog cap;
    ShaderTable table;
    auto shaders = parse(R"(old/light
{
    q3map_deprecateShader new/light
    q3map_surfacelight 1
}
new/light
{
    q3map_surfacelight 2
}
loop/a
{
    q3map_deprecateShader loop/a
}
gone/x
{
    q3map_deprecateShader gone/y.tga
})",
                         cap);
    for (ShaderInfo& s : shaders) table.add(std::move(s));
    EXPECT_EQ(table.find("old/light").name, "new/light");
    EXPECT_FLOAT_EQ(table.find("OLD/LIGHT").surfaceLight, 2);
    EXPECT_FLOAT_EQ(table.findExplicit("old/light")->surfaceLight, 1);
    EXPECT_EQ(table.find("loop/a").name, "loop/a");  // the chain is cut, no endless loop
    const ShaderInfo& gone = table.find("gone/x");
    EXPECT_FALSE(gone.explicitScript);
    EXPECT_EQ(gone.name, "gone/y");
}

TEST(ShaderKey, NormalisesCaseSlashesAndExtension) {
    EXPECT_EQ(shaderKey("Textures\\Base/Floor.TGA"), "textures/base/floor");
    EXPECT_EQ(shaderKey("textures/a.b/c"), "textures/a.b/c");
    EXPECT_EQ(shaderKey("noshader"), "noshader");
}

}  // namespace
}  // namespace q3
