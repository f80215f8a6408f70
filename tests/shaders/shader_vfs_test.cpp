// The shader table of a whole game tree, read through the VFS: the real OpenArena packages, and a
// small game folder with a shaderlist.txt that leaves files out.
#include <gtest/gtest.h>


#include "bspfile.h"
#include "file_io.h"
#include "script.h"
#include "shader_loader.h"
#include "shader_test_util.h"
#include "test_data.h"
#include "vfs.h"

namespace q3 {
namespace {

using test::CapturedLog;

Vfs openArenaVfs(Log& log) {
    VfsOptions options;
    options.basePaths = {test::openArenaBase()};
    options.baseGame = "baseoa";
    return Vfs(options, log);
}

TEST(VfsShaders, LoadsEveryScriptOfTheOpenArenaPackages) {
    CapturedLog cap;
    Vfs vfs = openArenaVfs(cap.log);
    std::vector<std::string> files = vfs.list("scripts", "shader");
    ShaderTable table = loadShaderTable(vfs, cap.log);
    // pak0.pk3 ships a shaderlist.txt naming 21 files (one of them missing); every file is loaded.
    EXPECT_TRUE(table.hasShaderList());
    EXPECT_GE(files.size(), 100u);
    ASSERT_EQ(table.files().size(), files.size());
    std::string all = cap.all();
    EXPECT_NE(all.find("shaderlist.txt names scripts/quark.shader, which does not exist"), std::string::npos) << all;
    int definitions = 0;
    for (const auto& f : table.files()) definitions += f.shaderCount;
    EXPECT_EQ(definitions, static_cast<int>(table.size()) + table.duplicateCount());
    EXPECT_GT(table.size(), 1000u);

    const ShaderInfo& sky = table.find("textures/clown/dark_sky");
    ASSERT_TRUE(sky.explicitScript);
    EXPECT_EQ(sky.sourceFile, "scripts/clown.shader");
    ASSERT_EQ(sky.suns.size(), 1u);
    EXPECT_FLOAT_EQ(sky.suns[0].intensity, 50);

    const ShaderInfo& light = table.find("textures/base_light/baslt4_1_2k");
    EXPECT_FLOAT_EQ(light.surfaceLight, 2000);

    const ShaderInfo& plain = table.find("textures/base_wall/no_such_script");
    EXPECT_FALSE(plain.explicitScript);
    EXPECT_EQ(plain.contentFlags, contents::Solid);
}

// q3map2 obeys pak0's shader list and so loses the community maps' own scripts: oacmpctf1's sky
// would stop being a sky. Here the sky keeps its script, and the omission is reported.
TEST(VfsShaders, UnlistedScriptsOfARealMapAreLoadedAndReported) {
    CapturedLog cap;
    Vfs vfs = openArenaVfs(cap.log);
    ShaderTable table = loadShaderTable(vfs, cap.log);
    bsp::Bsp map = bsp::readBsp(test::realBsp("oacmpctf1"));
    std::vector<std::string> used;
    for (const bsp::Shader& s : map.shaders) used.emplace_back(s.name);

    const ShaderInfo& sky = table.find("textures/oajg_sky/ctf1");
    ASSERT_TRUE(sky.explicitScript);
    EXPECT_EQ(sky.sourceFile, "scripts/oajgctf1.shader");
    EXPECT_TRUE(sky.isSky());
    ASSERT_EQ(sky.skyLights.size(), 1u);
    EXPECT_FLOAT_EQ(sky.skyLights[0].value, 180);
    EXPECT_EQ(sky.skyLights[0].iterations, 8);

    CapturedLog warned;
    int warnings = warnShadersOutsideShaderList(table, used, warned.log);
    EXPECT_GE(warnings, 1);
    EXPECT_EQ(static_cast<size_t>(warnings), warned.warnings.size());
    std::string all = warned.all();
    EXPECT_NE(all.find("scripts/oajgctf1.shader"), std::string::npos) << all;
    EXPECT_NE(all.find("textures/oajg_sky/ctf1"), std::string::npos) << all;
}

void writeText(const std::filesystem::path& path, const std::string& text) {
    std::filesystem::create_directories(path.parent_path());
    writeFileAtomic(path, text);
}

TEST(VfsShaders, ShaderListLeavingOutAFileIsReported) {
    const auto root = test::tempDir();
    const auto game = root / "baseq3" / "scripts";
    writeText(game / "shaderlist.txt", "base_wall\n");
    writeText(game / "base_wall.shader", "textures/base_wall/a\n{\n surfaceparm nomarks\n}\n");
    writeText(game / "skies.shader", "textures/skies/blue\n{\n q3map_sun 1 1 1 120 30 60\n}\n");
    writeText(game / "zz_extra.shader", "textures/base_wall/a\n{\n q3map_surfacelight 5\n}\n");

    CapturedLog cap;
    VfsOptions options;
    options.basePaths = {root};
    Vfs vfs(options, cap.log);
    ShaderTable table = loadShaderTable(vfs, cap.log);
    EXPECT_TRUE(cap.warnings.empty()) << cap.all();
    EXPECT_TRUE(table.hasShaderList());
    ASSERT_EQ(cap.infos.size(), 2u);
    EXPECT_EQ(cap.infos[0], "scripts/shaderlist.txt names 1 of 3 shader files; all of them are loaded\n");
    EXPECT_EQ(cap.infos[1], "3 shader files, 2 shaders (1 duplicate definitions ignored)\n");
    ASSERT_EQ(table.files().size(), 3u);
    EXPECT_EQ(table.files()[0].path, "scripts/base_wall.shader");
    EXPECT_TRUE(table.files()[0].inShaderList);
    EXPECT_FALSE(table.files()[1].inShaderList);
    // Unlisted scripts are still loaded; the listed definition of a duplicate wins.
    EXPECT_EQ(table.find("textures/skies/blue").suns.size(), 1u);
    EXPECT_FLOAT_EQ(table.find("textures/base_wall/a").surfaceLight, 0);

    std::vector<std::string> used = {"textures/base_wall/a", "textures/skies/blue"};
    CapturedLog report;
    EXPECT_EQ(warnShadersOutsideShaderList(table, used, report.log), 1);
    ASSERT_EQ(report.warnings.size(), 1u);
    EXPECT_NE(report.warnings[0].find("scripts/skies.shader is not named in scripts/shaderlist.txt"),
              std::string::npos)
        << report.warnings[0];
}

TEST(VfsShaders, MalformedScriptErrorNamesTheFile) {
    const auto root = test::tempDir();
    writeText(root / "baseq3" / "scripts" / "broken.shader", "textures/a/b\n{\n q3map_sun 1 1\n}\n");
    CapturedLog cap;
    VfsOptions options;
    options.basePaths = {root};
    Vfs vfs(options, cap.log);
    try {
        loadShaderTable(vfs, cap.log);
        FAIL() << "no error";
    } catch (const ScriptError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("broken.shader:3: missing argument for 'q3map_sun' in shader 'textures/a/b'"),
                  std::string::npos)
            << what;
    }
}

}  // namespace
}  // namespace q3
