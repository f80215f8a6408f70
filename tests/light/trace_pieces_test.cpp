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
    const std::vector<SceneSurface> pieces = traceCasterPieces(wall, noTree, {});
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
    const std::vector<SceneSurface> pieces = traceCasterPieces({bigWall()}, tree, {});
    EXPECT_TRUE(blockedAt(pieces, 1004));
    EXPECT_FALSE(blockedAt(pieces, 1007));
    EXPECT_TRUE(blockedAt(pieces, 400));  // the wall itself still blocks on both sides of the cut
    EXPECT_TRUE(blockedAt(pieces, 600));
}

TEST(TracePieces, TinyPiecesAreDroppedAndFiltersKeepTheirSize) {
    const bsp::Bsp noTree;
    // Edge cross product 0.09: below the coplanar epsilon, no ray ever hits it.
    const std::vector<SceneSurface> tiny = traceCasterPieces({quad({0, 50, 0}, {0.3f, 0, 0}, {0, 0, 0.3f})}, noTree, {});
    EXPECT_TRUE(tiny[0].triangles.empty());
    // Alpha-shadow surfaces are read inside their triangles only.
    LightingShader alpha;
    alpha.alphaShadow = true;
    const std::vector<SceneSurface> exact = traceCasterPieces({bigWall(&alpha)}, noTree, {});
    ASSERT_EQ(exact[0].triangles.size(), 6u);
    for (const Vec3& p : exact[0].xyz) EXPECT_LE(p.x, 1000.0f);
    // Only they keep texture coordinates: no other caster's texture is read.
    EXPECT_EQ(exact[0].st.size(), exact[0].xyz.size() * 2);
    const std::vector<SceneSurface> opaque = traceCasterPieces({bigWall()}, noTree, {});
    EXPECT_FALSE(opaque[0].triangles.empty());
    EXPECT_TRUE(opaque[0].st.empty());
    // Surfaces that cast nothing come back unchanged.
    LightingShader trans;
    trans.translucent = true;
    const std::vector<SceneSurface> glass = traceCasterPieces({bigWall(&trans)}, noTree, {});
    EXPECT_EQ(glass[0].xyz, bigWall().xyz);
}

}  // namespace
}  // namespace q3::light
