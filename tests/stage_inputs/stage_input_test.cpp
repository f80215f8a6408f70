// A broken .map, a broken .shader and a corrupt pk3 beside a good map: `q3map2 -light` stops with
// one ERROR line naming the file, exits with 1 (no crash), and leaves the BSP untouched.
#include "file_io.h"
#include "test_data.h"
#include "zip_builder.h"

#include <gtest/gtest.h>

#include <sstream>

namespace q3 {
namespace {
namespace fs = std::filesystem;

struct Game {
    fs::path base;  // holds baseoa/
    fs::path bsp;
    std::vector<uint8_t> original;
};

Game makeGame(const std::string& mapText) {
    Game g;
    g.base = test::tempDir();
    fs::path maps = g.base / "baseoa" / "maps";
    fs::create_directories(maps);
    g.bsp = maps / "stage.bsp";
    fs::copy_file(test::realBsp("oacmpdm4"), g.bsp);
    writeFileAtomic(maps / "stage.map", mapText);
    g.original = readFileBytes(g.bsp);
    return g;
}

const char* kGoodMap = "{\n\"classname\" \"worldspawn\"\n}\n{\n\"classname\" \"light\"\n\"origin\" \"0 0 64\"\n}\n";

// Runs -light and returns the ERROR lines of its output.
std::vector<std::string> runLight(const Game& g, int& status) {
    std::string output;
    status = test::runCommand(test::q3map2Exe().string() + " -fs_basepath " + g.base.string() +
                                  " -fs_game baseoa -light -fast " + g.bsp.string(),
                              &output);
    std::vector<std::string> errors;
    std::istringstream lines(output);
    for (std::string line; std::getline(lines, line);)
        if (line.rfind("ERROR:", 0) == 0) errors.push_back(line);
    return errors;
}

void expectCleanFailure(const Game& g, const std::string& fragment) {
    int status = -1;
    std::vector<std::string> errors = runLight(g, status);
    EXPECT_EQ(status, 1);
    ASSERT_EQ(errors.size(), 1u);
    EXPECT_NE(errors[0].find(fragment), std::string::npos) << errors[0];
    EXPECT_EQ(readFileBytes(g.bsp), g.original);
}

TEST(StageInputs, BrokenMapFile) {
    Game g = makeGame("{\n\"classname\" \"worldspawn\"\n}\n{\n\"classname\" \"light\"\n\"origin\" \"0 0 64\"\n");
    expectCleanFailure(g, "stage.map:");
}

TEST(StageInputs, MapWithBrokenBrush) {
    Game g = makeGame("{\n\"classname\" \"worldspawn\"\n{\n( 0 0 0 ) ( 1 0 0 ) x y z\n}\n}\n");
    expectCleanFailure(g, "stage.map:4:");
}

TEST(StageInputs, BrokenShaderScript) {
    Game g = makeGame(kGoodMap);
    test::writeLoose(g.base / "baseoa" / "scripts" / "broken.shader",
                     "textures/test/ok\n{\n surfaceparm nomarks\n}\n}\ntextures/test/after\n{\n}\n");
    expectCleanFailure(g, "broken.shader:5:");
}

TEST(StageInputs, ShaderScriptWithUnterminatedString) {
    Game g = makeGame(kGoodMap);
    test::writeLoose(g.base / "baseoa" / "scripts" / "quote.shader", "textures/test/q\n{\n qer_editorimage \"abc\n}\n");
    expectCleanFailure(g, "quote.shader:");
}

TEST(StageInputs, CorruptPk3Entry) {
    Game g = makeGame(kGoodMap);
    fs::path pk3 = g.base / "baseoa" / "zz_broken.pk3";
    std::string script;
    for (int i = 0; i < 400; ++i) script += "textures/test/s" + std::to_string(i) + "\n{\n surfaceparm nomarks\n}\n";
    test::writeZip(pk3, {{"scripts/damaged.shader", script}});
    // Damage the compressed data in the middle of the archive (the local header stays readable).
    std::vector<uint8_t> bytes = readFileBytes(pk3);
    ASSERT_GT(bytes.size(), 200u);
    for (size_t i = 80; i < 120; ++i) bytes[i] ^= 0x5a;
    writeFileAtomic(pk3, bytes);
    expectCleanFailure(g, "zz_broken.pk3");
}

TEST(StageInputs, ArchiveThatIsNotAZipIsSkippedWithAWarningAndFailsUnderWerror) {
    Game g = makeGame(kGoodMap);
    writeFileAtomic(g.base / "baseoa" / "zz_notzip.pk3", std::string("this is not a zip archive"));
    std::string output;
    int status = test::runCommand(test::q3map2Exe().string() + " -werror -fs_basepath " + g.base.string() +
                                      " -fs_game baseoa -light -fast -nolm -nogrid " + g.bsp.string(),
                                  &output);
    EXPECT_EQ(status, 1) << output;
    EXPECT_NE(output.find("zz_notzip.pk3"), std::string::npos) << output;
    EXPECT_NE(output.find("with -werror"), std::string::npos) << output;
}

}  // namespace
}  // namespace q3
