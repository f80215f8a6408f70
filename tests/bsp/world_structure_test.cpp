// The world structure steps on hand-made maps. The expected counts were worked out by hand; running
// the tests with Q3MAP_BSP_DUMP_MAPS=<dir> keeps the maps, and q3map2 2.5.17n -bsp writes .prt and
// .lin files byte-identical to ours for every one of them.
#include <gtest/gtest.h>

#include <sstream>

#include "bsp_test_maps.h"

namespace q3::bspstage {
namespace {

using test::boxBrush;
using test::compileMapText;
using test::hollowRoom;
using test::pointEntity;
using test::worldspawn;

std::vector<std::string> lines(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) out.push_back(line);
    return out;
}

DVec3 parsePoint(const std::string& line) {
    DVec3 p;
    std::istringstream(line) >> p.x >> p.y >> p.z;
    return p;
}

TEST(WorldStructure, SealedBoxInsideOneBlockIsOneClusterWithoutPortals) {
    // Inside 64..960 on every axis: no block boundary crosses the room.
    auto c = compileMapText(worldspawn(hollowRoom({64, 64, 64}, {960, 960, 960})) +
                            pointEntity("info_player_deathmatch", {512, 512, 100}));
    const WorldStructure& w = c->world;
    EXPECT_EQ(w.flood, FloodResult::Good);
    EXPECT_FALSE(w.leaked);
    EXPECT_TRUE(w.leakLine.empty());
    EXPECT_EQ(w.first.faceBsp.faces, 36);
    EXPECT_EQ(w.second.faceBsp.faces, 6);  // only the six inner faces are visible
    EXPECT_EQ(w.second.faceBsp.leafs, 7);
    EXPECT_EQ(w.clusters.clusters, 1);
    EXPECT_EQ(w.clusters.portals, 0);
    EXPECT_EQ(w.clusters.solidFaces, 6);
    EXPECT_EQ(w.areas, 1);
    const auto prt = lines(w.portalFile);
    ASSERT_EQ(prt.size(), 4u + 6u);
    EXPECT_EQ(prt[0], "PRT1");
    EXPECT_EQ(prt[1], "1");
    EXPECT_EQ(prt[2], "0");
    EXPECT_EQ(prt[3], "6");
    for (size_t i = 4; i < prt.size(); ++i) EXPECT_EQ(prt[i].rfind("4 0 (", 0), 0u) << prt[i];
}

TEST(WorldStructure, BlockBoundariesSplitARoomIntoClusters) {
    // The room straddles x = 0 and y = 0: the 1024-unit blocks cut it into four clusters joined by
    // four portals (two pieces on each cutting plane).
    auto c = compileMapText(worldspawn(hollowRoom({-448, -448, 64}, {448, 448, 448})) +
                            pointEntity("info_player_deathmatch", {100, 100, 100}));
    const WorldStructure& w = c->world;
    EXPECT_FALSE(w.leaked);
    EXPECT_EQ(w.clusters.clusters, 4);
    EXPECT_EQ(w.clusters.portals, 4);
    EXPECT_EQ(w.clusters.solidFaces, 4 * 4);  // two walls, floor and ceiling per quadrant
    EXPECT_EQ(w.areas, 1);
    const auto prt = lines(w.portalFile);
    ASSERT_GE(prt.size(), 8u);
    EXPECT_EQ(prt[4].substr(0, 2), "4 ");
    EXPECT_NE(prt[4].find(" 0 (0 "), std::string::npos);  // a portal on x = 0, flags 0
    // Blocks are aligned on multiples of their size, so 0 stays a boundary for any size; a block
    // size of 0 turns the forced splits off and keeps the room whole.
    auto whole = compileMapText(worldspawn(hollowRoom({-448, -448, 64}, {448, 448, 448}), "\"_blocksize\" \"0\"\n") +
                                pointEntity("info_player_deathmatch", {100, 100, 100}));
    EXPECT_EQ(whole->world.clusters.clusters, 1);
    EXPECT_EQ(whole->world.blockSize[1], 0);
}

TEST(WorldStructure, HoleInAWallLeaksAndTheLineRunsFromTheVoidToTheEntity) {
    // The +X wall has a 64-unit hole at y 480..544, z 480..544.
    auto leakyRoom = [](const std::string& keys) {
        return worldspawn(boxBrush({48, 48, 48}, {64, 976, 976}) + boxBrush({64, 48, 48}, {960, 64, 976}) +
                              boxBrush({64, 960, 48}, {960, 976, 976}) + boxBrush({64, 64, 48}, {960, 960, 64}) +
                              boxBrush({64, 64, 960}, {960, 960, 976}) +
                              // +X wall around the hole
                              boxBrush({960, 48, 48}, {976, 480, 976}) + boxBrush({960, 544, 48}, {976, 976, 976}) +
                              boxBrush({960, 480, 48}, {976, 544, 480}) + boxBrush({960, 480, 544}, {976, 544, 976}),
                          keys);
    };
    const std::string text = leakyRoom("");
    const DVec3 player{512, 512, 100};
    auto c = compileMapText(text + pointEntity("info_player_deathmatch", player));
    const WorldStructure& w = c->world;
    EXPECT_EQ(w.flood, FloodResult::Leaked);
    EXPECT_TRUE(w.leaked);
    EXPECT_TRUE(w.portalFile.empty());
    EXPECT_EQ(w.leakingEntity, 1);
    const auto lin = lines(w.leakLine);
    ASSERT_GE(lin.size(), 2u);
    EXPECT_EQ(lin.back(), "512.000000 512.000000 100.000000");
    // The walk starts at a portal of the outside node: on the padded tree bounds.
    const DVec3 first = parsePoint(lin.front());
    EXPECT_TRUE(first.x <= 40 || first.x >= 984 || first.y <= 40 || first.y >= 984 || first.z <= 40 || first.z >= 984)
        << lin.front();
    // Every step gets closer to the entity's leaf, so the line passes the hole (x = 960..976).
    bool throughHole = false;
    for (const std::string& l : lin) {
        const DVec3 p = parsePoint(l);
        if (p.x >= 960 && p.x <= 976 && p.y >= 480 && p.y <= 544 && p.z >= 480 && p.z <= 544) throughHole = true;
    }
    EXPECT_TRUE(throughHole) << w.leakLine;

    WorldStructureOptions leakTest;
    leakTest.leakTest = true;
    auto stopped = compileMapText(text + pointEntity("info_player_deathmatch", player), leakTest);
    EXPECT_TRUE(stopped->world.stoppedForLeakTest);
    EXPECT_EQ(stopped->world.leakLine, w.leakLine);
    EXPECT_EQ(stopped->world.clusters.clusters, 0);

    // _ignoreleaks treats the same map as sealed and writes a portal file.
    auto ignored = compileMapText(leakyRoom("\"_ignoreleaks\" \"1\"\n") + pointEntity("info_player_deathmatch", player));
    EXPECT_EQ(ignored->world.flood, FloodResult::Good);
    EXPECT_FALSE(ignored->world.portalFile.empty());
}

TEST(WorldStructure, NoEntityInOpenSpaceIsEmptyAndCountsAsLeaked) {
    auto c = compileMapText(worldspawn(hollowRoom({64, 64, 64}, {960, 960, 960})) +
                            pointEntity("info_player_deathmatch", {56, 512, 512}));  // inside the -X wall (48..64)
    EXPECT_EQ(c->world.flood, FloodResult::Empty);
    EXPECT_TRUE(c->world.leaked);
    EXPECT_TRUE(c->world.leakLine.empty());
    EXPECT_TRUE(c->world.portalFile.empty());
    EXPECT_EQ(c->world.second.faceBsp.faces, 0);  // the second tree is never built
}

TEST(WorldStructure, HintBrushesSplitFirstAndMakeHintPortals) {
    // A hint brush across the middle of a one-block room (x 500..508).
    auto c = compileMapText(worldspawn(hollowRoom({64, 64, 64}, {960, 960, 960}) +
                                       boxBrush({500, 64, 64}, {508, 960, 960}, "common/hint")) +
                            pointEntity("info_player_deathmatch", {200, 512, 100}));
    const WorldStructure& w = c->world;
    const TreeNode& root = w.tree.node(w.tree.head);
    ASSERT_FALSE(root.isLeaf());
    EXPECT_TRUE(root.compileFlags & compileflags::Hint);
    EXPECT_EQ(c->map.planes[root.planeNum].type, PlaneX);
    // Two hint planes make three clusters in a row, joined by two hint portals.
    EXPECT_EQ(w.clusters.clusters, 3);
    EXPECT_EQ(w.clusters.portals, 2);
    const auto prt = lines(w.portalFile);
    ASSERT_GE(prt.size(), 6u);
    for (int i = 4; i < 6; ++i) {
        std::istringstream fields(prt[size_t(i)]);
        int points = 0, a = 0, b = 0, flags = 0;
        fields >> points >> a >> b >> flags;
        EXPECT_EQ(flags, 1) << prt[size_t(i)];  // bit 0: hint
    }
}

TEST(WorldStructure, DetailBrushesMakeNoPortalsOrClusters) {
    const std::string room = hollowRoom({64, 64, 64}, {960, 960, 960});
    const std::string player = pointEntity("info_player_deathmatch", {200, 200, 100});
    auto detail = compileMapText(worldspawn(room + boxBrush({448, 448, 64}, {576, 576, 960}, "base/wall", true)) + player);
    EXPECT_EQ(detail->world.clusters.clusters, 1);
    EXPECT_EQ(detail->world.clusters.portals, 0);
    EXPECT_EQ(detail->world.second.faceBsp.faces, 6);
    // The same pillar structural splits the room.
    auto structural = compileMapText(worldspawn(room + boxBrush({448, 448, 64}, {576, 576, 960})) + player);
    EXPECT_GT(structural->world.clusters.clusters, 1);
    EXPECT_GT(structural->world.clusters.portals, 0);
}

TEST(WorldStructure, AreaportalSeparatesAreas) {
    // Two rooms side by side (x 64..496 and 528..960) joined by a doorway in the wall between them;
    // the doorway (y 448..576, z 64..192) is filled with an areaportal brush.
    auto twoRooms = [](const std::string& doorway) {
        std::string s = boxBrush({48, 48, 48}, {64, 976, 976}) + boxBrush({960, 48, 48}, {976, 976, 976}) +
                        boxBrush({64, 48, 48}, {960, 64, 976}) + boxBrush({64, 960, 48}, {960, 976, 976}) +
                        boxBrush({64, 64, 48}, {960, 960, 64}) + boxBrush({64, 64, 960}, {960, 960, 976});
        // The dividing wall x 496..528 with the doorway cut out.
        s += boxBrush({496, 64, 64}, {528, 448, 960}) + boxBrush({496, 576, 64}, {528, 960, 960}) +
             boxBrush({496, 448, 192}, {528, 576, 960});
        return worldspawn(s + doorway) + pointEntity("info_player_deathmatch", {200, 512, 100}) +
               pointEntity("info_player_deathmatch", {800, 512, 100});
    };
    auto open = compileMapText(twoRooms(""));
    EXPECT_FALSE(open->world.leaked);
    EXPECT_EQ(open->world.areas, 1);
    auto portal = compileMapText(twoRooms(boxBrush({496, 448, 64}, {528, 576, 192}, "common/areaportal")));
    EXPECT_FALSE(portal->world.leaked);
    EXPECT_EQ(portal->world.areas, 2);
    // The doorway is a leaf of its own either way; only the area flood stops at the areaportal.
    EXPECT_EQ(portal->world.clusters.clusters, open->world.clusters.clusters);
    EXPECT_EQ(portal->world.clusters.portals, open->world.clusters.portals);
    // Leaves on each side of the doorway belong to different areas.
    const Tree& t = portal->world.tree;
    auto areaAt = [&](DVec3 p) {
        int n = t.head;
        while (!t.node(n).isLeaf())
            n = t.node(n).children[portal->map.planes[t.node(n).planeNum].plane.distanceTo(p) >= 0 ? 0 : 1];
        return t.node(n).area;
    };
    EXPECT_NE(areaAt({200, 512, 100}), areaAt({800, 512, 100}));
    EXPECT_GE(areaAt({200, 512, 100}), 0);
}

TEST(WorldStructure, SameInputGivesTheSameOutput) {
    const std::string text = worldspawn(hollowRoom({-448, -448, 64}, {448, 448, 448}) +
                                        boxBrush({-40, -300, 64}, {40, 300, 200})) +
                             pointEntity("info_player_deathmatch", {100, 100, 300});
    auto a = compileMapText(text);
    auto b = compileMapText(text);
    EXPECT_EQ(a->world.portalFile, b->world.portalFile);
    EXPECT_FALSE(a->world.portalFile.empty());
}

}  // namespace
}  // namespace q3::bspstage
