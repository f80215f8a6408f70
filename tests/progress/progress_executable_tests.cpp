// Progress as the q3map2 executable shows it: on a terminal (a pseudo-terminal from util-linux's
// `script`) a bar redrawn in place ending at 100%; in a pipe q3map2's dots. Either way the run
// ends with each phase's time, and -stats holds the same phases, valid against
// docs/stats-schema.json. Uses -light -fast -nolm on a real map, so only the quick legacy grid
// loop reports progress.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <rapidjson/document.h>
#include <rapidjson/schema.h>
#include <rapidjson/stringbuffer.h>
#include <sstream>
#include <string>
#include <vector>

#include "stats_schema.h"
#include "test_data.h"

namespace q3::test {
namespace {

namespace fs = std::filesystem;

std::string lightCommand(const fs::path& dir, const std::string& commonOptions = "") {
    fs::copy_file(realBsp("oacmpdm1"), dir / "oacmpdm1.bsp");
    // The .map source holds the light entities (-bsp strips them from the BSP).
    for (const fs::path& source : oacmpMapSources())
        if (source.filename() == "oacmpdm1.map") fs::copy_file(source, dir / "oacmpdm1.map");
    EXPECT_TRUE(fs::exists(dir / "oacmpdm1.map"));
    return shellQuote(q3map2Exe()) + " " + commonOptions + "-light -fast -nolm " + shellQuote(dir / "oacmpdm1.bsp");
}


const std::string kDots = "0...1...2...3...4...5...6...7...8...9...10 (";
const std::string kFullBar = "\r[########################################]  100%  ";

void expectPhaseSummary(const std::string& output) {
    for (const char* phase : {"seconds  load", "seconds  scene", "seconds  lights", "seconds  vertex light",
                              "seconds  light grid", "seconds  write", "seconds elapsed"})
        EXPECT_NE(output.find(phase), std::string::npos) << phase << " missing in\n" << output;
}

TEST(ProgressExecutable, PipeGetsQ3map2DotsAndStatsHoldThePhases) {
    const fs::path dir = tempDir();
    const fs::path statsPath = dir / "stats.json";
    std::string output;
    ASSERT_EQ(runCommand(lightCommand(dir, "-stats " + shellQuote(statsPath) + " ") + " </dev/null", &output), 0)
        << output;
    EXPECT_NE(output.find("light grid: 51 x 51 x 6"), std::string::npos) << output;
    EXPECT_NE(output.find(kDots), std::string::npos) << output;
    EXPECT_EQ(output.find('\r'), std::string::npos) << "no carriage returns in a log";
    expectPhaseSummary(output);

    rapidjson::Document stats = test::readJsonFile(statsPath);
    EXPECT_EQ(test::statsSchemaViolation(stats), "");
    EXPECT_STREQ(stats["stage"].GetString(), "light");
    std::vector<std::string> phases;
    for (const auto& phase : stats["phases"].GetArray()) phases.emplace_back(phase["name"].GetString());
    EXPECT_EQ(phases, (std::vector<std::string>{"load", "scene", "lights", "vertex light", "light grid", "write"}));
    EXPECT_GT(stats["raysTraced"].GetUint64(), 0u);
    EXPECT_EQ(stats["luxels"].GetUint64(), 0u);  // -nolm
    const auto& legacy = stats["grids"]["legacy"];
    ASSERT_TRUE(legacy.IsObject());
    EXPECT_EQ(legacy["points"].GetUint64(), 51u * 51u * 6u);
    EXPECT_TRUE(stats["grids"]["sh"].IsNull());  // no -sh
}

TEST(ProgressExecutable, StatsHoldTheShGridSize) {
    const fs::path dir = tempDir();
    const fs::path statsPath = dir / "stats.json";
    std::string output;
    // A coarse SH grid keeps the run short; its size is what -stats must report.
    const std::string plain = lightCommand(dir, "-stats " + shellQuote(statsPath) + " ");
    const size_t at = plain.find("-nolm ");
    ASSERT_NE(at, std::string::npos);
    const std::string command = plain.substr(0, at) + "-nolm -sh -gridsh 256 256 256 " + plain.substr(at + 6);
    ASSERT_EQ(runCommand(command + " </dev/null", &output), 0) << output;
    rapidjson::Document stats = test::readJsonFile(statsPath);
    EXPECT_EQ(test::statsSchemaViolation(stats), "");
    const auto& sh = stats["grids"]["sh"];
    ASSERT_TRUE(sh.IsObject());
    const uint64_t points = sh["points"].GetUint64();
    EXPECT_GT(points, 0u);
    EXPECT_NE(output.find("SH grid: cell 256 256 256, "), std::string::npos) << output;
    EXPECT_NE(output.find(" = " + std::to_string(points) + " points"), std::string::npos) << output;
}

TEST(ProgressExecutable, TerminalGetsABarWithElapsedTimeAndEta) {
    std::string output;
    // The inner command quotes its paths with single quotes, so the whole goes in double quotes.
    const std::string command = "script -qec \"" + lightCommand(tempDir()) + "\" /dev/null </dev/null";
    ASSERT_EQ(runCommand(command, &output), 0) << output;
    size_t bar = output.find(kFullBar);
    ASSERT_NE(bar, std::string::npos) << output;
    EXPECT_NE(output.find(" elapsed, ETA 0:00", bar), std::string::npos) << output;
    EXPECT_NE(output.find("\r[........................................]    0%  0:00 elapsed, ETA --:--"),
              std::string::npos)
        << output;
    EXPECT_EQ(output.find(kDots), std::string::npos) << "dots on a terminal:\n" << output;
    expectPhaseSummary(output);
}

}  // namespace
}  // namespace q3::test
