#include <gtest/gtest.h>

#include "bsp_test_maps.h"
#include "structure_emit.h"

namespace q3::bspstage {
namespace {

// A sealed room straddling x = 0 (two clusters), a door with an origin brush, a light and a player.
const std::string kRoomWithDoor =
    test::worldspawn(test::hollowRoom({-448, 64, 64}, {448, 960, 448}), "\"message\" \"room\"\n") +
    "{\n\"classname\" \"func_door\"\n\"angle\" \"90\"\n" + test::boxBrush({-32, 400, 64}, {32, 416, 192}) +
    test::boxBrush({-8, 400, 64}, {8, 416, 80}, "common/origin") + "}\n" + test::pointEntity("light", {0, 500, 300}) +
    test::pointEntity("info_player_deathmatch", {-200, 500, 100});

bsp::Bsp emitRoom(std::unique_ptr<test::CompiledMap>& compiled, EntityLumpOptions options = {}) {
    static Log log(false);
    static const ShaderTable shaders = test::commonShaders(log);
    compiled = test::compileMapText(kRoomWithDoor);
    return emitStructure(compiled->map, compiled->world, shaders, options);
}

TEST(StructureEmit, TreeBecomesNodesAndLeafsAfterTheDummyLeaf) {
    std::unique_ptr<test::CompiledMap> c;
    const bsp::Bsp out = emitRoom(c);
    EXPECT_NO_THROW(bsp::validateBsp(out, "room"));
    const int worldLeafs = c->world.tree.leafCount();
    ASSERT_EQ(out.nodes.size(), size_t(worldLeafs - 1));
    ASSERT_EQ(out.leafs.size(), size_t(1 + worldLeafs + 1));  // dummy, world, the door's leaf
    EXPECT_EQ(out.leafs[0].mins[0], INT32_MAX);
    EXPECT_EQ(out.leafs[0].maxs[0], INT32_MIN);
    for (const bsp::Node& n : out.nodes) EXPECT_EQ(n.planeNum % 2, 0);
    EXPECT_EQ(out.planes.size(), size_t(c->map.planes.size()));
    // Clusters in the leafs are the portal file's: -1 for opaque leaves, 0 and 1 for the halves.
    int maxCluster = -1;
    for (size_t i = 1; i <= size_t(worldLeafs); ++i) maxCluster = std::max(maxCluster, out.leafs[i].cluster);
    EXPECT_EQ(maxCluster + 1, c->world.clusters.clusters);
    EXPECT_EQ(c->world.clusters.clusters, 2);
    // The door's single leaf: cluster 0, area 0, its one brush.
    const bsp::Leaf& door = out.leafs.back();
    EXPECT_EQ(door.cluster, 0);
    EXPECT_EQ(door.numLeafBrushes, 1);
    EXPECT_EQ(out.leafBrushes[size_t(door.firstLeafBrush)], 6);
}

TEST(StructureEmit, BrushesModelsAndShaders) {
    std::unique_ptr<test::CompiledMap> c;
    const bsp::Bsp out = emitRoom(c);
    ASSERT_EQ(out.models.size(), 2u);
    EXPECT_EQ(out.models[0].firstBrush, 0);
    EXPECT_EQ(out.models[0].numBrushes, 6);
    EXPECT_EQ(out.models[1].firstBrush, 6);
    EXPECT_EQ(out.models[1].numBrushes, 1);
    EXPECT_FLOAT_EQ(out.models[0].mins[0], -464);
    EXPECT_FLOAT_EQ(out.models[0].maxs[2], 464);
    // The door is relative to its origin brush centre (0 408 72).
    EXPECT_FLOAT_EQ(out.models[1].mins[0], -32);
    EXPECT_FLOAT_EQ(out.models[1].mins[2], -8);
    ASSERT_EQ(out.brushes.size(), 7u);
    for (const bsp::Brush& b : out.brushes) {
        ASSERT_EQ(b.numSides, 6);
        EXPECT_STREQ(out.shaders[size_t(b.shaderNum)].name, "textures/base/wall");
        for (int k = 0; k < 6; ++k) {
            const bsp::Plane& p = out.planes[size_t(out.brushSides[size_t(b.firstSide + k)].planeNum)];
            EXPECT_FLOAT_EQ(p.normal[k / 2], k % 2 ? 1.0f : -1.0f);  // -X +X -Y +Y -Z +Z
        }
    }
    EXPECT_EQ(out.drawIndexes, (std::vector<int32_t>{0, 1, 2, 0, 2, 3}));
}

TEST(StructureEmit, EntityLumpAsQ3map2WritesIt) {
    std::unique_ptr<test::CompiledMap> c;
    EntityLumpOptions options;
    options.stageArgs = {"-meta", "-samplesize \"8\";"};
    const bsp::Bsp out = emitRoom(c, options);
    const std::string expected =
        "{\n\"classname\" \"worldspawn\"\n\"message\" \"room\"\n"
        "\"_q3map2_cmdline\" \"-bsp -meta -samplesize 8\"\n\"_q3map2_version\" \"2.5.17n\"\n}\n"
        "{\n\"classname\" \"func_door\"\n\"angle\" \"90\"\n\"origin\" \"0.000000 408.000000 72.000000\"\n"
        "\"model\" \"*1\"\n}\n"
        "{\n\"classname\" \"info_player_deathmatch\"\n\"origin\" \"-200 500 100\"\n}\n";
    EXPECT_EQ(out.entities, expected + std::string(1, '\0'));  // the light is stripped

    EntityLumpOptions keep;
    keep.keepLights = true;
    const bsp::Bsp kept = emitRoom(c, keep);
    EXPECT_NE(kept.entities.find("\"classname\" \"light\""), std::string::npos);
    EXPECT_NE(kept.entities.find("\"_keepLights\" \"1\""), std::string::npos);
}

TEST(StructureEmit, CommandLineValueKeepsThePreviousOne) {
    EXPECT_EQ(commandLineValue("", {}), "-bsp");
    EXPECT_EQ(commandLineValue("-bsp -meta", {"-meta", "a\\b"}), "-bsp -meta; -bsp -meta ab");
}

}  // namespace
}  // namespace q3::bspstage
