#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <random>
#include <tuple>
#include <utility>

#include "file_io.h"
#include "image.h"
#include "lightmap_pack.h"
#include "log.h"
#include "test_data.h"

namespace q3::light {
namespace {

// A w x h block whose texels all differ (so it is never solid), offset by `seed`.
LightmapBlock gradient(int w, int h, int seed, std::string key = "textures/a") {
    LightmapBlock b;
    b.width = w;
    b.height = h;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) b.texels.push_back({uint8_t(seed + x * 10), uint8_t(seed + y * 10), uint8_t(seed)});
    b.sortKey = std::move(key);
    return b;
}

LightmapBlock uniformBlock(int w, int h, Rgb8 c) {
    LightmapBlock b;
    b.width = w;
    b.height = h;
    b.texels.assign(size_t(w) * h, c);
    return b;
}

PackOptions slow(int pageSize) {
    PackOptions o;
    o.pageSize = pageSize;
    o.fastAllocate = false;
    return o;
}

TEST(LightmapPack, SolidBlocks) {
    EXPECT_TRUE(blockIsSolid(uniformBlock(3, 3, {10, 20, 30})));
    LightmapBlock b = uniformBlock(3, 3, {10, 20, 30});
    b.texels[4] = {10, 20, 31};
    EXPECT_FALSE(blockIsSolid(b));
    b.used.assign(9, 1);
    b.used[4] = 0;  // the odd texel is unused
    EXPECT_TRUE(blockIsSolid(b));
    EXPECT_TRUE(blockIsSolid(gradient(2, 2, 0)));  // at most 2 x 2 is always solid
    EXPECT_FALSE(blockIsSolid(gradient(3, 2, 0)));
}

TEST(LightmapPack, MatchingFollowsQ3map2Tolerances) {
    const LightmapBlock a = gradient(3, 3, 20);
    LightmapBlock b = a;
    EXPECT_TRUE(blocksMatch(a, b));
    b.texels[8][0] += 3;  // last texel: mean difference 3/768/9 is within tolerance
    EXPECT_TRUE(blocksMatch(a, b));
    b = a;
    b.texels[0][0] += 3;  // first texel: 3/768 already exceeds 0.0025 at that point
    EXPECT_FALSE(blocksMatch(a, b));
    b = a;
    b.texels[8][1] += 4;  // any channel off by more than 3
    EXPECT_FALSE(blocksMatch(a, b));
    EXPECT_FALSE(blocksMatch(a, gradient(3, 4, 20)));
    EXPECT_TRUE(blocksMatch(uniformBlock(5, 5, {1, 2, 3}), uniformBlock(2, 2, {1, 2, 3})));  // solids by colour
    EXPECT_FALSE(blocksMatch(uniformBlock(5, 5, {1, 2, 3}), uniformBlock(5, 5, {1, 2, 4})));
}

// A page that refused a whole rectangle skips larger ones later, but not a smaller or flatter one:
// on an 8 x 8 page holding 8 x 6, a 4 x 3 and then a 3 x 3 find no place, while a 3 x 2 still fits
// the two free rows. Fast allocation (steps of one texel at these sizes) and slow agree.
TEST(LightmapPack, RefusedRectanglesOnlySkipLargerOnes) {
    const std::vector<LightmapBlock> blocks = {gradient(8, 6, 0), gradient(4, 3, 40), gradient(3, 3, 80),
                                               gradient(3, 2, 120)};
    for (const bool fast : {false, true}) {
        PackOptions o = slow(8);
        o.fastAllocate = fast;
        o.collapse = false;
        const PackedLightmaps p = packLightmaps(blocks, o);
        ASSERT_EQ(p.pages.size(), 2u) << fast;
        EXPECT_EQ(std::tie(p.placements[0].page, p.placements[0].x, p.placements[0].y), std::tuple(0, 0, 0)) << fast;
        EXPECT_EQ(std::tie(p.placements[1].page, p.placements[1].x, p.placements[1].y), std::tuple(1, 0, 0)) << fast;
        EXPECT_EQ(std::tie(p.placements[2].page, p.placements[2].x, p.placements[2].y), std::tuple(1, 4, 0)) << fast;
        EXPECT_EQ(std::tie(p.placements[3].page, p.placements[3].x, p.placements[3].y), std::tuple(0, 0, 6)) << fast;
    }
}

TEST(LightmapPack, FirstFitInSortedOrder) {
    std::vector<LightmapBlock> blocks = {gradient(4, 4, 0, "b"), gradient(4, 4, 100, "a"), uniformBlock(3, 3, {7, 8, 9})};
    blocks[2].sortKey = "c";
    const PackedLightmaps p = packLightmaps(blocks, slow(8));
    ASSERT_EQ(p.pages.size(), 1u);
    EXPECT_EQ(p.placements[1].x, 0);  // "a" goes first
    EXPECT_EQ(p.placements[1].y, 0);
    EXPECT_EQ(p.placements[0].x, 4);
    EXPECT_EQ(p.placements[0].y, 0);
    // The solid block takes one texel at the first position where its full size would fit.
    EXPECT_TRUE(p.placements[2].solid);
    EXPECT_EQ(p.placements[2].x, 0);
    EXPECT_EQ(p.placements[2].y, 4);
    EXPECT_EQ(p.placements[2].width, 1);
    const auto& page = p.pages[0];
    auto texel = [&](int x, int y) { return Rgb8{page[(y * 8 + x) * 3], page[(y * 8 + x) * 3 + 1], page[(y * 8 + x) * 3 + 2]}; };
    EXPECT_EQ(texel(0, 4), (Rgb8{7, 8, 9}));
    EXPECT_EQ(texel(1, 4), (Rgb8{0, 0, 0}));
    EXPECT_EQ(texel(5, 2), (Rgb8{10, 20, 0}));    // block "b" texel (1, 2)
    EXPECT_EQ(texel(3, 3), (Rgb8{130, 130, 100}));  // block "a" texel (3, 3)
    // Larger blocks first within a shader.
    std::vector<LightmapBlock> sized = {gradient(2, 3, 0), gradient(5, 5, 0), gradient(3, 3, 50)};
    const PackedLightmaps q = packLightmaps(sized, slow(8));
    EXPECT_EQ(q.placements[1].x, 0);
    EXPECT_EQ(q.placements[2].x, 5);
    EXPECT_EQ(q.placements[0].y, 3);
    // Shared lightmaps compare the sorted shader names of their surfaces in turn, then fewer styles
    // (a larger sum of style slots) first, then the area.
    std::vector<LightmapBlock> shared = {gradient(4, 4, 0), gradient(4, 4, 100), gradient(4, 4, 170), gradient(2, 2, 9)};
    shared[0].shaderNames = {"a", "z"};
    shared[1].shaderNames = {"a", "b"};
    shared[2].shaderNames = {"a", "b"};
    shared[2].styleSum = 2 * 255;  // one more style: after its equal
    shared[3].shaderNames = {"c"};
    const PackedLightmaps r = packLightmaps(shared, slow(8));
    ASSERT_EQ(r.pages.size(), 1u);
    auto corner = [&](size_t i) { return std::pair<int, int>{r.placements[i].x, r.placements[i].y}; };
    EXPECT_EQ(corner(1), (std::pair<int, int>{0, 0}));
    EXPECT_EQ(corner(2), (std::pair<int, int>{4, 0}));
    EXPECT_EQ(corner(0), (std::pair<int, int>{0, 4}));
    EXPECT_EQ(corner(3), (std::pair<int, int>{4, 4}));  // the solid one: one texel
    EXPECT_TRUE(r.placements[3].solid);
}

TEST(LightmapPack, CollapseNoCollapseAndNoTwins) {
    std::vector<LightmapBlock> blocks = {gradient(4, 4, 0), gradient(4, 4, 0), uniformBlock(4, 4, {5, 5, 5})};
    auto packWith = [&](bool collapse, bool twins) {
        PackOptions o = slow(8);
        o.collapse = collapse;
        o.twins = twins;
        return packLightmaps(blocks, o);
    };
    // Whether the two identical blocks were stored apart, each with its own texels.
    auto apart = [](const PackedLightmaps& p) {
        return p.placements[1].twinOf == -1 &&
               p.placements[1].x + 8 * p.placements[1].y != p.placements[0].x + 8 * p.placements[0].y;
    };
    const PackedLightmaps p = packWith(true, true);
    EXPECT_EQ(p.placements[1].twinOf, 0);
    EXPECT_EQ(p.placements[1].page, p.placements[0].page);
    EXPECT_EQ(p.placements[1].x, p.placements[0].x);
    EXPECT_TRUE(p.placements[2].solid);
    const PackedLightmaps q = packWith(false, true);  // -nocollapse
    EXPECT_TRUE(apart(q));
    EXPECT_FALSE(q.placements[2].solid);
    EXPECT_EQ(q.placements[2].width, 4);
    EXPECT_EQ(q.pages.size(), 1u);
    // -deluxe (no twins): q3map2 keeps identical lightmaps apart, each with its own directions,
    // but still stores a solid one as a single texel.
    const PackedLightmaps r = packWith(true, false);
    EXPECT_TRUE(apart(r));
    EXPECT_TRUE(r.placements[2].solid);
    EXPECT_EQ(r.placements[2].width, 1);
}

// A twin's texels that its master lacks are stored with the master's (q3map2 MergeBSPLuxels), so
// no other lightmap can take them; texels both use hold the mean of the two.
TEST(LightmapPack, TwinsMergeIntoTheirMaster) {
    LightmapBlock left = gradient(4, 4, 0), right = gradient(4, 4, 0);
    left.used.assign(16, 0);
    right.used.assign(16, 0);
    for (int y = 0; y < 4; ++y) {
        left.used[size_t(y) * 4] = left.used[size_t(y) * 4 + 1] = 1;    // columns 0 and 1
        right.used[size_t(y) * 4 + 1] = right.used[size_t(y) * 4 + 2] = 1;  // columns 1 and 2
    }
    right.texels[1] = {uint8_t(left.texels[1][0] + 3), left.texels[1][1], left.texels[1][2]};  // (1, 0)
    LightmapBlock other = gradient(1, 4, 200, "z");  // placed after the twins
    std::vector<LightmapBlock> blocks = {left, right, other};
    const PackedLightmaps p = packLightmaps(blocks, slow(4));
    ASSERT_EQ(p.placements[1].twinOf, 0);
    ASSERT_EQ(p.pages.size(), 1u);
    // Column 2 belongs to the twin: the other block takes column 3, the first one free for it.
    EXPECT_EQ(p.placements[2].x, 3);
    const auto& page = p.pages[0];
    auto red = [&](int x, int y) { return int(page[size_t(y * 4 + x) * 3]); };
    EXPECT_EQ(red(2, 1), right.texels[6][0]);
    EXPECT_EQ(red(1, 0), left.texels[1][0] + 1);  // mean of the two, rounded down
    EXPECT_EQ(red(0, 0), left.texels[0][0]);
}

// A block carrying its light, with the bytes `options` make of it.
LightmapBlock lightBlock(int w, int h, float base, const PackOptions& options) {
    LightmapBlock b;
    b.width = w;
    b.height = h;
    for (int i = 0; i < w * h; ++i) {
        b.light.push_back(Vec3::splat(base + 20.0f * float(i)));
        b.texels.push_back(colorToBytes(b.light.back(), 1.0f, options.color));
    }
    return b;
}

// q3map2 finds solid lightmaps and twins on the light, before -compensate halves it into bytes:
// its tolerances (3 per channel, 0.0625 for solids) span fewer bytes then.
TEST(LightmapPack, TwinsAndSolidsAreFoundOnLight) {
    PackOptions o = slow(16);
    o.color.compensate = 2;
    const LightmapBlock a = lightBlock(3, 3, 10, o);
    LightmapBlock b = a;
    b.light[8] += Vec3::splat(4);  // 4 units apart: 2 bytes, which bytes alone would let match
    b.texels[8] = colorToBytes(b.light[8], 1.0f, o.color);
    ASSERT_TRUE(blocksMatch(a, b));
    std::vector<LightmapBlock> twins = {a, b};
    EXPECT_EQ(packLightmaps(twins, o).placements[1].twinOf, -1);
    twins[1].light[8] = a.light[8] + Vec3::splat(2);  // within 3: twins, stored with the mean
    EXPECT_EQ(packLightmaps(twins, o).placements[1].twinOf, 0);

    LightmapBlock flat = lightBlock(3, 3, 10, o);
    for (size_t i = 0; i < flat.light.size(); ++i) {
        flat.light[i] = Vec3::splat(i % 2 ? 10.5f : 10.0f);  // one byte (5) everywhere
        flat.texels[i] = colorToBytes(flat.light[i], 1.0f, o.color);
    }
    ASSERT_TRUE(blockIsSolid(flat));
    std::vector<LightmapBlock> one = {flat};
    EXPECT_FALSE(packLightmaps(one, o).placements[0].solid);  // 0.5 apart: more than 0.0625
    for (Vec3& l : one[0].light) l = Vec3::splat(10.03f);
    EXPECT_TRUE(packLightmaps(one, o).placements[0].solid);
}

TEST(LightmapPack, UnusedTexelsMayOverlap) {
    LightmapBlock big = gradient(8, 8, 0);
    big.used.assign(64, 0);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) big.used[size_t(y) * 8 + x] = 1;
    std::vector<LightmapBlock> blocks = {big, gradient(4, 4, 9)};
    const PackedLightmaps p = packLightmaps(blocks, slow(8));
    EXPECT_EQ(p.pages.size(), 1u);
    EXPECT_EQ(p.placements[1].x, 4);
    EXPECT_EQ(p.placements[1].y, 0);
}

TEST(LightmapPack, NewPagesAndFastAllocation) {
    std::vector<LightmapBlock> two = {gradient(8, 8, 0), gradient(8, 8, 1)};
    EXPECT_EQ(packLightmaps(two, slow(8)).pages.size(), 2u);
    EXPECT_EQ(packLightmaps(two, slow(8)).placements[1].page, 1);

    // 8x7 leaves 8 free texels; after a 3x1 strip 5 remain (< 10% of 64): fast allocation skips
    // the page, the careful one still fits the next strip.
    std::vector<LightmapBlock> strips = {gradient(8, 7, 0, "a"), gradient(3, 1, 1, "b"), gradient(3, 1, 2, "c")};
    PackOptions fast;
    fast.pageSize = 8;
    const PackedLightmaps f = packLightmaps(strips, fast);
    EXPECT_EQ(f.placements[1].page, 0);
    EXPECT_EQ(f.placements[1].y, 7);
    EXPECT_EQ(f.placements[2].page, 1);
    const PackedLightmaps s = packLightmaps(strips, slow(8));
    EXPECT_EQ(s.placements[2].page, 0);
    EXPECT_EQ(s.placements[2].x, 3);
    EXPECT_EQ(s.placements[2].y, 7);
}

TEST(LightmapPack, FillUnusedTexels) {
    // A 3x1 block whose middle texel is unused, kept at full size by -nocollapse, on a 4x4 page.
    LightmapBlock b;
    b.width = 3;
    b.height = 1;
    b.texels = {{100, 0, 0}, {7, 7, 7}, {0, 200, 0}};
    b.used = {1, 0, 1};
    PackOptions o = slow(4);
    o.collapse = false;
    const PackedLightmaps packed = packLightmaps(std::vector<LightmapBlock>{b}, o);
    PackedLightmaps filled = packed;
    fillUnusedTexels(filled);
    auto texel = [&](int x, int y) {
        const auto& p = filled.pages[0];
        return Rgb8{p[size_t(y * 4 + x) * 3], p[size_t(y * 4 + x) * 3 + 1], p[size_t(y * 4 + x) * 3 + 2]};
    };
    for (uint8_t u : filled.pageUsed[0]) EXPECT_EQ(u, 1);
    // First pass: (1,0) and (3,0) (wrapping to (0,0)) average their two written neighbours.
    EXPECT_EQ(texel(1, 0), (Rgb8{50, 100, 0}));
    EXPECT_EQ(texel(3, 0), (Rgb8{50, 100, 0}));
    EXPECT_EQ(texel(0, 1), (Rgb8{100, 0, 0}));
    EXPECT_EQ(texel(2, 3), (Rgb8{0, 200, 0}));  // wraps from the top row
    // Second pass: (1,1) sees (1,0), (0,1) and (2,1) from the first pass.
    EXPECT_EQ(texel(1, 1), (Rgb8{(50 + 100 + 0) / 3, (100 + 0 + 200) / 3, 0}));

    PackedLightmaps pink = packed;
    fillUnusedTexelsPink(pink);
    EXPECT_EQ(pink.pages[0][1 * 3], 255);  // the unused middle texel
    EXPECT_EQ(pink.pages[0][1 * 3 + 1], 0);
    EXPECT_EQ(pink.pages[0][0], 100);  // written texels untouched
}

TEST(LightmapPack, BadInput) {
    std::vector<LightmapBlock> tooBig = {gradient(9, 2, 0)};
    EXPECT_THROW(packLightmaps(tooBig, slow(8)), CompileError);
    EXPECT_THROW(packLightmaps({}, slow(12)), CompileError);
    LightmapBlock broken = gradient(3, 3, 0);
    broken.texels.pop_back();
    EXPECT_THROW(packLightmaps(std::vector<LightmapBlock>{broken}, slow(8)), CompileError);
}

// Three lightmapped surfaces and a fourth that an earlier run left on page 5 and that gets no block.
bsp::Bsp twoSurfaceBsp() {
    bsp::Bsp b;
    b.surfaces.resize(4);
    for (int s = 0; s < 4; ++s) {
        b.surfaces[size_t(s)].firstVert = s * 3;
        b.surfaces[size_t(s)].numVerts = 3;
        b.surfaces[size_t(s)].lightmapNum = -1;
    }
    b.surfaces[3].lightmapNum = 5;
    b.drawVerts.resize(12);
    return b;
}

TEST(LightmapPack, ApplyRewritesSurfacesAndVertices) {
    std::vector<LightmapBlock> blocks = {gradient(4, 4, 0), uniformBlock(3, 3, {1, 1, 1})};
    blocks[0].surfaces = {0, 2};
    blocks[0].vertexCoords = {{{0.5f, 0.5f}, {3.5f, 0.5f}, {3.5f, 3.5f}}, {{1.0f, 1.0f}, {2.0f, 1.0f}, {2.0f, 4.0f}}};
    blocks[1].surfaces = {1};
    blocks[1].vertexCoords = {{{0.5f, 0.5f}, {2.5f, 0.5f}, {2.5f, 2.5f}}};
    PackOptions o = slow(8);
    o.gamePageSize = 8;
    bsp::Bsp b = twoSurfaceBsp();
    const PackedLightmaps p = packLightmaps(blocks, o);
    applyPackedLightmaps(b, blocks, p);
    EXPECT_EQ(b.surfaces[0].lightmapNum, 0);
    EXPECT_EQ(b.surfaces[0].lightmapWidth, 4);
    EXPECT_EQ(b.surfaces[2].lightmapX, p.placements[0].x);
    EXPECT_FLOAT_EQ(b.drawVerts[1].lightmap[0], (float(p.placements[0].x) + 3.5f) / 8.0f);
    EXPECT_FLOAT_EQ(b.drawVerts[8].lightmap[1], (float(p.placements[0].y) + 4.0f) / 8.0f);
    // Solid: every vertex on the texel centre.
    EXPECT_EQ(b.surfaces[1].lightmapWidth, 1);
    EXPECT_FLOAT_EQ(b.drawVerts[4].lightmap[0], (float(p.placements[1].x) + 0.5f) / 8.0f);
    EXPECT_FLOAT_EQ(b.drawVerts[5].lightmap[1], (float(p.placements[1].y) + 0.5f) / 8.0f);
    EXPECT_EQ(b.lightmaps.size(), 8u * 8u * 3u);
    EXPECT_EQ(b.surfaces[3].lightmapNum, bsp::kLightmapByVertex);  // no block: lit by vertex

    // A page size other than the game's without -external: custom shaders needed, no lump 14.
    PackOptions custom = slow(8);
    bsp::Bsp c = twoSurfaceBsp();
    applyPackedLightmaps(c, blocks, packLightmaps(blocks, custom));
    EXPECT_EQ(c.surfaces[0].lightmapNum, bsp::kLightmapByVertex);
    EXPECT_TRUE(c.lightmaps.empty());
    EXPECT_TRUE(packLightmaps(blocks, custom).needsExternalFiles());
    EXPECT_FALSE(p.needsExternalFiles());
    // -external: page numbers, no lump 14.
    PackOptions ext = slow(8);
    ext.external = true;
    bsp::Bsp e = twoSurfaceBsp();
    applyPackedLightmaps(e, blocks, packLightmaps(blocks, ext));
    EXPECT_EQ(e.surfaces[0].lightmapNum, 0);
    EXPECT_TRUE(e.lightmaps.empty());

    blocks[0].vertexCoords[1].pop_back();
    EXPECT_THROW(applyPackedLightmaps(b, blocks, p), CompileError);
}

TEST(LightmapPack, ExternalTgaPages) {
    const std::vector<uint8_t> rgb = {255, 0, 0, 0, 255, 0, 0, 0, 255, 9, 9, 9};
    const auto tga = encodeLightmapTga(rgb, 2, 2);
    ASSERT_EQ(tga.size(), 18u + 12u);
    EXPECT_EQ(tga[2], 2);   // uncompressed true colour
    EXPECT_EQ(tga[16], 24);
    const Image back = decodeTga(tga, "lm");
    ASSERT_EQ(back.width, 2);
    EXPECT_EQ(back.texel(0, 0)[0], 255);  // top-left stays top-left
    EXPECT_EQ(back.texel(1, 0)[1], 255);
    EXPECT_EQ(back.texel(0, 1)[2], 255);
    EXPECT_EQ(back.texel(1, 1)[0], 9);

    std::vector<LightmapBlock> blocks = {gradient(8, 8, 0), gradient(8, 8, 50)};
    PackOptions ext = slow(8);
    ext.external = true;
    const PackedLightmaps p = packLightmaps(blocks, ext);
    const auto dir = test::tempDir() / "maps" / "test";
    std::filesystem::create_directories(dir);
    writeFileAtomic(dir / "lm_0002.tga", std::string("stale"));
    writeFileAtomic(dir / "lm_0003.tga", std::string("stale"));
    writeFileAtomic(dir / "lm_0005.tga", std::string("kept: not contiguous"));
    const auto written = writeExternalLightmaps(p, dir);
    ASSERT_EQ(written.size(), 2u);
    EXPECT_EQ(written[1].filename(), "lm_0001.tga");
    EXPECT_EQ(externalLightmapName(12), "lm_0012.tga");
    EXPECT_FALSE(std::filesystem::exists(dir / "lm_0002.tga"));
    EXPECT_FALSE(std::filesystem::exists(dir / "lm_0003.tga"));
    EXPECT_TRUE(std::filesystem::exists(dir / "lm_0005.tga"));
    const Image page1 = decodeTga(readFileBytes(dir / "lm_0001.tga"), "lm_0001");
    EXPECT_EQ(page1.width, 8);
    EXPECT_EQ(page1.texel(3, 2)[0], 50 + 30);
    EXPECT_EQ(page1.texel(3, 2)[1], 50 + 20);
}

// Replays a packing texel by texel, as q3map2 places blocks: in sorted order, each block at the
// first position (page, then row, then column, with the fast-allocation steps) where all its used
// texels are free. Random blocks with holes, several page sizes (multi-word rows included).
TEST(LightmapPack, PlacementsAreTheFirstFitOfATexelByTexelSearch) {
    std::mt19937 rng(7);
    for (int pageSize : {16, 64, 128, 256}) {
        for (bool fast : {false, true}) {
            std::vector<LightmapBlock> blocks;
            for (int i = 0; i < 160; ++i) {
                const int w = 1 + int(rng() % uint32_t(std::min(pageSize, 70)));
                const int h = 1 + int(rng() % uint32_t(std::min(pageSize, 40)));
                LightmapBlock b = gradient(w, h, int(rng() % 200), i % 3 ? "textures/a" : "textures/b");
                if (i % 4 == 0) {  // holes: a disc or random texels
                    b.used.assign(b.texels.size(), 1);
                    for (int y = 0; y < h; ++y)
                        for (int x = 0; x < w; ++x)
                            if ((i % 8 == 0) ? (2 * x - w) * (2 * x - w) + (2 * y - h) * (2 * y - h) > w * h
                                             : rng() % 3 == 0)
                                b.used[size_t(y) * w + x] = 0;
                }
                blocks.push_back(std::move(b));
            }
            PackOptions options = slow(pageSize);
            options.fastAllocate = fast;
            const PackedLightmaps packed = packLightmaps(blocks, options);

            std::vector<size_t> order(blocks.size());
            for (size_t i = 0; i < order.size(); ++i) order[i] = i;
            // q3map2's order: std::sort by shader, then larger area (equal ones as introsort leaves them).
            std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
                if (blocks[a].sortKey != blocks[b].sortKey) return blocks[a].sortKey < blocks[b].sortKey;
                return long(blocks[a].width) * blocks[a].height > long(blocks[b].width) * blocks[b].height;
            });
            std::vector<std::vector<uint8_t>> pages;
            auto used = [&](const LightmapBlock& b, bool solid, int sx, int sy) {
                if (solid) return sx == 0 && sy == 0;
                return b.used.empty() || b.used[size_t(sy) * b.width + sx] != 0;
            };
            auto fits = [&](const std::vector<uint8_t>& page, const LightmapBlock& b, bool solid, int x, int y) {
                if (x + b.width > pageSize || y + b.height > pageSize) return false;
                for (int sy = 0; sy < b.height; ++sy)
                    for (int sx = 0; sx < b.width; ++sx)
                        if (used(b, solid, sx, sy) && page[size_t(y + sy) * pageSize + x + sx]) return false;
                return true;
            };
            for (size_t index : order) {
                const BlockPlacement& at = packed.placements[index];
                if (at.twinOf >= 0) continue;
                const LightmapBlock& b = blocks[index];
                const bool solid = at.solid;
                int needed = 0;  // every used texel, even of a solid lightmap stored as one
                for (int sy = 0; sy < b.height; ++sy)
                    for (int sx = 0; sx < b.width; ++sx) needed += used(b, false, sx, sy);
                int page = -1, px = 0, py = 0;
                for (size_t p = 0; p < pages.size() && page < 0; ++p) {
                    const int free = int(std::count(pages[p].begin(), pages[p].end(), 0));
                    if (free < needed || (fast && free < pageSize * pageSize / 10)) continue;
                    const int xStep = fast ? std::max(1, b.width / 15) : 1;
                    const int yStep = fast ? std::max(1, b.height / 15) : 1;
                    for (int y = 0; y < pageSize && page < 0; y += yStep)
                        for (int x = 0; x < pageSize; x += xStep)
                            if (fits(pages[p], b, solid, x, y)) {
                                page = int(p), px = x, py = y;
                                break;
                            }
                }
                if (page < 0) {
                    pages.emplace_back(size_t(pageSize) * pageSize, 0);
                    page = int(pages.size()) - 1;
                }
                ASSERT_EQ(at.page, page) << "block " << index << " page size " << pageSize;
                ASSERT_EQ(at.x, px) << "block " << index;
                ASSERT_EQ(at.y, py) << "block " << index;
                for (int sy = 0; sy < b.height; ++sy)
                    for (int sx = 0; sx < b.width; ++sx)
                        if (used(b, solid, sx, sy)) pages[size_t(page)][size_t(py + sy) * pageSize + px + sx] = 1;
            }
            EXPECT_EQ(packed.pages.size(), pages.size());
        }
    }
}

// q3map2 keeps -1 in the luxels nothing reached and takes them into its solid test, so a lightmap
// with such a hole is never solid, however even its light.
TEST(LightmapPack, HolesKeepALightmapFromBeingSolid) {
    LightmapBlock holed = uniformBlock(3, 3, {10, 10, 10});
    holed.light.assign(9, Vec3{10, 10, 10});
    holed.used.assign(9, 1);
    holed.used[4] = 0;
    LightmapBlock whole = holed;
    whole.used.assign(9, 1);
    const std::vector<LightmapBlock> blocks = {holed, whole};
    const PackedLightmaps p = packLightmaps(blocks, slow(8));
    EXPECT_FALSE(p.placements[0].solid);
    EXPECT_EQ(p.placements[0].width, 3);
    EXPECT_TRUE(p.placements[1].solid);
    EXPECT_EQ(p.placements[1].width, 1);
}

}  // namespace
}  // namespace q3::light
