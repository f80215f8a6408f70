#include <gtest/gtest.h>

#include <cstdio>
#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "bsp_tree.h"
#include "solid_shell.h"
#include "test_data.h"

namespace q3::light {
namespace {

TEST(BspTreeRealData, SpawnPointsAreInOpenSpace) {
    int maps = 0, spawns = 0;
    for (const std::string name : {"oa_dm1", "oa_dm4", "oacmpdm1"}) {
        const bsp::Bsp b = bsp::readBsp(test::realBsp(name));
        const BspTree tree(b);
        const auto entities = bsp::parseEntities(b.entities, name);
        ASSERT_GT(tree.numClusters(), 0) << name;
        for (const auto& e : entities) {
            if (e.classname() != "info_player_deathmatch") continue;
            float x, y, z;
            ASSERT_EQ(std::sscanf(e.value("origin").c_str(), "%f %f %f", &x, &y, &z), 3);
            const Vec3 origin{x, y, z};
            const int cluster = tree.clusterForPointExt(origin, 0.0f);
            EXPECT_GE(cluster, 0) << name << " spawn at " << e.value("origin");
            EXPECT_EQ(cluster, tree.clusterForPoint(origin));
            EXPECT_GE(tree.areaForPoint(origin), 0);
            EXPECT_TRUE(tree.clusterVisible(cluster, cluster));
            // Straight down from a spawn point there is a floor: some point within 256 units is solid,
            // and the nudge search from there finds open space again within 16 units.
            bool foundSolid = false;
            for (int d = 1; d <= 256 && !foundSolid; ++d) {
                const Vec3 below = origin - Vec3{0, 0, float(d)};
                if (!tree.pointInSolid(below)) continue;
                foundSolid = true;
                const auto free = tree.nudgeOutOfSolid(below, 16.0f, 1.0f);
                ASSERT_TRUE(free.has_value()) << name;
                EXPECT_FALSE(tree.pointInSolid(*free));
                EXPECT_LE(distance(*free, below), 16.0f);
            }
            EXPECT_TRUE(foundSolid) << name << " spawn at " << e.value("origin");
            ++spawns;
        }
        // Far outside a sealed world: no cluster. oa_dm4 was compiled with a leak, so its outside
        // leafs carry clusters and only the sealed maps are checked.
        if (name != "oa_dm4") {
            for (const Vec3 far : {Vec3{60000, 60000, 60000}, Vec3{-60000, -60000, -60000}}) {
                EXPECT_LT(tree.clusterForPoint(far), 0) << name;
                EXPECT_TRUE(tree.pointInSolid(far)) << name;
            }
        }
        ++maps;
    }
    EXPECT_EQ(maps, 3);
    EXPECT_GE(spawns, 12);
}

TEST(BspTreeRealData, VisibilityMatchesTheLumpBits) {
    const bsp::Bsp b = bsp::readBsp(test::realBsp("oa_dm4"));
    const BspTree tree(b);
    ASSERT_GT(b.visibility.size(), 8u);
    int32_t header[2];
    std::memcpy(header, b.visibility.data(), 8);
    ASSERT_EQ(tree.numClusters(), header[0]);
    int visible = 0;
    for (int a = 0; a < header[0]; ++a)
        for (int c = 0; c < header[0]; ++c) {
            const bool bit = (b.visibility[8 + size_t(a) * header[1] + (c >> 3)] >> (c & 7)) & 1;
            EXPECT_EQ(tree.clusterVisible(a, c), a == c || bit);
            visible += tree.clusterVisible(a, c);
        }
    EXPECT_GT(visible, header[0]);
    EXPECT_LT(visible, header[0] * header[0]);
}

TEST(BspTreeRealData, CompactWalksMatchThePlainOnes) {
    for (const std::string name : {"oa_dm4", "oacmpdm1"}) {
        const bsp::Bsp b = bsp::readBsp(test::realBsp(name));
        const BspTree compact(b), plain(b, {}, false);
        ASSERT_TRUE(compact.usesCompactTree()) << name;
        const bsp::Model& world = b.models[0];
        std::mt19937 rng(7);
        auto coord = [&](int axis) {
            const float t = std::uniform_real_distribution<float>(-0.1f, 1.1f)(rng);
            // Every third coordinate whole: the lattice axial planes sit on.
            const float v = world.mins[axis] + t * (world.maxs[axis] - world.mins[axis]);
            return rng() % 3 == 0 ? std::round(v) : v;
        };
        const std::vector<Vec3> box = nudgeOffsetsInBox({32, 32, 64}, 4);
        int solid = 0, entries = 0;
        for (int i = 0; i < 20000; ++i) {
            const Vec3 p{coord(0), coord(1), coord(2)}, q{coord(0), coord(1), coord(2)};
            ASSERT_EQ(compact.leafForPoint(p), plain.leafForPoint(p)) << name << " " << i;
            ASSERT_EQ(compact.clusterForPointExt(p, 0.0f), plain.clusterForPointExt(p, 0.0f));
            ASSERT_EQ(compact.segmentCrossesSolid(p, q), plain.segmentCrossesSolid(p, q)) << name << " " << i;
            const std::optional<Vec3> entry = compact.segmentSolidEntry(p, q);
            ASSERT_EQ(entry, plain.segmentSolidEntry(p, q)) << name << " " << i;
            entries += entry.has_value() && !(*entry == p) ? 1 : 0;
            if (i % 10 == 0 && compact.pointInSolid(p)) {
                ++solid;
                ASSERT_EQ(compact.nudgeOutOfSolid(p, box, -0.125f), plain.nudgeOutOfSolid(p, box, -0.125f));
            }
        }
        EXPECT_GT(solid, 50) << name;
        EXPECT_GT(entries, 1000) << name;  // segments that start open and enter solid on the way
    }
}

// A hinted point walk gives the walk from the root's leaf, whatever the hint: points wandering in
// small steps (the hint mostly right), points within 0.1 of the lattice's axial planes (where the
// walk may take either side) and hints picked at random.
TEST(BspTreeRealData, HintedWalksMatchTheWalkFromTheRoot) {
    for (const std::string name : {"oa_dm4", "oacmpdm1"}) {
        const bsp::Bsp b = bsp::readBsp(test::realBsp(name));
        const BspTree tree(b);
        ASSERT_TRUE(tree.usesCompactTree()) << name;
        const bsp::Model& world = b.models[0];
        std::mt19937 rng(11);
        std::uniform_real_distribution<float> unit(0, 1), step(-24, 24);
        const float nearPlane[] = {0.0f, 0.05f, -0.05f, 0.1f, -0.1f, 0.11f, -0.11f, 0.125f};
        BspTree::LeafHint hint;
        Vec3 p{};
        int same = 0;
        for (int i = 0; i < 60000; ++i) {
            if (i % 500 == 0) {
                for (int axis = 0; axis < 3; ++axis)
                    p[axis] = world.mins[axis] + unit(rng) * (world.maxs[axis] - world.mins[axis]);
            } else {
                p += Vec3{step(rng), step(rng), step(rng)} * (i % 7 == 0 ? 0.01f : 0.25f);
            }
            Vec3 q = p;
            if (i % 3 == 0) {
                const int axis = int(rng() % 3);
                q[axis] = std::round(q[axis] / 8) * 8 + nearPlane[rng() % 8];
            }
            if (i % 97 == 0) hint.leaf = int32_t(rng() % b.leafs.size());
            const int before = hint.leaf;
            const int leaf = tree.leafForPoint(q, hint);
            ASSERT_EQ(leaf, tree.leafForPoint(q)) << name << " " << i;
            same += leaf == before;
            BspTree::LeafHint other = hint;
            ASSERT_EQ(tree.clusterForPointExt(q, 0.125f, other), tree.clusterForPointExt(q, 0.125f)) << name << " " << i;
        }
        EXPECT_GT(same, 30000) << name;  // the hint was mostly the answer
    }
}

// On real maps, every segment whose walk enters structural solid meets a cell of the solid shell,
// and most segments that stay open meet none (so their walks are saved).
TEST(BspTreeRealData, SolidShellHoldsEveryWalkIntoSolid) {
    for (const std::string name : {"oa_dm4", "oacmpdm1"}) {
        const bsp::Bsp b = bsp::readBsp(test::realBsp(name));
        const BspTree tree(b);
        const SolidShell shell = solidShellOf(&b.models[0], tree);
        ASSERT_FALSE(shell.empty()) << name;
        const bsp::Model& world = b.models[0];
        std::mt19937 rng(11);
        auto coord = [&](int axis) {
            const float t = std::uniform_real_distribution<float>(0.0f, 1.0f)(rng);
            const float v = world.mins[axis] + t * (world.maxs[axis] - world.mins[axis]);
            return rng() % 3 == 0 ? std::round(v) : v;
        };
        int crossing = 0, open = 0, spared = 0;
        for (int i = 0; i < 1500; ++i) {
            const Vec3 p{coord(0), coord(1), coord(2)};
            // Half the segments short, so that many stay in open space.
            const Vec3 q = i % 2 ? Vec3{coord(0), coord(1), coord(2)}
                                 : p + Vec3{float(int(rng() % 65) - 32), float(int(rng() % 65) - 32),
                                            float(int(rng() % 65) - 32)};
            if (!shell.region.contains(p) || !shell.region.contains(q)) continue;
            const bool meets = shell.segmentMeetsAnyCell(p, q);
            if (tree.segmentCrossesSolid(p, q)) {
                ASSERT_TRUE(meets) << name << " " << i;
                ++crossing;
            } else {
                ++open;
                spared += !meets;
            }
        }
        EXPECT_GT(crossing, 300) << name;
        EXPECT_GT(open, 50) << name;
        EXPECT_GT(spared, open / 2) << name;
    }
}

}  // namespace
}  // namespace q3::light
