// The engine's legacy-grid layout as recomputed by the engine tests: hand-worked cases, the
// worldspawn key as ioquake3 parses it, and every shipped oacmp map (compiled by q3map2 and
// loaded by the engines without a mismatch) matches its lump 15.
#include <gtest/gtest.h>

#include "bspfile.h"
#include "engine_grid_count.h"
#include "test_data.h"

namespace q3::enginetest {
namespace {

TEST(EngineGridCount, GridSizeParsedLikeSscanf) {
    EXPECT_EQ(engineGridSize(""), (std::array<float, 3>{64, 64, 128}));
    EXPECT_EQ(engineGridSize("32 48 96"), (std::array<float, 3>{32, 48, 96}));
    EXPECT_EQ(engineGridSize("40 40"), (std::array<float, 3>{40, 40, 128}));
    EXPECT_EQ(engineGridSize("24 x 8"), (std::array<float, 3>{24, 64, 128}));
    EXPECT_EQ(engineGridSize("nothing"), (std::array<float, 3>{64, 64, 128}));
    EXPECT_EQ(engineGridSize("70.5 64 128"), (std::array<float, 3>{70.5f, 64, 128}));
}

TEST(EngineGridCount, BoundsRoundInwardToWholeCells) {
    // x, y: ceil(-100/64) = -1 -> -64, floor(300/64) = 4 -> 256: (256 + 64) / 64 + 1 = 6 points.
    // z: ceil(-50/128) = 0, floor(200/128) = 1 -> 128: 2 points.
    const EngineGrid g = engineGridFor({-100, -100, -50}, {300, 300, 200}, {64, 64, 128});
    EXPECT_EQ(g.origin, (std::array<float, 3>{-64, -64, 0}));
    EXPECT_EQ(g.bounds, (std::array<int, 3>{6, 6, 2}));
    EXPECT_EQ(g.numPoints(), 72);
    // Bounds on cell boundaries keep both end points.
    const EngineGrid exact = engineGridFor({0, -64, -128}, {64, 64, 128}, {64, 64, 128});
    EXPECT_EQ(exact.bounds, (std::array<int, 3>{2, 3, 3}));
    // A box thinner than a cell that straddles no boundary has no point on that axis.
    const EngineGrid thin = engineGridFor({10, 0, 0}, {50, 64, 128}, {64, 64, 128});
    EXPECT_EQ(thin.bounds[0], 0);
    EXPECT_EQ(thin.numPoints(), 0);
}

TEST(EngineGridCount, WorldspawnKeyAndModelZero) {
    bsp::Bsp map;
    map.models.resize(2);
    const float mins[3] = {-512, -256, -64}, maxs[3] = {512, 256, 320};
    for (int i = 0; i < 3; ++i) {
        map.models[0].mins[i] = mins[i];
        map.models[0].maxs[i] = maxs[i];
        map.models[1].mins[i] = -4096;  // brush models do not widen the grid
        map.models[1].maxs[i] = 4096;
    }
    map.entities = "{\n\"classname\" \"worldspawn\"\n}\n";
    EXPECT_EQ(engineGridOf(map, "a.bsp").bounds, (std::array<int, 3>{17, 9, 3}));  // 64 64 128
    map.entities = "{\n\"classname\" \"worldspawn\"\n\"GridSize\" \"128 128 256\"\n}\n";
    EXPECT_EQ(engineGridOf(map, "a.bsp").bounds, (std::array<int, 3>{9, 5, 2}));
    // A later key is scanned over the earlier one; parts it lacks keep the earlier values.
    map.entities = "{\n\"classname\" \"worldspawn\"\n\"gridsize\" \"128 128 256\"\n\"gridsize\" \"256\"\n}\n";
    EXPECT_EQ(engineGridOf(map, "a.bsp").size, (std::array<float, 3>{256, 128, 256}));
    // Only worldspawn counts.
    map.entities = "{\n\"classname\" \"worldspawn\"\n}\n{\n\"classname\" \"info_null\"\n\"gridsize\" \"8 8 8\"\n}\n";
    EXPECT_EQ(engineGridOf(map, "a.bsp").size, (std::array<float, 3>{64, 64, 128}));
    map.models.clear();
    EXPECT_THROW(engineGridOf(map, "a.bsp"), bsp::BspError);
}

TEST(EngineGridCount, ShippedOacmpMapsMatchTheirGridLump) {
    int maps = 0;
    for (const std::filesystem::path& source : test::oacmpMapSources()) {
        const std::filesystem::path path = test::realBsp(source.stem().string());
        const bsp::Bsp map = bsp::readBsp(path);
        EXPECT_EQ(int64_t(map.lightGrid.size()), engineGridOf(map, path.string()).numPoints()) << path;
        ++maps;
    }
    EXPECT_EQ(maps, 13);
}

}  // namespace
}  // namespace q3::enginetest
