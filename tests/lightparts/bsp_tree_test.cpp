#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <limits>

#include <cmath>
#include <cstring>

#include "bsp_tree.h"
#include "test_data.h"

namespace q3::light {
namespace {

// One node splitting at x = 0: leaf 0 (x > 0, cluster 0) and leaf 1 (x < 0, cluster 1) holding a
// brush spanning x -64..-32, y and z -16..16.
bsp::Bsp twoLeafBsp() {
    bsp::Bsp b;
    bsp::Shader solid{};
    std::strcpy(solid.name, "textures/test/solid");
    solid.contentFlags = contents::kSolid;
    b.shaders = {solid};
    b.planes = {{{1, 0, 0}, 0},   {{1, 0, 0}, -32}, {{-1, 0, 0}, 64}, {{0, 1, 0}, 16},
                {{0, -1, 0}, 16}, {{0, 0, 1}, 16},  {{0, 0, -1}, 16}};
    b.nodes = {{0, {-1, -2}, {-1000, -1000, -1000}, {1000, 1000, 1000}}};
    b.leafs = {{0, 0, {0, -1000, -1000}, {1000, 1000, 1000}, 0, 0, 0, 0},
               {1, 1, {-1000, -1000, -1000}, {0, 1000, 1000}, 0, 0, 0, 1}};
    b.leafBrushes = {0};
    b.brushes = {{0, 6, 0}};
    for (int i = 1; i <= 6; ++i) b.brushSides.push_back({i, 0});
    b.models = {{{-1000, -1000, -1000}, {1000, 1000, 1000}, 0, 0, 0, 1}};
    // 2 clusters, 1 byte per row: cluster 0 sees only itself, cluster 1 sees both.
    b.visibility = {2, 0, 0, 0, 1, 0, 0, 0, 0x01, 0x03};
    return b;
}

TEST(BspTree, LeafClusterArea) {
    const bsp::Bsp b = twoLeafBsp();
    const BspTree tree(b);
    EXPECT_EQ(tree.leafForPoint({10, 0, 0}), 0);
    EXPECT_EQ(tree.leafForPoint({-10, 0, 0}), 1);
    EXPECT_EQ(tree.clusterForPoint({-10, 0, 0}), 1);
    EXPECT_EQ(tree.areaForPoint({-10, 0, 0}), 1);
    // On the plane (within 0.1): the front leaf wins because it has a cluster.
    EXPECT_EQ(tree.leafForPoint({0.05f, 0, 0}), 0);
    EXPECT_EQ(tree.leafForPoint({-0.05f, 0, 0}), 0);
    EXPECT_EQ(tree.leafForPoint({-0.2f, 0, 0}), 1);
    bsp::Bsp noCluster = b;
    noCluster.leafs[0].cluster = -1;
    EXPECT_EQ(BspTree(noCluster).leafForPoint({0.05f, 0, 0}), 1);
    // Non-finite points (from hostile vertex data) lie in no leaf, and the walk ends at once.
    const float nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_EQ(tree.leafForPoint({nan, 0, 0}), -1);
    EXPECT_EQ(tree.clusterForPoint({0, std::numeric_limits<float>::infinity(), 0}), -1);
    EXPECT_LT(tree.clusterForPointExt({nan, nan, nan}, 0), 0);
}

TEST(BspTree, Visibility) {
    bsp::Bsp b = twoLeafBsp();
    const BspTree tree(b);
    EXPECT_EQ(tree.numClusters(), 2);
    EXPECT_TRUE(tree.clusterVisible(0, 0));
    EXPECT_FALSE(tree.clusterVisible(0, 1));
    EXPECT_TRUE(tree.clusterVisible(1, 0));
    EXPECT_FALSE(tree.clusterVisible(-1, 0));
    b.visibility.clear();
    EXPECT_TRUE(BspTree(b).clusterVisible(0, 1));
}

TEST(BspTree, PointInOpaqueBrush) {
    bsp::Bsp b = twoLeafBsp();
    const BspTree tree(b);
    EXPECT_TRUE(tree.brushIsOpaque(0));
    EXPECT_EQ(tree.clusterForPointExt({-48, 0, 0}, 0), -1);  // -1 - brush 0
    EXPECT_TRUE(tree.pointInSolid({-48, 0, 0}));
    EXPECT_EQ(tree.clusterForPointExt({-20, 0, 0}, 0), 1);
    EXPECT_EQ(tree.clusterForPointExt({-48, 0, 16.1f}, 0), 1);
    // Epsilon: a point 0.1 outside counts as inside with epsilon 0.125 (q3map2's LUXEL_EPSILON).
    EXPECT_EQ(tree.clusterForPointExt({-48, 0, 16.1f}, 0.125f), -1);
    // A water brush does not block light; the caller's shader table can override.
    b.shaders[0].contentFlags = contents::kWater;
    EXPECT_EQ(BspTree(b).clusterForPointExt({-48, 0, 0}, 0), 1);
    const uint8_t opaqueOverride[] = {0};
    EXPECT_EQ(BspTree(b, opaqueOverride).clusterForPointExt({-48, 0, 0}, 0), -1);
    b.shaders[0].contentFlags = contents::kSolid;
    b.shaders[0].surfaceFlags = contents::kSurfAlphaShadow;
    EXPECT_FALSE(BspTree(b).brushIsOpaque(0));
}

TEST(BspTree, BoxInSolidOnlyWhenEveryPointIs) {
    const bsp::Bsp b = twoLeafBsp();
    const BspTree tree(b);
    // Wholly inside the brush (x -64..-32, y and z -16..16): solid.
    EXPECT_TRUE(tree.boxInSolid({-60, -10, -10}, {-36, 10, 10}));
    // Reaching 0.2 past its top: points there are free, even with epsilon 0.125.
    EXPECT_FALSE(tree.boxInSolid({-60, -10, -10}, {-36, 10, 16.2f}));
    EXPECT_FALSE(tree.boxInSolid({-60, -10, -10}, {-36, 10, 16.2f}, 0.125f));
    // 0.05 past it counts as inside within epsilon 0.125, not within 0.
    EXPECT_TRUE(tree.boxInSolid({-60, -10, -10}, {-36, 10, 16.05f}, 0.125f));
    EXPECT_FALSE(tree.boxInSolid({-60, -10, -10}, {-36, 10, 16.05f}));
    // The open leaf, and boxes that are not boxes.
    EXPECT_FALSE(tree.boxInSolid({10, 0, 0}, {20, 5, 5}));
    EXPECT_FALSE(tree.boxInSolid({-36, 0, 0}, {-60, 5, 5}));
    EXPECT_FALSE(tree.boxInSolid({-60, 0, 0}, {-36, std::numeric_limits<float>::infinity(), 5}));

    // Leaf 0 outside every cluster: solid, but within 0.1 of the node's plane a point may end in
    // leaf 1 (which has a cluster), so a box reaching that band is not.
    bsp::Bsp outside = b;
    outside.leafs[0].cluster = -1;
    const BspTree outsideTree(outside);
    EXPECT_TRUE(outsideTree.boxInSolid({5, -100, -100}, {50, 100, 100}));
    EXPECT_FALSE(outsideTree.boxInSolid({0.05f, -100, -100}, {50, 100, 100}));
    // Across the plane into leaf 1: its part between the brush and the plane is free.
    EXPECT_FALSE(outsideTree.boxInSolid({-40, -10, -10}, {50, 10, 10}));

    // Every verdict of solid holds for a lattice of points inside the box.
    for (const BspTree* t : {&tree, &outsideTree})
        for (float x0 : {-70.0f, -60.0f, -33.0f, -0.2f, 0.0f, 2.0f})
            for (float width : {1.0f, 10.0f, 40.0f}) {
                const Vec3 lo{x0, -12, -17}, hi{x0 + width, 12, 15.9f};
                if (!t->boxInSolid(lo, hi, -0.125f)) continue;
                for (int i = 0; i <= 8; ++i)
                    for (int j = 0; j <= 8; ++j) {
                        const Vec3 p = lo + (hi - lo) * Vec3{float(i) / 8, float(j) / 8, float((i + j) % 9) / 8};
                        EXPECT_TRUE(t->pointInSolid(p, -0.125f)) << p.x << " " << p.y << " " << p.z;
                    }
            }
}

TEST(BspTree, NudgeSearchIsNearestFirst) {
    const auto offsets = nudgeOffsets(2.0f, 1.0f);
    ASSERT_FALSE(offsets.empty());
    EXPECT_EQ(offsets[0], (Vec3{0, 0, 0}));
    EXPECT_EQ(offsets[1], (Vec3{0, 0, -1}));  // length 1, then by z, y, x
    EXPECT_EQ(offsets.back(), (Vec3{0, 0, 2}));
    // 1 + 6 + 12 + 8 (len^2 <= 3) + 6 (len 2) = 33 lattice points within radius 2.
    EXPECT_EQ(offsets.size(), 33u);
    for (size_t i = 1; i < offsets.size(); ++i) EXPECT_LE(dot(offsets[i - 1], offsets[i - 1]), dot(offsets[i], offsets[i]));

    const bsp::Bsp b = twoLeafBsp();
    const BspTree tree(b);
    // Inside the brush, 2 units below its top face: the nearest free lattice point is 3 units up.
    const auto free = tree.nudgeOutOfSolid({-48, 0, 14}, 4.0f, 1.0f);
    ASSERT_TRUE(free.has_value());
    EXPECT_EQ(*free, (Vec3{-48, 0, 17}));
    EXPECT_FALSE(tree.nudgeOutOfSolid({-48, 0, 0}, 4.0f, 1.0f).has_value());
    EXPECT_EQ(*tree.nudgeOutOfSolid({10, 0, 0}, 4.0f, 1.0f), (Vec3{10, 0, 0}));
    const auto coarse = nudgeOffsets(8.0f, 4.0f);  // 0, +-4, +-8 per axis within radius 8
    EXPECT_EQ(*tree.nudgeOutOfSolid({-48, 0, 14}, coarse), (Vec3{-48, 0, 18}));
}


TEST(BspTree, SegmentCrossesSolidLeafOnly) {
    // Leaf 0 (x > 0) has a cluster; leaf 1 (x < 0) is made solid (no cluster), as structural
    // brushes are after -bsp. Its detail brush does not matter to the walk.
    bsp::Bsp b = twoLeafBsp();
    b.leafs[1].cluster = -1;
    const BspTree tree(b);
    EXPECT_FALSE(tree.segmentCrossesSolid({10, 0, 0}, {100, 5, -3}));
    EXPECT_TRUE(tree.segmentCrossesSolid({10, 0, 0}, {-10, 0, 0}));
    EXPECT_TRUE(tree.segmentCrossesSolid({-10, 0, 0}, {10, 0, 0}));
    // Within 0.1 of the plane counts as on the front side (q3map2's TRACE_ON_EPSILON).
    EXPECT_FALSE(tree.segmentCrossesSolid({10, 0, 0}, {-0.05f, 0, 0}));
    EXPECT_TRUE(tree.segmentCrossesSolid({10, 0, 0}, {-0.2f, 0, 0}));
    // Along the plane itself: front side, open.
    EXPECT_FALSE(tree.segmentCrossesSolid({0, -50, 0}, {0, 50, 0}));
    // Where the segment enters the solid leaf: on the plane, or at its start when it starts inside.
    EXPECT_EQ(*tree.segmentSolidEntry({10, 0, 0}, {-10, 0, 0}), (Vec3{0, 0, 0}));
    EXPECT_EQ(*tree.segmentSolidEntry({0, 5, 0}, {-10, 5, 0}), (Vec3{0, 5, 0}));
    EXPECT_EQ(*tree.segmentSolidEntry({-10, 0, 0}, {10, 0, 0}), (Vec3{-10, 0, 0}));
    EXPECT_FALSE(tree.segmentSolidEntry({10, 0, 0}, {100, 5, -3}).has_value());
    // With both leafs in clusters only the detail brush is between: nothing solid is crossed.
    EXPECT_FALSE(BspTree(twoLeafBsp()).segmentCrossesSolid({10, 0, 0}, {-100, 0, 0}));
    // No node tree: nothing can be tested, nothing blocks.
    bsp::Bsp flat = b;
    flat.nodes.clear();
    EXPECT_FALSE(BspTree(flat).segmentCrossesSolid({10, 0, 0}, {-10, 0, 0}));
    // A node pointing at itself ends instead of looping.
    bsp::Bsp loop = b;
    loop.nodes[0].children[0] = 0;
    loop.nodes[0].children[1] = 0;
    EXPECT_FALSE(BspTree(loop).segmentCrossesSolid({10, 0, 0}, {20, 0, 0}));
}

TEST(BspTree, PolygonInSolidOnlyWhenEveryPartIs) {
    bsp::Bsp b = twoLeafBsp();
    b.leafs[1].cluster = -1;  // x < 0 solid
    const BspTree tree(b);
    const std::array<Vec3, 3> behind{Vec3{-0.5f, 0, 0}, Vec3{-0.5f, 100, 0}, Vec3{-0.5f, 0, 100}};
    EXPECT_TRUE(tree.polygonInSolid(behind));
    const std::array<Vec3, 4> deep{Vec3{-10, 0, 0}, Vec3{-200, 0, 0}, Vec3{-200, 0, 50}, Vec3{-10, 0, 50}};
    EXPECT_TRUE(tree.polygonInSolid(deep));
    // A polygon the plane cuts has a part in the open leaf.
    const std::array<Vec3, 3> across{Vec3{-5, 0, 0}, Vec3{5, 0, 0}, Vec3{-5, 0, 10}};
    EXPECT_FALSE(tree.polygonInSolid(across));
    // Within 0.01 of the plane counts as on both sides: not in solid.
    const std::array<Vec3, 3> touching{Vec3{-0.005f, 0, 0}, Vec3{-10, 0, 0}, Vec3{-10, 0, 10}};
    EXPECT_FALSE(tree.polygonInSolid(touching));
    EXPECT_FALSE(tree.polygonInSolid(std::array<Vec3, 3>{Vec3{1, 0, 0}, Vec3{2, 0, 0}, Vec3{1, 1, 0}}));
    // Both leafs in clusters, no node tree, a non-finite corner, too few corners: never in solid.
    EXPECT_FALSE(BspTree(twoLeafBsp()).polygonInSolid(behind));
    bsp::Bsp flat = b;
    flat.nodes.clear();
    EXPECT_FALSE(BspTree(flat).polygonInSolid(behind));
    const float nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_FALSE(tree.polygonInSolid(std::array<Vec3, 3>{Vec3{-1, 0, 0}, Vec3{nan, 0, 0}, Vec3{-1, 1, 0}}));
    EXPECT_FALSE(tree.polygonInSolid(std::span(behind.data(), 2)));
    // A node pointing at itself ends instead of looping.
    bsp::Bsp loop = b;
    loop.nodes[0].children[1] = 0;
    EXPECT_FALSE(BspTree(loop).polygonInSolid(behind));
}

TEST(BspTree, BoxNudgeSearchGoesRingByRing) {
    // Half a 64 x 64 x 128 cell: z steps are twice as long as x and y steps, and the search
    // widens the box in proportion, as q3map2's random nudges do.
    const auto offsets = nudgeOffsetsInBox({32, 32, 64}, 4);
    ASSERT_EQ(offsets.size(), 9u * 9u * 9u);
    EXPECT_EQ(offsets[0], (Vec3{0, 0, 0}));
    EXPECT_EQ(offsets[1], (Vec3{0, -8, 0}));  // first ring, shortest first, then by z, y, x
    for (const Vec3& o : offsets) {
        EXPECT_LE(std::fabs(o.x), 32.0f);
        EXPECT_LE(std::fabs(o.z), 64.0f);
    }
    // Every first-ring offset (one step of 8, 8, 16) comes before any second-ring one.
    auto ring = [](Vec3 o) { return std::max({std::fabs(o.x) / 8, std::fabs(o.y) / 8, std::fabs(o.z) / 16}); };
    for (size_t i = 1; i < offsets.size(); ++i) EXPECT_LE(ring(offsets[i - 1]), ring(offsets[i]) + 1e-6f);
    EXPECT_EQ(ring(offsets[26]), 1.0f);
    EXPECT_EQ(ring(offsets[27]), 2.0f);
}

}  // namespace
}  // namespace q3::light
