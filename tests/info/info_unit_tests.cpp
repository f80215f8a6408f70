// The pure parts of -info: the engine's legacy grid size, SH grid statistics, and the report of a
// small BSP built in memory.
#include "grid_stats.h"
#include "info_stage.h"
#include "../sh/world_lights_samples.h"

#include <gtest/gtest.h>

#include <cstring>

namespace q3::test {
namespace {

TEST(InfoGrid, LegacyLayoutFollowsTheEngineFormula) {
    const float mins[3] = {-100, -64, -10}, maxs[3] = {100, 64, 300}, size[3] = {64, 64, 128};
    info::LegacyGridLayout g = info::legacyGridLayout(mins, maxs, size);
    // x: ceil(-100/64)*64 = -64 .. floor(100/64)*64 = 64 -> 3; y: -64..64 -> 3; z: 0..256 -> 3.
    EXPECT_FLOAT_EQ(g.origin[0], -64);
    EXPECT_FLOAT_EQ(g.origin[2], 0);
    EXPECT_EQ(g.bounds[0], 3);
    EXPECT_EQ(g.bounds[1], 3);
    EXPECT_EQ(g.bounds[2], 3);
    EXPECT_EQ(g.points, 27);

    const float tinyMins[3] = {1, 1, 1}, tinyMaxs[3] = {2, 2, 2};
    g = info::legacyGridLayout(tinyMins, tinyMaxs, size);  // no grid plane inside: zero points
    EXPECT_EQ(g.bounds[0], 0);
    EXPECT_EQ(g.points, 0);
}

TEST(InfoGrid, GridSizeKey) {
    float size[3] = {64, 64, 128};
    info::parseGridSize("32 48 96", size);
    EXPECT_FLOAT_EQ(size[0], 32);
    EXPECT_FLOAT_EQ(size[1], 48);
    EXPECT_FLOAT_EQ(size[2], 96);
    float partial[3] = {64, 64, 128};
    info::parseGridSize("16 x", partial);
    EXPECT_FLOAT_EQ(partial[0], 16);
    EXPECT_FLOAT_EQ(partial[1], 64);
    float negative[3] = {64, 64, 128};
    info::parseGridSize("-8 0 40", negative);
    EXPECT_FLOAT_EQ(negative[0], 64);
    EXPECT_FLOAT_EQ(negative[1], 64);
    EXPECT_FLOAT_EQ(negative[2], 40);
}

TEST(InfoGrid, ShStatistics) {
    sh::GridSH grid;
    grid.points.resize(3);
    std::memset(grid.points.data(), 0, grid.points.size() * sizeof(sh::GridPointSH));
    grid.points[0].coeffs[0][0] = 2;
    grid.points[0].coeffs[0][1] = -1;
    grid.points[2].coeffs[8][2] = 0.5f;  // not zero, but coefficient 0 is
    info::ShGridStats s = info::shGridStats(grid);
    EXPECT_EQ(s.points, 3);
    EXPECT_FLOAT_EQ(s.coeff0Min, -1);
    EXPECT_FLOAT_EQ(s.coeff0Max, 2);
    EXPECT_DOUBLE_EQ(s.coeff0Mean, 1.0 / 9.0);
    EXPECT_EQ(s.allZeroPoints, 1);
}

TEST(InfoReport, SmallBspInMemory) {
    bsp::Bsp b;
    b.entities = "{\n\"classname\" \"worldspawn\"\n\"gridsize\" \"32 32 64\"\n}\n{\n\"classname\" \"light\"\n}\n";
    b.entities.push_back('\0');
    b.models.resize(1);
    for (int i = 0; i < 3; ++i) {
        b.models[0].mins[i] = -32;
        b.models[0].maxs[i] = 32;
    }
    b.shaders.resize(2);
    b.surfaces.resize(3);
    b.surfaces[0].surfaceType = bsp::MST_PATCH;
    b.surfaces[1].surfaceType = bsp::MST_PLANAR;
    b.surfaces[2].surfaceType = bsp::MST_PLANAR;
    b.lightmaps.resize(2 * bsp::kLightmapPageBytes);
    b.lightGrid.resize(3 * 3 * 2);  // x, y: -32..32 step 32 -> 3; z: 0..0 step 64 -> 1
    std::string report = info::formatBspInfo(b, "maps/tiny.bsp", 1234);
    EXPECT_NE(report.find("\nmaps/tiny.bsp\n"), std::string::npos);
    EXPECT_NE(report.find("File size: 1234 bytes"), std::string::npos);
    EXPECT_NE(report.find("        1 models               40\n"), std::string::npos) << report;
    EXPECT_NE(report.find("        2 shaders             144\n"), std::string::npos);
    EXPECT_NE(report.find("        2 entdata       " + std::string(9 - std::to_string(b.entities.size()).size(), ' ') +
                          std::to_string(b.entities.size()) + "\n"),
              std::string::npos);
    EXPECT_NE(report.find("        3 drawsurfaces        312 *\n"), std::string::npos);
    EXPECT_NE(report.find("        1   patch surfaces\n"), std::string::npos);
    EXPECT_NE(report.find("        2   planar surfaces\n"), std::string::npos);
    EXPECT_NE(report.find("        2 lightmaps         98304\n"), std::string::npos);
    EXPECT_NE(report.find("Legacy grid: 18 points stored, engine expects 9 (gridsize 32 32 64, bounds 3 x 3 x 1)"),
              std::string::npos)
        << report;
    EXPECT_NE(report.find("count mismatch"), std::string::npos);
    EXPECT_NE(report.find("SH grid: none"), std::string::npos);

    b.entities = "{ \"classname\" ";  // broken entity text is an error naming the file
    EXPECT_THROW(
        {
            try {
                info::formatBspInfo(b, "maps/tiny.bsp", 1);
            } catch (const bsp::BspError& e) {
                EXPECT_EQ(std::string(e.what()).rfind("maps/tiny.bsp", 0), 0u) << e.what();
                throw;
            }
        },
        bsp::BspError);
}

TEST(InfoReport, WorldLightsSizeAndCount) {
    bsp::Bsp b;
    b.entities = "{\n\"classname\" \"worldspawn\"\n}\n";
    b.entities.push_back('\0');
    b.setBspx(sh::kWorldLightsLumpName, sh::encodeWorldLights(sh::test::sampleWorldLights()));
    const std::string report = info::formatBspInfo(b, "maps/lights.bsp", 1);
    EXPECT_NE(report.find("  WORLDLIGHTS                    496\n"), std::string::npos) << report;
    EXPECT_NE(report.find("World lights (BSPX WORLDLIGHTS): 5 lights, 496 bytes\n"), std::string::npos) << report;
    EXPECT_NE(report.find("  2 point, 2 spot, 1 sun; 2 with their direct light in the SH grid\n"), std::string::npos)
        << report;

    std::vector<uint8_t> lump = sh::encodeWorldLights(sh::test::sampleWorldLights());
    lump.resize(100);
    b.setBspx(sh::kWorldLightsLumpName, lump);
    try {
        info::formatBspInfo(b, "maps/lights.bsp", 1);
        ADD_FAILURE() << "a malformed WORLDLIGHTS lump was reported";
    } catch (const bsp::BspError& e) {
        EXPECT_NE(std::string(e.what()).find("maps/lights.bsp: BSPX WORLDLIGHTS: 5 lights need 496 bytes, the lump has 100"),
                  std::string::npos)
            << e.what();
    }
}

}  // namespace
}  // namespace q3::test
