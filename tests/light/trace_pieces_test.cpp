// The shadow casters cut and grown as q3map2's tracer holds them.
#include <gtest/gtest.h>

#include "light_test_util.h"
#include "trace_pieces.h"

namespace q3::light {
namespace {

using test::quad;

// A 1000 x 1000 wall in the plane y = 50, x and z from 0 to 1000.
SceneSurface bigWall(const LightingShader* shader = nullptr) { return quad({0, 50, 0}, {1000, 0, 0}, {0, 0, 1000}, shader); }

bool blockedAt(const std::vector<SceneSurface>& surfaces, float x) {
    const TraceScene scene(surfaces, {});
    return scene.transmission({x, 0, 500}, {x, 100, 500}) == Vec3{};
}

TEST(TracePieces, GrowByOnePercentOfThePiece) {
    const std::vector<SceneSurface> wall{bigWall()};
    const bsp::Bsp noTree;
    const std::vector<SceneSurface> pieces = traceCasterPieces(wall, noTree, {}).surfaces;
    EXPECT_FALSE(blockedAt(wall, 1004));
    // 1 % of the 1000-unit triangle: rays up to 10 units beside its edge are stopped.
    EXPECT_TRUE(blockedAt(pieces, 1004));
    EXPECT_TRUE(blockedAt(pieces, 1009));
    EXPECT_FALSE(blockedAt(pieces, 1011));
}

TEST(TracePieces, TheTreeCutsThePiecesAndTheirSlack) {
    // One node on the plane x = 500: the wall is cut there, and the pieces along its edge at
    // x = 1000 are 500 units across, so their slack is 5 units.
    bsp::Bsp tree;
    tree.planes = {{{1, 0, 0}, 500}};
    tree.nodes = {{0, {-1, -2}, {-2000, -2000, -2000}, {2000, 2000, 2000}}};
    tree.leafs = {{0, 0, {500, -2000, -2000}, {2000, 2000, 2000}, 0, 0, 0, 0},
                  {0, 0, {-2000, -2000, -2000}, {500, 2000, 2000}, 0, 0, 0, 0}};
    const std::vector<SceneSurface> pieces = traceCasterPieces({bigWall()}, tree, {}).surfaces;
    EXPECT_TRUE(blockedAt(pieces, 1004));
    EXPECT_FALSE(blockedAt(pieces, 1007));
    EXPECT_TRUE(blockedAt(pieces, 400));  // the wall itself still blocks on both sides of the cut
    EXPECT_TRUE(blockedAt(pieces, 600));
}

TEST(TracePieces, TinyPiecesAreDroppedAndFiltersKeepTheirSize) {
    const bsp::Bsp noTree;
    // Edge cross product 0.09: below the coplanar epsilon, no ray ever hits it.
    const std::vector<SceneSurface> tiny = traceCasterPieces({quad({0, 50, 0}, {0.3f, 0, 0}, {0, 0, 0.3f})}, noTree, {}).surfaces;
    EXPECT_TRUE(tiny[0].triangles.empty());
    // Alpha-shadow surfaces are read inside their triangles only.
    LightingShader alpha;
    alpha.alphaShadow = true;
    const std::vector<SceneSurface> exact = traceCasterPieces({bigWall(&alpha)}, noTree, {}).surfaces;
    ASSERT_EQ(exact[0].triangles.size(), 6u);
    for (const Vec3& p : exact[0].xyz) EXPECT_LE(p.x, 1000.0f);
    // Only they keep texture coordinates: no other caster's texture is read.
    EXPECT_EQ(exact[0].st.size(), exact[0].xyz.size() * 2);
    const std::vector<SceneSurface> opaque = traceCasterPieces({bigWall()}, noTree, {}).surfaces;
    EXPECT_FALSE(opaque[0].triangles.empty());
    EXPECT_TRUE(opaque[0].st.empty());
    // Surfaces that cast nothing come back unchanged.
    LightingShader trans;
    trans.translucent = true;
    const std::vector<SceneSurface> glass = traceCasterPieces({bigWall(&trans)}, noTree, {}).surfaces;
    EXPECT_EQ(glass[0].xyz, bigWall().xyz);
}

// One node on the plane x = 500: open (cluster 0) in front, solid (outside every cluster) behind.
bsp::Bsp openInFrontSolidBehind() {
    bsp::Bsp tree;
    tree.planes = {{{1, 0, 0}, 500}};
    tree.nodes = {{0, {-1, -2}, {-4000, -4000, -4000}, {4000, 4000, 4000}}};
    tree.leafs = {{0, 0, {500, -4000, -4000}, {4000, 4000, 4000}, 0, 0, 0, 0},
                  {-1, 0, {-4000, -4000, -4000}, {500, 4000, 4000}, 0, 0, 0, 0}};
    return tree;
}

// A strip of `n` quads, 200 units wide each, in the plane y = 50 from x = `x0`, z from 0 to 1000.
SceneSurface wallStrip(float x0, int n) {
    SceneSurface s;
    for (int i = 0; i <= n; ++i) {
        s.xyz.push_back({x0 + 200.0f * float(i), 50, 0});
        s.xyz.push_back({x0 + 200.0f * float(i), 50, 1000});
    }
    for (uint32_t i = 0; i < uint32_t(n); ++i)
        for (uint32_t k : {0u, 2u, 3u, 0u, 3u, 1u}) s.triangles.push_back(2 * i + k);
    return s;
}

TEST(TracePieces, OpaquePiecesInSolidAreLeftOutOrKeptForSunRays) {
    const bsp::Bsp tree = openInFrontSolidBehind();
    LightingShader alpha, sky;
    alpha.alphaShadow = true;
    sky.sky = true;
    // A wall in the open leaf, and in solid a two-triangle wall and an alpha-shadow one: too few
    // triangles for the tracer to split the solid leaf.
    TraceLeafContents contents;
    const CasterPieces whole =
        traceCasterPieces({quad({600, 50, 0}, {400, 0, 0}, {0, 0, 1000}), quad({-900, 50, 0}, {400, 0, 0}, {0, 0, 1000}),
                           quad({-900, 50, 0}, {400, 0, 0}, {0, 0, 1000}, &alpha)},
                          tree, {}, &contents);
    ASSERT_EQ(contents.subdivided.size(), 2u);
    EXPECT_EQ(contents.subdivided[1], 0);
    // The open wall stays, the opaque wall in solid is gone, the filter stays.
    EXPECT_TRUE(blockedAt({whole.surfaces[0]}, 800));
    EXPECT_TRUE(whole.surfaces[1].triangles.empty());
    EXPECT_FALSE(whole.surfaces[2].triangles.empty());
    EXPECT_TRUE(whole.forSunOnly.empty());

    // A strip of eight triangles in solid, 800 units long, with a sky ceiling: the tracer splits
    // the leaf, and the strip is kept for sun rays alone.
    const CasterPieces split =
        traceCasterPieces({wallStrip(-900, 4), quad({-4000, -4000, 2000}, {8000, 0, 0}, {0, 8000, 0}, &sky, 0)}, tree,
                          {}, &contents);
    EXPECT_EQ(contents.subdivided[1], 1);
    EXPECT_TRUE(split.surfaces[0].triangles.empty());
    ASSERT_EQ(split.forSunOnly.size(), 2u);
    EXPECT_FALSE(split.forSunOnly[0].triangles.empty());
    EXPECT_FALSE(split.surfaces[1].triangles.empty());
    EXPECT_TRUE(split.forSunOnly[1].triangles.empty());
    // Without sun rays they are left out as well.
    TraceSceneOptions noSun;
    noSun.sunRays = false;
    const CasterPieces withoutSun =
        traceCasterPieces({wallStrip(-900, 4), quad({-4000, -4000, 2000}, {8000, 0, 0}, {0, 8000, 0}, &sky, 0)}, tree,
                          noSun);
    EXPECT_TRUE(withoutSun.surfaces[0].triangles.empty());
    EXPECT_TRUE(withoutSun.forSunOnly.empty());
    // Through the strip at x = -400 towards the sky: only sun rays meet it, one at a time or in a batch.
    const TraceScene withSunOnly(split.surfaces, {}, split.forSunOnly);
    const TraceScene without(split.surfaces, {});
    const Vec3 from{-400, 0, 500}, up = normalize(Vec3{0, 1, 1});
    EXPECT_EQ(withSunOnly.skyTransmission(from, up, 0), (Vec3{0, 0, 0}));
    EXPECT_EQ(without.skyTransmission(from, up, 0), (Vec3{1, 1, 1}));
    EXPECT_EQ(withSunOnly.transmission(from, from + up * 100.0f), (Vec3{1, 1, 1}));
    std::vector<ShadowRay> rays(8, TraceScene::skyRay(from, up, 0));
    rays[3] = *TraceScene::segmentRay(from, from + up * 100.0f);
    std::vector<Vec3> out(rays.size());
    withSunOnly.traceBatch(rays, out);
    for (size_t i = 0; i < rays.size(); ++i) EXPECT_EQ(out[i], (i == 3 ? Vec3{1, 1, 1} : Vec3{})) << i;
}

}  // namespace
}  // namespace q3::light
