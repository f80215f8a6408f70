// Every malformed lump the light cache reads is refused with one line naming the map, the lump and
// the fault, and a refused load keeps nothing of the map.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "light_cache.h"
#include "light_cache_test_bsp.h"
#include "sh_test_support.h"

namespace q3::sh {
namespace {

using test::putF32;
using test::putU32;

struct Malformed {
    const char* name;
    std::function<void(test::TestLumps&)> edit;
    const char* expected;  // part of the message
};

// The pillar room with two clusters that see each other, so the visibility lump is there too.
test::TestMap roomWithVisibility() {
    test::TestMap map = test::roomWithPillar();
    map.numClusters = 2;
    map.cluster = [](const float*, const float maxs[3]) { return maxs[0] <= 0 ? 0 : 1; };
    map.visible = [](int32_t, int32_t) { return true; };
    return map;
}

TEST(LightCacheMalformed, EveryFaultIsOneLineNamingIt) {
    constexpr size_t kNode = 36, kLeaf = 48, kSide = 8, kBrush = 12;
    const std::vector<Malformed> cases = {
        {"truncated nodes", [](auto& l) { l.lumps[3].pop_back(); }, "BSP nodes lump: 2267 bytes is not a multiple of 36"},
        {"no nodes", [](auto& l) { l.lumps[3].clear(); }, "BSP nodes lump: empty"},
        {"node child past the end", [](auto& l) { putU32(l.lumps[3], 4, 999); }, "node 0 child 999 is not a later node (63 nodes)"},
        {"node child loops back", [&](auto& l) { putU32(l.lumps[3], kNode + 4, 1); }, "node 1 child 1 is not a later node"},
        {"node reached twice", [&](auto& l) { putU32(l.lumps[3], 8, 1); }, "node 0 child 1 is reached twice"},
        {"node leaf out of range", [&](auto& l) { putU32(l.lumps[3], 62 * kNode + 4, uint32_t(-1000)); }, "names leaf 999 of 64"},
        {"leaf reached twice", [&](auto& l) { putU32(l.lumps[3], 62 * kNode + 8, uint32_t(-63)); }, "is reached twice"},
        {"node plane", [](auto& l) { putU32(l.lumps[3], 0, 5000); }, "node 0 plane 5000 is not in 0..47"},
        {"side plane", [&](auto& l) { putU32(l.lumps[9], 3 * kSide, 48); }, "BSP brushsides lump: side 3 plane 48 is not in 0..47"},
        {"side shader", [&](auto& l) { putU32(l.lumps[9], 4, uint32_t(-1)); }, "side 0 shader -1 is not in 0..3"},
        {"truncated sides", [](auto& l) { l.lumps[9].resize(l.lumps[9].size() - 3); }, "BSP brushsides lump: 333 bytes"},
        {"brush sides", [&](auto& l) { putU32(l.lumps[8], 6 * kBrush, 40); }, "brush 6 sides 40 + 6 run past the 42 brush sides"},
        {"brush shader", [&](auto& l) { putU32(l.lumps[8], 8, 4); }, "brush 0 shader 4 is not in 0..3"},
        {"leaf brush", [](auto& l) { putU32(l.lumps[6], 0, 7); }, "BSP leafbrushes lump: entry 0 brush 7 is not in 0..6"},
        {"leaf brushes", [&](auto& l) { putU32(l.lumps[4], 44, 100000); }, "BSP leafs lump: leaf 0 brushes 0 + 100000 run past"},
        {"leaf cluster", [](auto& l) { putU32(l.lumps[4], 0, 2); }, "BSP leafs lump: leaf 0 cluster 2 is not in -1..1"},
        {"leaf cluster below -1", [&](auto& l) { putU32(l.lumps[4], 5 * kLeaf, uint32_t(-2)); }, "leaf 5 cluster -2"},
        {"no leafs", [](auto& l) { l.lumps[4].clear(); }, "BSP leafs lump: empty"},
        {"vis too short", [](auto& l) { l.lumps[16].pop_back(); }, "2 clusters of 1 bytes need 10 bytes, the lump has 9"},
        {"vis header", [](auto& l) { l.lumps[16].resize(6); }, "visibility lump: 6 bytes, shorter than its 8-byte header"},
        {"vis rows", [](auto& l) { putU32(l.lumps[16], 0, 9); }, "rows of 1 bytes cannot hold 9 clusters"},
        {"vis negative", [](auto& l) { putU32(l.lumps[16], 4, uint32_t(-1)); }, "negative cluster count 2 or row size -1"},
        {"plane", [](auto& l) { putF32(l.lumps[2], 16 * 3 + 12, std::nanf("")); }, "BSP planes lump: plane 3 is not finite"},
        {"planes size", [](auto& l) { l.lumps[2].push_back(0); }, "BSP planes lump: 769 bytes"},
        {"shaders size", [](auto& l) { l.lumps[1].resize(100); }, "BSP shaders lump: 100 bytes is not a multiple of 72"},
        {"light cluster", [](auto& l) { putU32(l.worldLights, 16 + 16, 2); }, "WORLDLIGHTS: light 0 cluster 2 is not below the map's 2 clusters"},
        {"world lights", [](auto& l) { l.worldLights[0] = 'X'; }, "WORLDLIGHTS: magic is not WLIT"},
    };
    const test::TestLumps good = test::testLumps(roomWithVisibility());
    {
        const std::vector<uint8_t> bsp = test::assembleTestBsp(good);
        LightCache cache;
        ASSERT_EQ(cache.loadFromBsp(bsp.data(), bsp.size(), "test.bsp"), "");
        ASSERT_EQ(cache.collision().nodes.size(), 63u);
        ASSERT_EQ(cache.collision().leafs.size(), 64u);
        ASSERT_EQ(cache.collision().planes.size(), 48u);
    }
    for (const Malformed& c : cases) {
        test::TestLumps lumps = good;
        c.edit(lumps);
        const std::vector<uint8_t> bsp = test::assembleTestBsp(lumps);
        LightCache cache;
        // A cache that held a map before: a failed load must not leave any of it behind.
        const std::vector<uint8_t> valid = test::assembleTestBsp(good);
        ASSERT_EQ(cache.loadFromBsp(valid.data(), valid.size()), "");
        const std::string error = cache.loadFromBsp(bsp.data(), bsp.size(), "test.bsp");
        EXPECT_TRUE(error.starts_with("test.bsp: ")) << c.name << ": " << error;
        EXPECT_NE(error.find(c.expected), std::string::npos) << c.name << ": " << error;
        EXPECT_EQ(error.find('\n'), std::string::npos) << c.name;
        EXPECT_TRUE(cache.lights().empty()) << c.name;
        EXPECT_TRUE(cache.collision().nodes.empty()) << c.name;
        const float p[3] = {200, 200, 64};
        EXPECT_EQ(cache.query(p).localCount, 0) << c.name;
    }
}

TEST(LightCacheMalformed, TreesDeeperThanTheLimitAreRefused) {
    // A chain: each node's back child is the next node, its front child a leaf.
    test::TestLumps lumps = test::testLumps(roomWithVisibility());
    const int32_t depth = kMaxTreeDepth + 1;
    std::vector<uint8_t> nodes(size_t(depth) * 36, 0), leafs(size_t(depth + 1) * 48, 0);
    for (int32_t i = 0; i < depth; ++i) {
        putU32(nodes, size_t(i) * 36 + 4, uint32_t(-1 - i));
        putU32(nodes, size_t(i) * 36 + 8, i + 1 < depth ? uint32_t(i + 1) : uint32_t(-1 - depth));
    }
    lumps.lumps[3] = nodes;
    lumps.lumps[4] = leafs;
    const std::vector<uint8_t> bsp = test::assembleTestBsp(lumps);
    LightCache cache;
    EXPECT_EQ(cache.loadFromBsp(bsp.data(), bsp.size()), "BSP nodes lump: the tree is deeper than 1024 levels");
    // One level less loads.
    nodes.resize(size_t(kMaxTreeDepth) * 36);
    putU32(nodes, size_t(kMaxTreeDepth - 1) * 36 + 8, uint32_t(-1 - kMaxTreeDepth));
    lumps.lumps[3] = nodes;
    lumps.lumps[4].resize(size_t(kMaxTreeDepth + 1) * 48);
    const std::vector<uint8_t> fits = test::assembleTestBsp(lumps);
    EXPECT_EQ(cache.loadFromBsp(fits.data(), fits.size()), "");
    const float p[3] = {0, 0, -5};  // behind plane 0 (the floor's x = 272 side) at every level
    EXPECT_GE(cache.query(p).leaf, 0);
}

TEST(LightCacheMalformed, NotABsp) {
    LightCache cache;
    const uint8_t junk[12] = {'I', 'B', 'S', 'P', 46, 0, 0, 0, 0, 0, 0, 0};
    EXPECT_EQ(cache.loadFromBsp(junk, sizeof junk, "x.bsp"), "x.bsp: BSP header truncated: 12 bytes");
    EXPECT_NE(cache.loadFromBsp(nullptr, 0).find("shorter than 8 bytes"), std::string::npos);
}

}  // namespace
}  // namespace q3::sh
