// shaderlist.txt handling: every script is loaded, listed files first, and a map depending on a
// file the list leaves out is reported.
#include <gtest/gtest.h>

#include "script.h"
#include "shader_loader.h"
#include "shader_test_util.h"

namespace q3 {
namespace {

using test::CapturedLog;

TEST(ShaderList, ParsesNamesAddsExtensionAndDropsDuplicates) {
    auto names = parseShaderList("base_light\nsky.shader // comment\nBASE_LIGHT\n  gothic  ", "scripts/shaderlist.txt");
    EXPECT_EQ(names, (std::vector<std::string>{"scripts/base_light.shader", "scripts/sky.shader",
                                               "scripts/gothic.shader"}));
}

TEST(ShaderList, LoadOrderPutsListedFilesFirst) {
    CapturedLog cap;
    std::vector<std::string> available = {"scripts/a.shader", "scripts/b.shader", "scripts/c.shader",
                                          "scripts/d.shader"};
    auto order = shaderScriptLoadOrder(available, {"scripts/C.shader", "scripts/missing.shader", "scripts/a.shader"},
                                       cap.log);
    EXPECT_EQ(order, (std::vector<std::string>{"scripts/c.shader", "scripts/a.shader", "scripts/b.shader",
                                               "scripts/d.shader"}));
    ASSERT_EQ(cap.warnings.size(), 1u);
    EXPECT_EQ(cap.warnings[0], "WARNING: shaderlist.txt names scripts/missing.shader, which does not exist\n");
}

// The OpenArena situation: the list names some files only, the map uses shaders from others.
TEST(ShaderList, WarnsForUnlistedFilesDefiningUsedShaders) {
    std::vector<ShaderScriptSource> scripts = {
        {"scripts/listed.shader", "pak0.pk3:scripts/listed.shader",
         "textures/l/one\n{\n surfaceparm nomarks\n}\ntextures/shared/x\n{\n q3map_surfacelight 1\n}\n"},
        {"scripts/unlisted_sky.shader", "pak0.pk3:scripts/unlisted_sky.shader",
         "textures/skies/s\n{\n q3map_sun 1 1 1 100 0 45\n}\ntextures/skies/t\n{\n surfaceparm sky\n}\n"},
        {"scripts/unlisted_other.shader", "pak0.pk3:scripts/unlisted_other.shader",
         "textures/o/unused\n{\n}\ntextures/shared/x\n{\n q3map_surfacelight 2\n}\n"},
    };
    CapturedLog cap;
    ShaderTable table = buildShaderTable(scripts, {"scripts/listed.shader"}, true, cap.log);
    EXPECT_TRUE(cap.warnings.empty()) << cap.all();
    ASSERT_EQ(table.files().size(), 3u);
    EXPECT_TRUE(table.files()[0].inShaderList);
    EXPECT_FALSE(table.files()[1].inShaderList);
    EXPECT_EQ(table.files()[1].shaderCount, 2);
    // Unlisted files are loaded all the same.
    EXPECT_EQ(table.size(), 5u);
    EXPECT_EQ(table.find("textures/skies/s").suns.size(), 1u);
    EXPECT_EQ(table.find("textures/skies/s").sourceFile, "scripts/unlisted_sky.shader");
    // The listed file's definition of the shared name wins.
    EXPECT_FLOAT_EQ(table.find("textures/shared/x").surfaceLight, 1);

    std::vector<std::string> used = {"textures/l/one", "textures/skies/t", "textures/skies/S",
                                     "textures/shared/x", "textures/no/script", "textures/skies/s"};
    CapturedLog report;
    EXPECT_EQ(warnShadersOutsideShaderList(table, used, report.log), 1);
    ASSERT_EQ(report.warnings.size(), 1u);
    EXPECT_EQ(report.warnings[0],
              "WARNING: scripts/unlisted_sky.shader is not named in scripts/shaderlist.txt but defines 2 shader(s) "
              "this map uses (textures/skies/t, ...); loaded anyway, q3map2 would ignore it\n");

    // Nothing to report when the map only uses listed or script-less shaders.
    CapturedLog quiet;
    std::vector<std::string> listedOnly = {"textures/l/one", "textures/no/script"};
    EXPECT_EQ(warnShadersOutsideShaderList(table, listedOnly, quiet.log), 0);
    EXPECT_TRUE(quiet.warnings.empty());
}

TEST(ShaderList, NoWarningWithoutAShaderList) {
    std::vector<ShaderScriptSource> scripts = {{"scripts/a.shader", "scripts/a.shader", "textures/a/b\n{\n}\n"}};
    CapturedLog cap;
    ShaderTable table = buildShaderTable(scripts, {}, false, cap.log);
    std::vector<std::string> used = {"textures/a/b"};
    EXPECT_EQ(warnShadersOutsideShaderList(table, used, cap.log), 0);
    EXPECT_TRUE(cap.warnings.empty());
}

// Scripts are parsed side by side: a q3map_baseShader naming a shader of an earlier file still
// finds it, the table keeps file order, and each file's warnings come out in file order.
TEST(ShaderList, ScriptsParsedTogetherKeepFileOrder) {
    std::vector<ShaderScriptSource> scripts;
    for (int i = 0; i < 24; ++i) {
        const std::string n = std::to_string(i);
        scripts.push_back({"scripts/f" + n + ".shader", "scripts/f" + n + ".shader",
                           "textures/f/s" + n + "\n{\n q3map_surfacelight " + n + "\n q3map_lightRGB 1 x 1\n}\n"});
    }
    scripts.push_back({"scripts/derived.shader", "scripts/derived.shader",
                       "textures/d/lamp\n{\n Q3MAP_BASESHADER textures/f/s7\n q3map_backsplash 3 9\n}\n"});
    scripts.push_back({"scripts/late.shader", "scripts/late.shader", "textures/f/s3\n{\n q3map_surfacelight 99\n}\n"});
    CapturedLog cap;
    ShaderTable table = buildShaderTable(scripts, {}, false, cap.log);
    ASSERT_EQ(table.files().size(), scripts.size());
    for (size_t i = 0; i < scripts.size(); ++i) EXPECT_EQ(table.files()[i].path, scripts[i].path);
    EXPECT_FLOAT_EQ(table.find("textures/d/lamp").surfaceLight, 7);  // from the earlier file's s7
    EXPECT_FLOAT_EQ(table.find("textures/f/s3").surfaceLight, 3);     // the first definition wins
    ASSERT_EQ(cap.warnings.size(), 24u) << cap.all();
    for (size_t i = 0; i < 24; ++i)
        EXPECT_NE(cap.warnings[i].find("scripts/f" + std::to_string(i) + ".shader:"), std::string::npos)
            << cap.warnings[i];
}

// A fatal error stops the table at its file, after the messages of the files before it, as a
// sequential parse would.
TEST(ShaderList, FatalScriptErrorStopsAtItsFile) {
    std::vector<ShaderScriptSource> scripts = {
        {"scripts/a.shader", "scripts/a.shader", "textures/a/a\n{\n q3map_lightRGB 1 x 1\n}\n"},
        {"scripts/b.shader", "scripts/b.shader", "textures/b/b\n  surfaceparm nodraw\n}\n"},
        {"scripts/c.shader", "scripts/c.shader", "textures/c/c\n{\n q3map_lightRGB 1 y 1\n}\n"},
    };
    CapturedLog cap;
    EXPECT_THROW(buildShaderTable(scripts, {}, false, cap.log), ScriptError);
    ASSERT_EQ(cap.warnings.size(), 1u) << cap.all();
    EXPECT_NE(cap.warnings[0].find("scripts/a.shader:"), std::string::npos);
}

}  // namespace
}  // namespace q3
