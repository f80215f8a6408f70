// Fallback to the legacy grid: hand-built lump 15, engine placement rule, worldspawn gridsize,
// direction bytes, zero-ambient points left out, and every shipped OpenArena map.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "sh.h"
#include "sh_bsp_scan.h"
#include "sh_grid_runtime.h"
#include "sh_legacy_grid.h"
#include "sh_test_support.h"
#include "test_data.h"

namespace q3::sh {
namespace {

struct LegacyBsp {
    std::vector<uint8_t> bytes;
    std::vector<uint8_t> grid;  // lump 15
};

// World (-10, 0, 5)..(100, 40, 70) with gridsize 32 32 32: origin (0, 0, 32), maxs (96, 32, 64),
// bounds (4, 2, 2).
LegacyBsp legacyBsp(const std::string& gridsizeValue, int version = 46) {
    const float mins[3] = {-10, 0, 5}, maxs[3] = {100, 40, 70};
    std::vector<std::vector<uint8_t>> lumps(17);
    std::string ents = "{\n\"classname\" \"worldspawn\"\n";
    if (!gridsizeValue.empty()) ents += "\"gridsize\" \"" + gridsizeValue + "\"\n";
    ents += "}\n{\n\"classname\" \"light\"\n\"gridsize\" \"8 8 8\"\n}\n";
    lumps[0].assign(ents.begin(), ents.end());
    lumps[0].push_back(0);
    lumps[7] = test::worldModelLump(mins, maxs);
    LegacyBsp out;
    out.grid.resize(16 * 8);
    for (size_t p = 0; p < 16; ++p) {
        uint8_t* point = &out.grid[p * 8];
        point[0] = uint8_t(10 + p);  // ambient
        point[1] = 20;
        point[2] = 30;
        point[3] = uint8_t(100 + p);  // directed
        point[4] = 50;
        point[5] = 0;
        point[6] = 0;  // longitude 0: straight up
        point[7] = 0;
    }
    lumps[15] = out.grid;
    out.bytes = test::buildBsp(version, 17, lumps);
    return out;
}

TEST(ShLegacyGrid, DecodesDirectionBytesLikeTheEngine) {
    uint8_t point[8] = {};
    float dir[3];
    decodeLegacyDirection(point, dir);
    EXPECT_NEAR(dir[2], 1, 1e-6);
    point[6] = 64;  // 90 degrees from up
    decodeLegacyDirection(point, dir);
    EXPECT_NEAR(dir[0], 1, 1e-6);
    EXPECT_NEAR(dir[2], 0, 1e-6);
    point[7] = 64;  // then 90 degrees around z
    decodeLegacyDirection(point, dir);
    EXPECT_NEAR(dir[1], 1, 1e-6);
    EXPECT_NEAR(dir[0], 0, 1e-6);
    point[6] = 128;
    decodeLegacyDirection(point, dir);
    EXPECT_NEAR(dir[2], -1, 1e-6);
}

TEST(ShLegacyGrid, PlacementFollowsTheEngineRule) {
    const float mins[3] = {-10, 0, 5}, maxs[3] = {100, 40, 70}, size[3] = {32, 32, 32};
    float origin[3];
    int32_t bounds[3];
    ASSERT_EQ(legacyGridPlacement(mins, maxs, size, origin, bounds), "");
    EXPECT_EQ(origin[0], 0);
    EXPECT_EQ(origin[1], 0);
    EXPECT_EQ(origin[2], 32);
    EXPECT_EQ(bounds[0], 4);
    EXPECT_EQ(bounds[1], 2);
    EXPECT_EQ(bounds[2], 2);
    const float thinMaxs[3] = {100, 40, 20};  // ceil(5/32)*32 = 32 > floor(20/32)*32 = 0
    EXPECT_NE(legacyGridPlacement(mins, thinMaxs, size, origin, bounds), "");
}

TEST(ShLegacyGrid, FallbackDecodesAHandBuiltLump15) {
    const LegacyBsp bsp = legacyBsp("32 32 32");
    GridRuntime rt;
    ASSERT_EQ(rt.loadFromBsp(bsp.bytes.data(), bsp.bytes.size(), "legacy.bsp"), "");
    EXPECT_EQ(rt.source(), GridSource::Legacy);
    const GridSH& g = rt.grid();
    EXPECT_EQ(g.bounds[0], 4);
    EXPECT_EQ(g.bounds[1], 2);
    EXPECT_EQ(g.bounds[2], 2);
    EXPECT_EQ(g.mins[2], 32);
    EXPECT_EQ(g.size[0], 32);

    // Point (2, 1, 1) = index 2 + 4 + 8 = 14: ambient (24, 20, 30)/255, directed (114, 50, 0)/255 from +Z.
    const float pos[3] = {64, 32, 64};
    const GridPointSH p = rt.sample(pos);
    const float up[3] = {0, 0, 1}, side[3] = {1, 0, 0}, down[3] = {0, 0, -1};
    float rgb[3];
    irradianceAt(p, up, rgb);
    EXPECT_NEAR(rgb[0], 24 / 255.0 + 1.0625 * 114 / 255.0, 1e-5);
    EXPECT_NEAR(rgb[1], 20 / 255.0 + 1.0625 * 50 / 255.0, 1e-5);
    EXPECT_NEAR(rgb[2], 30 / 255.0, 1e-5);
    irradianceAt(p, side, rgb);
    EXPECT_NEAR(rgb[0], 24 / 255.0 + 0.09375 * 114 / 255.0, 1e-5);
    irradianceAt(p, down, rgb);
    EXPECT_NEAR(rgb[0], 24 / 255.0 + 0.0625 * 114 / 255.0, 1e-5);
    // Converted back for legacy shaders the point is close to what was stored.
    const LegacyLighting light = toLegacyLighting(p);
    EXPECT_NEAR(light.direction[2], 1, 1e-5);
    EXPECT_NEAR(light.directed[0], 0.9875 * 114 / 255.0, 1e-4);
    EXPECT_NEAR(light.ambient[0], 24 / 255.0 + 0.003125 * 114 / 255.0, 1e-4);
}

TEST(ShLegacyGrid, DefaultGridSizeWhenWorldspawnHasNone) {
    // 64 64 128 over the same world: origin (0, 0, 128) > maxs z 0: no points along z.
    const LegacyBsp bsp = legacyBsp("");
    GridRuntime rt;
    const std::string err = rt.loadFromBsp(bsp.bytes.data(), bsp.bytes.size(), "legacy.bsp");
    EXPECT_NE(err.find("legacy.bsp: legacy grid has no points"), std::string::npos) << err;
}

TEST(ShLegacyGrid, RejectsSizeMismatchAndBadGridsize) {
    GridRuntime rt;
    LegacyBsp bsp = legacyBsp("32 32 16");  // needs 4*2*4 points, lump has 16
    std::string err = rt.loadFromBsp(bsp.bytes.data(), bsp.bytes.size(), "m.bsp");
    EXPECT_NE(err.find("legacy light grid mismatch"), std::string::npos) << err;
    bsp = legacyBsp("32 zero 32");
    err = rt.loadFromBsp(bsp.bytes.data(), bsp.bytes.size(), "m.bsp");
    EXPECT_NE(err.find("worldspawn gridsize \"32 zero 32\""), std::string::npos) << err;
    bsp = legacyBsp("32 -32 32");
    EXPECT_NE(rt.loadFromBsp(bsp.bytes.data(), bsp.bytes.size()).find("gridsize"), std::string::npos);
}

TEST(ShLegacyGrid, ZeroAmbientPointsAreLeftOut) {
    LegacyBsp bsp = legacyBsp("32 32 32");
    // Zero the ambient of point (1, 0, 0) (index 1): between x = 0 and 1 only point 0 counts.
    const size_t gridOffset = bsp.bytes.size() - bsp.grid.size();
    for (int c = 0; c < 3; ++c) bsp.bytes[gridOffset + 8 + c] = 0;
    GridRuntime rt;
    ASSERT_EQ(rt.loadFromBsp(bsp.bytes.data(), bsp.bytes.size()), "");
    const float between[3] = {16, 0, 32};
    const float at0[3] = {0, 0, 32};
    const GridPointSH a = rt.sample(between), b = rt.sample(at0);
    for (int i = 0; i < 9; ++i) EXPECT_NEAR(a.coeffs[i][0], b.coeffs[i][0], 1e-6);
}

TEST(ShLegacyGrid, WorldspawnParserReadsOnlyTheFirstEntity) {
    float size[3];
    const std::string text = "{ \"GridSize\" \"16 24 40\" }{ \"gridsize\" \"8 8 8\" }";
    ByteRange range{reinterpret_cast<const uint8_t*>(text.data()), text.size()};
    ASSERT_EQ(readWorldGridSize(range, size), "");
    EXPECT_EQ(size[0], 16);
    EXPECT_EQ(size[1], 24);
    EXPECT_EQ(size[2], 40);
    const std::string unterminated = "{ \"gridsize\"";
    range = {reinterpret_cast<const uint8_t*>(unterminated.data()), unterminated.size()};
    EXPECT_NE(readWorldGridSize(range, size), "");
    range = {};
    ASSERT_EQ(readWorldGridSize(range, size), "");
    EXPECT_EQ(size[2], 128);
}

std::vector<uint8_t> readAll(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(ShLegacyGrid, EveryShippedOpenArenaMapFallsBackToItsLegacyGrid) {
    const std::vector<std::filesystem::path> maps = q3::test::allRealBsps();
    ASSERT_GE(maps.size(), 100u);
    size_t loaded = 0, withoutGrid = 0;
    for (const std::filesystem::path& path : maps) {
        const std::vector<uint8_t> bytes = readAll(path);
        GridRuntime rt;
        const std::string err = rt.loadFromBsp(bytes.data(), bytes.size(), path.filename().string());
        if (!err.empty()) {
            ADD_FAILURE() << err;
            continue;
        }
        ++loaded;
        BspDirectory dir;
        ASSERT_EQ(readBspDirectory(bytes.data(), bytes.size(), dir), "");
        if (dir.lumps[kLumpLightGrid].empty()) {  // compiled without a grid (oa_ctf2)
            EXPECT_EQ(rt.source(), GridSource::None) << path;
            ++withoutGrid;
            continue;
        }
        EXPECT_EQ(rt.source(), GridSource::Legacy) << path;
        // The centre of the grid has light, finite and non-negative.
        const GridSH& g = rt.grid();
        float centre[3];
        for (int a = 0; a < 3; ++a) centre[a] = g.mins[a] + 0.5f * g.size[a] * float(g.bounds[a] - 1);
        const GridPointSH p = rt.sample(centre);
        const AmbientCube cube = toAmbientCube(p);
        for (int f = 0; f < 6; ++f)
            for (int c = 0; c < 3; ++c) EXPECT_TRUE(std::isfinite(cube.face[f][c]) && cube.face[f][c] >= 0) << path;
    }
    EXPECT_EQ(loaded, maps.size());
    EXPECT_LE(withoutGrid, 2u);
}

TEST(ShLegacyGrid, NoGridAtAllLoadsAsNone) {
    std::vector<std::vector<uint8_t>> lumps(17);
    lumps[0] = {'{', '}', 0};
    const std::vector<uint8_t> bytes = test::buildBsp(46, 17, lumps);
    GridRuntime rt;
    ASSERT_EQ(rt.loadFromBsp(bytes.data(), bytes.size()), "");
    EXPECT_EQ(rt.source(), GridSource::None);
    const float pos[3] = {0, 0, 0};
    EXPECT_EQ(rt.sample(pos).coeffs[0][0], 0.0f);
}

}  // namespace
}  // namespace q3::sh
