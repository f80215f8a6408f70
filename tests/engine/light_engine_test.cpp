// Issue 3 in real engines: three oacmp maps relit with `-light -fast` load in ioquake3 and
// DarkPlaces without a warning about the BSP (strict checks), keep the legacy grid the engines
// accept (its point count recomputed here as ioquake3 does) and render lit in ioquake3 - clearly
// brighter than the same map with its lightmaps zeroed, so a black or missing lightmap cannot pass.
// ioquake3 checks the grid size in its renderer, which the dedicated server of q3-load-check does
// not load: the strict screenshot is where ioquake3 would report "light grid mismatch".
#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>

#include "bspfile.h"
#include "engine_grid_count.h"
#include "engine_picture.h"
#include "engine_run.h"
#include "test_data.h"

namespace q3::enginetest {
namespace {
namespace fs = std::filesystem;

// Cheap maps of the oacmp set, each a few CPU seconds with -fast (oacmpdm5 ~1 s, oacmpdm1 and
// oacmpctf2 ~2.5 s). A build that samples the real maps (the sanitizer build) runs the first.
std::vector<std::string> relitMaps() {
    if (test::realBspsAreSampled()) return {"oacmpdm5"};
    return {"oacmpdm5", "oacmpdm1", "oacmpctf2"};
}

// What a lit view must show in ioquake3's lightmap-only mode and in the normal view. The spawn
// views of these maps measured a mean luma of 50-163 (lightmap) and 22-48 (normal, textured), with
// 77-99.9% of the pixels above the black level; the floors sit at about half of the lowest, low
// enough for a darker view of a correct map, far above a black or missing lightmap (luma < 2).
constexpr double kMinLightmapLuma = 25, kMinNormalLuma = 10;
constexpr double kMinLitFraction = 0.4;
// Zeroed lightmaps leave only the sky and vertex-lit surfaces (measured 0.1-23 luma, at most 48%
// of the lit view where the sky fills a third of the picture): the picture must lose at least 40%
// of its mean luma, which a renderer ignoring the lightmaps would not.
constexpr double kMaxDarkToLitRatio = 0.6;

void printLines(const RunResult& r, const std::string& needle) {
    for (const std::string& line : linesWith(r.output, needle)) std::cout << "    " << line << "\n";
}

class LitMapInEngines : public ::testing::TestWithParam<std::string> {};

TEST_P(LitMapInEngines, LoadsWithEngineGridAndRendersLit) {
    const std::string name = GetParam();
    const fs::path dir = test::tempDir();
    const fs::path gameDir = stageOacmpMap(dir / "game", name);

    const RunResult light = runLight(gameDir, name, {"-fast"});
    ASSERT_EQ(light.status, 0) << light.command << "\n" << light.output;
    printLines(light, "light grid:");
    const fs::path litPath = gameDir / "maps" / (name + ".bsp");
    const bsp::Bsp lit = bsp::readBsp(litPath);
    EXPECT_EQ(lit.version, bsp::kVersionQ3);

    // The legacy grid: exactly the engine's point count for model 0's bounds and the gridsize the
    // compiler wrote back to worldspawn.
    const EngineGrid grid = engineGridOf(lit, litPath.string());
    std::cout << "  engine grid " << grid.bounds[0] << " x " << grid.bounds[1] << " x " << grid.bounds[2] << " = "
              << grid.numPoints() << " points (cell " << grid.size[0] << " " << grid.size[1] << " " << grid.size[2]
              << "), lump 15 holds " << lit.lightGrid.size() << "\n";
    EXPECT_GT(grid.numPoints(), 0);
    EXPECT_EQ(int64_t(lit.lightGrid.size()), grid.numPoints());
    size_t litPoints = 0;
    for (const bsp::GridPoint& p : lit.lightGrid)
        if (p.ambient[0] + p.ambient[1] + p.ambient[2] + p.directed[0] + p.directed[1] + p.directed[2] > 0) ++litPoints;
    EXPECT_GT(litPoints, lit.lightGrid.size() / 10) << "grid points with light";

    // The engines see the file under a name no package ships, so no packaged map can stand in.
    const fs::path engineDir = dir / "engine";
    const fs::path litCopy = copyForEngines(litPath, engineDir, name + "_lit");
    const RunResult load = expectLoads(litCopy, "ioq3,dp", engineDir / "logs");
    // DarkPlaces samples the grid 36 units above the first spawn points: some of them are lit
    // (the brightest measured an RGB sum of 29 on oacmpdm1 and 239 on oacmpdm5; 0 when black).
    const std::vector<double> spawnLight = darkPlacesGridSums(load.output, "lightgrid at ");
    ASSERT_FALSE(spawnLight.empty()) << "DarkPlaces printed no light-grid samples";
    EXPECT_GT(*std::max_element(spawnLight.begin(), spawnLight.end()), 10.0);

    // The same map with every lightmap byte zeroed, written with the BSP library.
    bsp::Bsp dark = lit;
    ASSERT_FALSE(dark.lightmaps.empty());
    std::fill(dark.lightmaps.begin(), dark.lightmaps.end(), uint8_t(0));
    const fs::path darkCopy = engineDir / (name + "_dark.bsp");
    bsp::writeBsp(darkCopy, dark);

    const RunResult litShots = runScreenshot(litCopy, "ioq3", "lightmap,normal", engineDir / "lit", engineDir / "logs");
    std::cout << litShots.output;
    // Strict: ioquake3's renderer would have warned here about a grid of the wrong size.
    ASSERT_EQ(litShots.status, 0) << litShots.command;
    EXPECT_TRUE(linesWith(litShots.output, "light grid mismatch").empty());
    const RunResult darkShots =
        runScreenshot(darkCopy, "ioq3", "lightmap,normal", engineDir / "dark", engineDir / "logs");
    ASSERT_EQ(darkShots.status, 0) << darkShots.command << "\n" << darkShots.output;

    for (const std::string mode : {"lightmap", "normal"}) {
        const PictureStats litView = pictureStats(readPng(screenshotPath(engineDir / "lit", "ioq3", mode)));
        const PictureStats darkView = pictureStats(readPng(screenshotPath(engineDir / "dark", "ioq3", mode)));
        std::cout << "  ioq3 " << mode << ": lit luma " << litView.meanLuminance << ", " << 100 * litView.litFraction
                  << "% lit pixels; zeroed lightmaps luma " << darkView.meanLuminance << ", "
                  << 100 * darkView.litFraction << "%\n";
        EXPECT_GT(litView.meanLuminance, mode == std::string("lightmap") ? kMinLightmapLuma : kMinNormalLuma) << mode;
        EXPECT_GT(litView.litFraction, kMinLitFraction) << mode;
        EXPECT_LT(darkView.meanLuminance, kMaxDarkToLitRatio * litView.meanLuminance) << mode;
    }
}

// The strict checks are what catch a grid of the wrong size: the shipped oacmpdm5 with its last
// grid point dropped fails q3-load-check -s through DarkPlaces ("invalid lightgrid lump size") and
// q3-screenshot -s through ioquake3's renderer ("light grid mismatch"). ioquake3's dedicated
// server has no renderer, so it never looks at the grid: the screenshot is the ioquake3 check.
TEST(EngineStrictCheck, GridOnePointShortFails) {
    const fs::path dir = test::tempDir();
    bsp::Bsp map = bsp::readBsp(test::realBsp("oacmpdm5"));
    ASSERT_EQ(int64_t(map.lightGrid.size()), engineGridOf(map, "oacmpdm5").numPoints());
    map.lightGrid.pop_back();
    EXPECT_NE(int64_t(map.lightGrid.size()), engineGridOf(map, "oacmpdm5").numPoints());
    const fs::path shortGrid = dir / "oacmpdm5_short.bsp";
    bsp::writeBsp(shortGrid, map);
    const RunResult load = runLoadCheck(shortGrid, "ioq3,dp", dir / "logs");
    EXPECT_NE(load.status, 0) << load.command << "\n" << load.output;
    EXPECT_FALSE(linesWith(load.output, "invalid lightgrid lump size").empty()) << load.output;
    const RunResult shot = runScreenshot(shortGrid, "ioq3", "lightmap", dir / "short", dir / "logs");
    EXPECT_NE(shot.status, 0) << shot.command << "\n" << shot.output;
    EXPECT_FALSE(linesWith(shot.output, "light grid mismatch").empty()) << shot.output;
}

INSTANTIATE_TEST_SUITE_P(Oacmp, LitMapInEngines, ::testing::ValuesIn(relitMaps()),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

}  // namespace
}  // namespace q3::enginetest
