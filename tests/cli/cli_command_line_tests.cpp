// The whole command line: common options, the stage switch, the map path.
#include "common_option_table.h"
#include "cli_test_support.h"

#include <gtest/gtest.h>

namespace q3::test {
namespace {

using Args = std::vector<std::string>;

std::string splitError(const Args& args) {
    return usageErrorOf([&] { split(args); });
}

TEST(CliCommandLine, CommonOptionsAndStage) {
    CommonOptions common;
    cli::CommandLine line = split({"-v", "-threads", "4", "-fs_basepath", "/a", "-fs_basepath", "/b", "-fs_game",
                                   "mod", "-fs_basegame", "baseoa", "-fs_homepath", "/h", "-game", "QuakeLive", "-force", "-light", "-fast",
                                   "-samples", "2", "maps/x.map"},
                                  &common);
    EXPECT_FALSE(line.help);
    EXPECT_EQ(line.stage, "-light");
    EXPECT_EQ(line.stageArgs, (Args{"-fast", "-samples", "2"}));
    EXPECT_EQ(line.mapArg, "maps/x.map");
    EXPECT_TRUE(common.verbose);
    EXPECT_EQ(common.threads, 4);
    EXPECT_EQ(common.basePaths, (std::vector<std::string>{"/a", "/b"}));
    EXPECT_EQ(common.fsGame, "mod");
    EXPECT_EQ(common.baseGame, "baseoa");
    EXPECT_EQ(common.homePath, "/h");
    EXPECT_EQ(common.game, "quakelive");
    EXPECT_TRUE(common.force);
    EXPECT_EQ(common.mapPath, std::filesystem::path("maps/x.bsp"));
    EXPECT_EQ(common.commandLine, "-light -fast -samples 2");
}

TEST(CliCommandLine, StageIsMatchedWithoutCase) {
    cli::CommandLine line = split({"-INFO", "m.bsp"});
    EXPECT_EQ(line.stage, "-info");
}

TEST(CliCommandLine, StageMissing) {
    const std::string message =
        "no stage given: expected a stage switch such as -light or -info before the map file (see q3map2 -help)";
    EXPECT_EQ(splitError({}), message);
    EXPECT_EQ(splitError({"map.bsp"}), message);
    EXPECT_EQ(splitError({"-v", "-threads", "2", "map.bsp"}), message);
    EXPECT_EQ(splitError({"-ligt", "map.bsp"}), "unknown option '-ligt'; did you mean '-light'?");
}

TEST(CliCommandLine, MapMissing) {
    EXPECT_EQ(splitError({"-light"}), "-light needs a map file as its last argument (-light [options] <filename.map>)");
    EXPECT_EQ(splitError({"-light", "-fast"}),
              "-light needs a map file as its last argument (-light [options] <filename.map>)");
    EXPECT_EQ(splitError({"-info"}), "-info needs a map file as its last argument (-info [options] <filename.bsp>)");
}

TEST(CliCommandLine, CommonOptionErrors) {
    EXPECT_EQ(splitError({"-threads", "-light", "m.bsp"}), "-threads needs 1 value (-threads <N>)");
    EXPECT_EQ(splitError({"-threads", "0", "-light", "m.bsp"}),
              "-threads: 0 is out of range (must be between 1 and 1024)");
    EXPECT_EQ(splitError({"-threads", "four", "-light", "m.bsp"}),
              "-threads: 'four' is not an integer (-threads <N>)");
    EXPECT_EQ(splitError({"-game", "quak3", "-light", "m.bsp"}), "-game: unknown game 'quak3'; did you mean 'quake3'?");
    EXPECT_EQ(splitError({"-game", "sof2", "-light", "m.bsp"}),
              "-game sof2 is a q3map2 game profile this build does not implement yet");
    EXPECT_EQ(splitError({"-game", "xonotic", "-light", "m.bsp"}),
              "-game xonotic is a q3map2 game profile this build does not implement yet");
    EXPECT_EQ(splitError({"-game", "-light", "m.bsp"}), "-game needs 1 value (-game <gamename>)");
    EXPECT_EQ(splitError({"-connect", "-light", "m.bsp"}), "-connect needs 1 value (-connect <address>)");
    EXPECT_EQ(splitError({"-stats", "-light", "m.bsp"}), "-stats needs 1 value (-stats <FILE.json>)");
    EXPECT_EQ(splitError({"-fs_pakpath", "/p", "-light", "m.bsp"}),
              "-fs_pakpath is a q3map2 option this build does not implement yet");
    EXPECT_EQ(splitError({"-threds", "2", "-light", "m.bsp"}), "unknown option '-threds'; did you mean '-threads'?");
    EXPECT_EQ(splitError({"-fast", "-light", "m.bsp"}), "unknown option '-fast' (see q3map2 -help)");
    EXPECT_EQ(splitError({"stray", "-light", "m.bsp"}),
              "unexpected argument 'stray': the map file must be the last argument");
}

TEST(CliCommandLine, CommonOptionAfterTheStage) {
    // q3map2 takes -threads, -force, -subdivisions, -game and the -fs_ paths from anywhere on the
    // line: after the stage switch they still set the common options and leave the stage's list.
    CommonOptions common;
    cli::CommandLine line = split({"-light", "-fast", "-threads", "4", "-fs_basepath", "/x", "m.bsp"}, &common);
    EXPECT_EQ(common.threads, 4);
    ASSERT_EQ(common.basePaths.size(), 1u);
    EXPECT_EQ(common.basePaths[0], "/x");
    EXPECT_EQ(line.stageArgs, std::vector<std::string>{"-fast"});
    // Other common options keep their place before the stage switch.
    line = split({"-light", "-v", "m.bsp"});
    EXPECT_EQ(usageErrorOf([&] { parseLight(line.stageArgs); }),
              "common option -v must come before the stage switch -light");
}

TEST(CliCommandLine, StagesThisBuildLacks) {
    EXPECT_EQ(splitError({"-bsp", "m.map"}), "-bsp is a q3map2 stage this build does not implement yet");
    EXPECT_EQ(splitError({"-v", "-analyze", "m.bsp"}), "-analyze is a q3map2 stage this build does not implement yet");
    EXPECT_EQ(splitError({"-minimap", "m.bsp"}), "-minimap is a q3map2 stage this build does not implement yet");
}

TEST(CliCommandLine, MapPathExtensions) {
    EXPECT_EQ(cli::bspPathFor("maps/a.bsp"), std::filesystem::path("maps/a.bsp"));
    EXPECT_EQ(cli::bspPathFor("maps/a.map"), std::filesystem::path("maps/a.bsp"));
    EXPECT_EQ(cli::bspPathFor("maps/a.MAP"), std::filesystem::path("maps/a.bsp"));
    EXPECT_EQ(cli::bspPathFor("maps/a"), std::filesystem::path("maps/a.bsp"));
    EXPECT_EQ(cli::bspPathFor("maps/A.BSP"), std::filesystem::path("maps/A.BSP"));
    EXPECT_EQ(usageErrorOf([] { cli::bspPathFor("maps/a.txt"); }),
              "map file 'maps/a.txt' must end in .bsp, .map, .reg or .ent (or have no extension)");
    EXPECT_EQ(splitError({"-info", "x.pk3"}), "map file 'x.pk3' must end in .bsp, .map, .reg or .ent (or have no extension)");
}

TEST(CliCommandLine, HelpRequests) {
    cli::CommandLine line = split({"-help"});
    EXPECT_TRUE(line.help);
    EXPECT_EQ(line.helpTopic, "");
    line = split({"-help", "light"});
    EXPECT_EQ(line.helpTopic, "light");
    line = split({"--help", "-light"});
    EXPECT_EQ(line.helpTopic, "light");
    EXPECT_EQ(splitError({"-help", "light", "extra"}), "-help takes at most one stage name, got 'extra'");
}

}  // namespace
}  // namespace q3::test

namespace q3::test {
namespace {

// With -bsp in the build, a command line without a stage switch compiles the map, as q3map2 does:
// the common options are taken from anywhere, the rest are -bsp's.
TEST(CliCommandLine, NoStageSwitchMeansBsp) {
    std::vector<cli::StageDescription> stages = testStages();
    for (cli::StageDescription& s : stages)
        if (s.name == "-bsp") s.available = true;
    CommonOptions common;
    const cli::CommandLine line =
        cli::splitCommandLine(std::vector<std::string>{"-v", "-nodetail", "-threads", "2", "maps/x.map"},
                              cli::commonOptionTable(), stages, common);
    EXPECT_EQ(line.stage, "-bsp");
    EXPECT_EQ(line.stageArgs, (std::vector<std::string>{"-nodetail"}));
    EXPECT_EQ(line.mapArg, "maps/x.map");
    EXPECT_TRUE(common.verbose);
    EXPECT_EQ(common.threads, 2);
    EXPECT_EQ(common.mapPath, std::filesystem::path("maps/x.bsp"));
    EXPECT_EQ(common.commandLine, "-bsp -nodetail");
}

}  // namespace
}  // namespace q3::test
