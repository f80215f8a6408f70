// Malformed scripts: fatal ones throw one line naming file:line, tolerated ones warn (file:line)
// and keep going the way q3map2 and the engines do.
#include <gtest/gtest.h>

#include <random>

#include "script.h"
#include "shader_parser.h"
#include "shader_test_util.h"

namespace q3 {
namespace {

using test::CapturedLog;

struct FatalCase {
    const char* label;
    const char* text;
    const char* message;  // the whole exception text
};

class FatalScript : public ::testing::TestWithParam<FatalCase> {};

TEST_P(FatalScript, ThrowsOneLineNamingFileAndLine) {
    const FatalCase& c = GetParam();
    CapturedLog cap;
    try {
        parseShaderScript(c.text, "scripts/bad.shader", cap.log);
        FAIL() << "no error for " << c.label;
    } catch (const ScriptError& e) {
        EXPECT_EQ(std::string(e.what()), c.message);
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    }
}

INSTANTIATE_TEST_SUITE_P(
    Shaders, FatalScript,
    ::testing::Values(
        FatalCase{"missing_open_brace", "textures/a/b\n  surfaceparm nodraw\n}\n",
                  "scripts/bad.shader:2: shader 'textures/a/b': expected '{' after the shader name, found "
                  "'surfaceparm'"},
        FatalCase{"name_at_end_of_file", "textures/a/b { }\ntextures/a/c\n",
                  "scripts/bad.shader:2: shader 'textures/a/c' has no body: expected '{' after its name"},
        FatalCase{"stray_closing_brace", "textures/a/b\n{\n}\n}\n",
                  "scripts/bad.shader:4: expected a shader name, found '}'"},
        FatalCase{"stray_opening_brace", "{\n}\n", "scripts/bad.shader:1: expected a shader name, found '{'"},
        FatalCase{"unterminated_string", "textures/a/b\n{\n qer_editorImage \"textures/a/b.tga\n}\n",
                  "scripts/bad.shader:3: unterminated quoted string"},
        FatalCase{"sun_missing_arguments", "sky\n{\n q3map_sun 1 1 1 100 45\n}\n",
                  "scripts/bad.shader:3: missing argument for 'q3map_sun' in shader 'sky'"},
        FatalCase{"surfacelight_missing_value", "light\n{\n\n q3map_surfacelight\n}\n",
                  "scripts/bad.shader:4: missing argument for 'q3map_surfacelight' in shader 'light'"},
        FatalCase{"surfaceparm_missing_name", "x\n{\n surfaceparm // nothing\n}\n",
                  "scripts/bad.shader:3: missing argument for 'surfaceparm' in shader 'x'"},
        FatalCase{"skyparms_short", "x\n{\n skyParms env/a 512\n}\n",
                  "scripts/bad.shader:3: missing argument for 'skyParms' in shader 'x'"},
        FatalCase{"stage_map_without_image", "x\n{\n {\n  map\n }\n}\n",
                  "scripts/bad.shader:4: missing argument for 'map' in shader 'x'"},
        FatalCase{"lightrgb_short", "x\n{\n q3map_lightRGB 1 0.5\n}\n",
                  "scripts/bad.shader:3: missing argument for 'q3map_lightRGB' in shader 'x'"}),
    [](const ::testing::TestParamInfo<FatalCase>& info) { return std::string(info.param.label); });

TEST(TolerantScript, UnclosedShaderAtEndOfFileIsDroppedWithWarning) {
    CapturedLog cap;
    auto shaders = parseShaderScript("good\n{\n}\nbad\n{\n surfaceparm sky\n", "scripts/t.shader", cap.log);
    ASSERT_EQ(shaders.size(), 1u);
    EXPECT_EQ(shaders[0].name, "good");
    ASSERT_EQ(cap.warnings.size(), 1u);
    EXPECT_EQ(cap.warnings[0],
              "WARNING: scripts/t.shader:6: end of file inside the body of shader 'bad' (line 4): missing '}', "
              "shader ignored\n");
}

TEST(TolerantScript, UnclosedStageAtEndOfFileIsDroppedWithWarning) {
    CapturedLog cap;
    auto shaders = parseShaderScript("bad\n{\n {\n map x.tga\n", "scripts/t.shader", cap.log);
    EXPECT_TRUE(shaders.empty());
    ASSERT_EQ(cap.warnings.size(), 1u);
    EXPECT_NE(cap.warnings[0].find("scripts/t.shader:4: end of file inside a stage of shader 'bad' (line 1)"),
              std::string::npos)
        << cap.warnings[0];
}

TEST(TolerantScript, BadNumbersReadLikeAtofWithWarning) {
    CapturedLog cap;
    auto shaders = parseShaderScript("x\n{\n q3map_surfacelight 100x\n q3map_lightSubdivide abc\n}\n",
                                     "scripts/t.shader", cap.log);
    ASSERT_EQ(shaders.size(), 1u);
    EXPECT_FLOAT_EQ(shaders[0].surfaceLight, 100);
    EXPECT_EQ(shaders[0].lightSubdivide, 0);
    ASSERT_EQ(cap.warnings.size(), 2u);
    EXPECT_EQ(cap.warnings[0],
              "WARNING: scripts/t.shader:3: shader 'x': bad number '100x' for 'q3map_surfacelight', read as "
              "100.000000\n");
    EXPECT_NE(cap.warnings[1].find("scripts/t.shader:4: shader 'x': bad number 'abc' for 'q3map_lightSubdivide'"),
              std::string::npos);
}

TEST(TolerantScript, UnknownSurfaceparmAndDirectiveWarn) {
    CapturedLog cap;
    auto shaders = parseShaderScript("x\n{\n surfaceparm shiny\n q3map_sparkles 3\n surfaceparm nomarks\n}\n",
                                     "scripts/t.shader", cap.log);
    ASSERT_EQ(shaders.size(), 1u);
    EXPECT_EQ(shaders[0].surfaceFlags, 0x20u);  // the known parm still applies
    ASSERT_EQ(cap.warnings.size(), 2u);
    EXPECT_EQ(cap.warnings[0], "WARNING: scripts/t.shader:3: shader 'x': unknown surfaceparm 'shiny'\n");
    EXPECT_EQ(cap.warnings[1], "WARNING: scripts/t.shader:4: shader 'x': unknown directive 'q3map_sparkles'\n");
}

TEST(TolerantScript, BadLightmapAxisAndSizeWarn) {
    CapturedLog cap;
    auto shaders = parseShaderScript("x\n{\n q3map_lightmapAxis w\n q3map_lightmapSize 100 128\n}\n",
                                     "scripts/t.shader", cap.log);
    ASSERT_EQ(shaders.size(), 1u);
    EXPECT_EQ(shaders[0].lightmapAxis, -1);
    EXPECT_EQ(shaders[0].lightmapWidth, 0);
    ASSERT_EQ(cap.warnings.size(), 2u);
    EXPECT_EQ(cap.warnings[0], "WARNING: scripts/t.shader:3: shader 'x': unknown lightmap axis 'w'\n");
    EXPECT_NE(cap.warnings[1].find("scripts/t.shader:4: shader 'x': lightmap size 100x128 is not a power of two"),
              std::string::npos);
}

TEST(TolerantScript, RestOfDirectiveLineIgnored) {
    CapturedLog cap;
    auto shaders = parseShaderScript("x\n{\n q3map_surfacelight 50 extra tokens here\n surfaceparm trans junk\n}\n",
                                     "scripts/t.shader", cap.log);
    ASSERT_EQ(shaders.size(), 1u);
    EXPECT_FLOAT_EQ(shaders[0].surfaceLight, 50);
    EXPECT_TRUE(shaders[0].isTranslucent());
    EXPECT_TRUE(cap.warnings.empty());
}

TEST(TolerantScript, EmptyAndCommentOnlyFiles) {
    CapturedLog cap;
    EXPECT_TRUE(parseShaderScript("", "scripts/e.shader", cap.log).empty());
    EXPECT_TRUE(parseShaderScript("// nothing\n/* at all */\n", "scripts/e.shader", cap.log).empty());
    EXPECT_TRUE(cap.warnings.empty());
}

// Scrambled scripts made of real shader vocabulary either parse or fail with a ScriptError;
// nothing else escapes (no crash, no other exception type).
TEST(TolerantScript, ScrambledScriptsFailCleanly) {
    const char* pieces[] = {"{", "}", "\n", " ", "textures/a/b", "q3map_sun", "1", "-2.5", "x1", "\"", "//",
                            "/*", "*/", "surfaceparm", "sky", "map", "animMap", "$lightmap", "skyParms",
                            "q3map_skyLight", "q3map_lightmapSize", "q3map_baseShader", "q3map_deprecateShader",
                            "q3map_sunExt", "(", ")", "q3map_floodLight", "cull", ":q3map", "\t"};
    std::mt19937 rng(1234);
    std::uniform_int_distribution<size_t> pick(0, std::size(pieces) - 1);
    std::uniform_int_distribution<int> length(0, 60);
    int parsed = 0, failed = 0;
    for (int i = 0; i < 3000; ++i) {
        std::string text;
        for (int n = length(rng); n > 0; --n) {
            std::string piece = pieces[pick(rng)];
            text += piece + ((rng() & 3) ? " " : "");
        }
        CapturedLog cap;
        try {
            parseShaderScript(text, "scripts/fuzz.shader", cap.log);
            ++parsed;
        } catch (const ScriptError& e) {
            EXPECT_EQ(std::string(e.what()).rfind("scripts/fuzz.shader:", 0), 0u) << e.what();
            ++failed;
        }
    }
    EXPECT_GT(parsed, 0);
    EXPECT_GT(failed, 0);
}

}  // namespace
}  // namespace q3
