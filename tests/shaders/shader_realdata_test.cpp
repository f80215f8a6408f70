// Every shader script shipped with the OpenArena test data parses, and known shaders carry the
// values their scripts give.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "file_io.h"
#include "shader_loader.h"
#include "shader_math.h"
#include "shader_parser.h"
#include "shader_test_util.h"
#include "test_data.h"

namespace q3 {
namespace {

using test::CapturedLog;

// All unpacked scripts as loader sources, named by their path below the cache.
std::vector<ShaderScriptSource> realScripts() {
    std::vector<ShaderScriptSource> out;
    const auto root = test::dataCache() / "loose";
    for (const auto& path : test::allShaderScripts()) {
        ShaderScriptSource s;
        s.path = std::filesystem::relative(path, root).generic_string();
        s.displayName = s.path;
        s.text = readFileText(path);
        out.push_back(std::move(s));
    }
    return out;
}

// Shader definitions counted independently of the parser: blocks opened at brace depth 0, with
// comments and quoted strings skipped.
size_t countTopLevelBlocks(const std::string& text) {
    size_t count = 0;
    int depth = 0;
    for (size_t i = 0; i < text.size(); ++i) {
        char c = text[i];
        if (c == '/' && i + 1 < text.size() && text[i + 1] == '/') {
            while (i < text.size() && text[i] != '\n') ++i;
        } else if (c == '/' && i + 1 < text.size() && text[i + 1] == '*') {
            size_t end = text.find("*/", i + 2);
            i = end == std::string::npos ? text.size() : end + 1;
        } else if (c == '"') {
            size_t end = text.find('"', i + 1);
            i = end == std::string::npos ? text.size() : end;
        } else if (c == '{') {
            if (depth++ == 0) ++count;
        } else if (c == '}') {
            --depth;
        }
    }
    return count;
}

size_t countAllBlocks(const std::vector<ShaderScriptSource>& scripts) {
    size_t n = 0;
    for (const ShaderScriptSource& s : scripts) n += countTopLevelBlocks(s.text);
    return n;
}

TEST(RealShaders, EveryScriptParses) {
    std::vector<ShaderScriptSource> scripts = realScripts();
    ASSERT_GE(scripts.size(), 150u);
    CapturedLog cap;
    size_t definitions = 0;
    for (const ShaderScriptSource& s : scripts) {
        std::vector<ShaderInfo> shaders;
        ASSERT_NO_THROW(shaders = parseShaderScript(s.text, s.displayName, cap.log)) << s.path;
        EXPECT_FALSE(shaders.empty()) << s.path;
        definitions += shaders.size();
    }
    EXPECT_EQ(definitions, countAllBlocks(scripts));
    // The one questionable line in the data: pak0's clown2.shader gives q3map_surfacelight a texture
    // name instead of a number, which q3map2 reads as 0.
    ASSERT_EQ(cap.warnings.size(), 1u) << cap.all();
    EXPECT_NE(cap.warnings[0].find("clown2.shader:168"), std::string::npos) << cap.all();
    EXPECT_NE(cap.warnings[0].find("q3map_surfacelight"), std::string::npos) << cap.all();
}

TEST(RealShaders, TableKeepsFirstOfDuplicateDefinitions) {
    CapturedLog cap;
    std::vector<ShaderScriptSource> scripts = realScripts();
    ShaderTable table = buildShaderTable(scripts, {}, false, cap.log);
    EXPECT_EQ(table.files().size(), scripts.size());
    EXPECT_EQ(table.size() + static_cast<size_t>(table.duplicateCount()), countAllBlocks(scripts));
    EXPECT_GT(table.duplicateCount(), 0);  // the two patch packages repeat many files
    // Sorted paths put pak6-patch085 before pak6-patch088: its definition is the one kept.
    const ShaderInfo* sky = table.findExplicit("textures/cosmo_skies/desertsky1");
    ASSERT_NE(sky, nullptr);
    EXPECT_EQ(sky->sourceFile, "pak6-patch085/scripts/am_cosmoflash.shader");
}

const ShaderInfo& findIn(const std::vector<ShaderInfo>& shaders, std::string_view name) {
    auto it = std::find_if(shaders.begin(), shaders.end(), [&](const ShaderInfo& s) { return s.name == name; });
    if (it == shaders.end()) throw std::runtime_error("no shader " + std::string(name));
    return *it;
}

std::vector<ShaderInfo> parseRealFile(const std::string& relative) {
    CapturedLog cap;
    auto path = test::dataCache() / "loose" / relative;
    auto shaders = parseShaderScript(readFileText(path), relative, cap.log);
    EXPECT_TRUE(cap.warnings.empty()) << cap.all();
    return shaders;
}

TEST(RealShaders, ClownDarkSkySun) {
    auto shaders = parseRealFile("pak6-patch088/scripts/clown.shader");
    const ShaderInfo& s = findIn(shaders, "textures/clown/dark_sky");
    // surfaceparm noimpact, nolightmap, sky; q3map_lightimage textures/clown/dark_sky.tga;
    // q3map_sun .5 .1 .1 50 65 35; q3map_surfacelight 100; skyparms - 1024 -
    ASSERT_EQ(s.suns.size(), 1u);
    const ShaderSun& sun = s.suns[0];
    EXPECT_NEAR(sun.color.x, 1.0f, 1e-6f);
    EXPECT_NEAR(sun.color.y, 0.2f, 1e-6f);
    EXPECT_NEAR(sun.color.z, 0.2f, 1e-6f);
    EXPECT_FLOAT_EQ(sun.intensity, 50);
    const double yaw = 65 * kPiD / 180, elev = 35 * kPiD / 180;
    EXPECT_NEAR(sun.direction.x, std::cos(yaw) * std::cos(elev), 1e-6);
    EXPECT_NEAR(sun.direction.y, std::sin(yaw) * std::cos(elev), 1e-6);
    EXPECT_NEAR(sun.direction.z, std::sin(elev), 1e-6);
    EXPECT_EQ(sun.samples, 1);
    EXPECT_FLOAT_EQ(s.surfaceLight, 100);
    EXPECT_TRUE(s.isSky());
    EXPECT_TRUE(s.isVertexLit());
    EXPECT_EQ(s.surfaceFlags, surfaceflags::Sky | surfaceflags::NoImpact | surfaceflags::VertexLit);
    EXPECT_EQ(s.contentFlags, contents::Solid);
    EXPECT_EQ(s.lightImage, "textures/clown/dark_sky.tga");
    EXPECT_EQ(s.skyParmsEnv, "");
    EXPECT_EQ(s.firstStageImage, "textures/clown/dark_sky.tga");
}

TEST(RealShaders, DesertFactorySunExtAndSkyParms) {
    auto shaders = parseRealFile("pak6-patch088/scripts/desertfactory.shader");
    const ShaderInfo& s = findIn(shaders, "textures/desertfactory_shaders/sky");
    // skyparms env/desert/desert - -; q3map_sunExt 1 0.95 0.9 400 315 50 0 16
    ASSERT_EQ(s.suns.size(), 1u);
    EXPECT_FLOAT_EQ(s.suns[0].intensity, 400);
    EXPECT_FLOAT_EQ(s.suns[0].yawDegrees, 315);
    EXPECT_FLOAT_EQ(s.suns[0].elevationDegrees, 50);
    EXPECT_FLOAT_EQ(s.suns[0].devianceDegrees, 0);
    EXPECT_EQ(s.suns[0].samples, 16);
    EXPECT_NEAR(s.suns[0].color.y, 0.95f, 1e-6f);
    EXPECT_EQ(s.skyParmsEnv, "env/desert/desert");
    EXPECT_EQ(s.lightImage, "env/desert/desert_up");
    EXPECT_EQ(s.editorImage, "textures/desertfactory_shaders/sky.jpg");
    EXPECT_FALSE(s.hasStages);
}

TEST(RealShaders, BaseLightSurfaceLight) {
    auto shaders = parseRealFile("pak6-patch085/scripts/base_light.shader");
    const ShaderInfo& s = findIn(shaders, "textures/base_light/baslt4_1_2k");
    // qer_editorimage textures/base_light/baslt4_1.jpg;
    // q3map_lightimage textures/base_light/baslt4_1.blend.jpg; surfaceparm nomarks;
    // q3map_surfacelight 2000
    EXPECT_FLOAT_EQ(s.surfaceLight, 2000);
    EXPECT_EQ(s.surfaceFlags, surfaceflags::NoMarks);
    EXPECT_EQ(s.lightImage, "textures/base_light/baslt4_1.blend.jpg");
    EXPECT_EQ(s.editorImage, "textures/base_light/baslt4_1.jpg");
    EXPECT_EQ(s.firstStageImage, "textures/base_light/baslt4_1.jpg");
    EXPECT_FALSE(s.lightRGB.has_value());
    EXPECT_EQ(s.lightImageCandidates(),
              (std::vector<std::string>{"textures/base_light/baslt4_1.blend.jpg", "textures/base_light/baslt4_1.jpg",
                                        "textures/base_light/baslt4_1_2k"}));
    EXPECT_TRUE(s.explicitScript);
    EXPECT_EQ(s.sourceLine, 2);
}

TEST(RealShaders, BraceGluedToShaderName) {
    // "models/mapobjects/cosmoflash/teleporter3{" on one line, then five stages.
    auto shaders = parseRealFile("pak6-patch085/scripts/am_cf_models.shader");
    const ShaderInfo& s = findIn(shaders, "models/mapobjects/cosmoflash/teleporter3");
    EXPECT_TRUE(s.hasStages);
    EXPECT_EQ(s.firstStageImage, "textures/cosmo_sfx/pulse.jpg");
    EXPECT_EQ(s.sourceLine, 3);
    const ShaderInfo& torch = findIn(shaders, "models/mapobjects/cosmoflash/torch1");
    EXPECT_EQ(torch.firstStageImage, "models/mapobjects/cosmoflash/torch1.tga");
}

TEST(RealShaders, CountsOfLightingDirectives) {
    CapturedLog cap;
    ShaderTable table = buildShaderTable(realScripts(), {}, false, cap.log);
    int suns = 0, surfaceLights = 0, skies = 0, alphaShadows = 0;
    for (const auto& s : table.shaders()) {
        suns += static_cast<int>(s->suns.size());
        surfaceLights += s->surfaceLight > 0;
        skies += s->isSky();
        alphaShadows += s->isAlphaShadow();
    }
    EXPECT_GT(suns, 0);
    EXPECT_GT(surfaceLights, 100);
    EXPECT_GT(skies, 5);
    EXPECT_GT(alphaShadows, 5);
}

}  // namespace
}  // namespace q3
