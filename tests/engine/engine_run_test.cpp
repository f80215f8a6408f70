// The plain-text helpers of the engine runners: quoting, screenshot names, and reading
// DarkPlaces' light-grid samples out of the scripts' reports.
#include <gtest/gtest.h>

#include "engine_run.h"
#include "test_data.h"

namespace q3::enginetest {
namespace {

TEST(EngineRun, QuotesWordsForTheShell) {
    EXPECT_EQ(shellQuote("plain"), "'plain'");
    EXPECT_EQ(shellQuote("a b"), "'a b'");
    EXPECT_EQ(shellQuote("it's"), "'it'\\''s'");
    std::string echoed;
    ASSERT_EQ(test::runCommand("printf %s " + shellQuote("it's $HOME `x`"), &echoed), 0);
    EXPECT_EQ(echoed, "it's $HOME `x`");
}

TEST(EngineRun, ScreenshotNamesFollowTheScript) {
    EXPECT_EQ(screenshotPath("/t/lit", "ioq3", "lightmap"), std::filesystem::path("/t/lit-ioq3-lightmap.png"));
}

TEST(EngineRun, ReadsDarkPlacesGridSamples) {
    const std::string report =
        "  dp    OK     0.4s  DarkPlaces (map + QuakeC): map x running\n"
        "      lightgrid at info_player_deathmatch '-328.0 -1320.0 276.0' = ' 36.0  43.0  49.1'\n"
        "      lightgrid at info_player_deathmatch '688.0 608.0  76.0' = '  5.1   5.1   5.1'\n"
        "      model at '-323.5 -1224.1 250.0' lightgrid = ' 36.0  40.2  44.3'\n"
        "      lightgrid at info_player_deathmatch '0 0 0' = 'garbled'\n";
    const std::vector<double> spawns = darkPlacesGridSums(report, "lightgrid at ");
    ASSERT_EQ(spawns.size(), 2u);
    EXPECT_NEAR(spawns[0], 128.1, 1e-4);
    EXPECT_NEAR(spawns[1], 15.3, 1e-4);
    const std::vector<double> model = darkPlacesGridSums(report, "model at ");
    ASSERT_EQ(model.size(), 1u);
    EXPECT_NEAR(model[0], 120.5, 1e-4);
    EXPECT_TRUE(darkPlacesGridSums(report, "absent").empty());
    EXPECT_EQ(linesWith(report, " OK ").size(), 1u);
}

}  // namespace
}  // namespace q3::enginetest
