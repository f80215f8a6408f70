#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "bsp_test_maps.h"
#include "fake_map.h"

namespace q3::bspstage {
namespace {

using test::boxBrush;
using test::worldspawn;

LoadedMap load(const std::string& text, map::MapFile& file, MapLoadOptions options = {}) {
    static Log log(false);
    static const ShaderTable shaders = test::commonShaders(log);
    file = map::parseMap(text, "test.map");
    return loadMapForBsp(file, shaders, options, log);
}

// A wedge 64 deep: floor, back wall, two sides and a slope from (0,0,size) down to (size,0,0).
std::string wedgeBrush(int size) {
    const std::string n = std::to_string(size);
    return "{\n( 0 0 0 ) ( 0 1 0 ) ( 0 0 1 ) base/wall 0 0 0 0.5 0.5 0 0 0\n"
           "( 0 0 0 ) ( 0 0 1 ) ( 1 0 0 ) base/wall 0 0 0 0.5 0.5 0 0 0\n"
           "( 0 64 0 ) ( 1 64 0 ) ( 0 64 1 ) base/wall 0 0 0 0.5 0.5 0 0 0\n"
           "( 0 0 0 ) ( 1 0 0 ) ( 0 1 0 ) base/wall 0 0 0 0.5 0.5 0 0 0\n"
           "( 0 0 " + n + " ) ( 0 64 " + n + " ) ( " + n + " 0 0 ) base/wall 0 0 0 0.5 0.5 0 0 0\n}\n";
}

TEST(BspBrushes, BoxHasSixAxialSidesInCanonicalOrderWithQuadWindings) {
    map::MapFile file;
    LoadedMap m = load(worldspawn(boxBrush({0, 0, 0}, {64, 32, 16})), file);
    ASSERT_EQ(m.entities.size(), 1u);
    ASSERT_EQ(m.entities[0].brushes.size(), 1u);
    const Brush& b = m.entities[0].brushes[0];
    ASSERT_EQ(b.sides.size(), 6u);
    const DVec3 expected[6] = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};
    for (int i = 0; i < 6; ++i) {
        EXPECT_EQ(m.planes[b.sides[size_t(i)].planeNum].normal(), expected[i]) << i;
        EXPECT_EQ(b.sides[size_t(i)].winding.size(), 4u);
        EXPECT_FALSE(b.sides[size_t(i)].bevel);
    }
    EXPECT_EQ(b.bounds.mins, (DVec3{0, 0, 0}));
    EXPECT_EQ(b.bounds.maxs, (DVec3{64, 32, 16}));
    EXPECT_TRUE(b.opaque);
    EXPECT_FALSE(b.detail);
    EXPECT_EQ(b.contentFlags, contents::Solid);
    EXPECT_EQ(m.counts.boxBevels, 0);
}

// A brush of many sides is bounded by its chopped windings instead of the corner search over
// every triple of planes (cubic): its windings are the same polygons either way.
std::string prismBrush(int sides, double radius, double height) {
    std::string text = "{\n";
    char line[256];
    for (int i = 0; i < sides; ++i) {
        const double a = 2 * kPiD * i / sides, b = 2 * kPiD * (i + 1) / sides;
        std::snprintf(line, sizeof line, "( %.4f %.4f 0 ) ( %.4f %.4f %g ) ( %.4f %.4f 0 ) base/wall 0 0 0 0.5 0.5 0 0 0\n",
                      radius * std::cos(a), radius * std::sin(a), radius * std::cos(a), radius * std::sin(a), height,
                      radius * std::cos(b), radius * std::sin(b));
        text += line;
    }
    std::snprintf(line, sizeof line, "( 0 0 0 ) ( 1 0 0 ) ( 0 1 0 ) base/wall 0 0 0 0.5 0.5 0 0 0\n"
                                     "( 0 0 %g ) ( 0 1 %g ) ( 1 0 %g ) base/wall 0 0 0 0.5 0.5 0 0 0\n}\n",
                  height, height, height);
    return text + line;
}

TEST(BspBrushes, PrismsOfFewAndManySidesGetTheirPolygons) {
    for (const int sides : {24, 200}) {
        map::MapFile file;
        LoadedMap m = load(worldspawn(prismBrush(sides, 256, 64)), file);
        ASSERT_EQ(m.entities[0].brushes.size(), 1u) << sides;
        const Brush& b = m.entities[0].brushes[0];
        size_t walls = 0, caps = 0;
        for (const BrushSide& side : b.sides) {
            if (side.bevel) continue;
            if (side.winding.size() == 4) ++walls;
            if (side.winding.size() == size_t(sides)) ++caps;
            for (const DVec3& p : side.winding) EXPECT_NEAR(m.planes[side.planeNum].plane.distanceTo(p), 0, 0.01);
        }
        EXPECT_EQ(walls, size_t(sides)) << sides;
        EXPECT_EQ(caps, 2u) << sides;
        EXPECT_NEAR(b.bounds.maxs.z - b.bounds.mins.z, 64, 1e-3) << sides;
        EXPECT_NEAR(b.bounds.maxs.x, 256, 1e-3) << sides;
    }
}

TEST(BspBrushes, WedgeGetsAxialAndEdgeBevels) {
    const std::string wedge = wedgeBrush(64);
    map::MapFile file;
    LoadedMap m = load(worldspawn(wedge), file);
    const Brush& b = m.entities[0].brushes.at(0);
    ASSERT_GE(b.sides.size(), 7u);
    const DVec3 expected[6] = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};
    for (int i = 0; i < 6; ++i) EXPECT_EQ(m.planes[b.sides[size_t(i)].planeNum].normal(), expected[i]) << i;
    // +X and +Z are missing on a wedge: bevels at the bounds, without windings.
    EXPECT_TRUE(b.sides[1].bevel);
    EXPECT_DOUBLE_EQ(m.planes[b.sides[1].planeNum].dist(), 64);
    EXPECT_TRUE(b.sides[5].bevel);
    EXPECT_TRUE(b.sides[5].winding.empty());
    EXPECT_EQ(m.counts.boxBevels, 2);
    // The slope is the only non-axial side; its edges along Y are axial, the others lie on the
    // existing sides, so no edge bevel is needed.
    EXPECT_EQ(b.sides.size(), 7u);
    EXPECT_EQ(m.counts.edgeBevels, 0);
}

TEST(BspBrushes, SnapMovesAddedBevelsInwardsToMultiples) {
    // A wedge 0..60 wide and high: its +X and +Z bevels land on 48 with -snap 16.
    const std::string wedge = wedgeBrush(60);
    map::MapFile file;
    MapLoadOptions options;
    options.bevelSnap = 16;
    LoadedMap m = load(worldspawn(wedge), file, options);
    const Brush& b = m.entities[0].brushes.at(0);
    ASSERT_GE(b.sides.size(), 6u);
    ASSERT_TRUE(b.sides[1].bevel);
    EXPECT_DOUBLE_EQ(m.planes[b.sides[1].planeNum].dist(), 48);
    ASSERT_TRUE(b.sides[5].bevel);
    EXPECT_DOUBLE_EQ(m.planes[b.sides[5].planeNum].dist(), 48);
    EXPECT_DOUBLE_EQ(m.planes[b.sides[0].planeNum].dist(), 0);  // a real side: never snapped
    map::MapFile plainFile;
    LoadedMap plain = load(worldspawn(wedge), plainFile);
    EXPECT_DOUBLE_EQ(plain.planes[plain.entities[0].brushes.at(0).sides[1].planeNum].dist(), 60);
}

TEST(BspBrushes, FakeMapWritesEveryWorldSideAsThreeIntegerPoints) {
    map::MapFile file;
    LoadedMap m = load(worldspawn(boxBrush({0, 0, 0}, {64, 32, 16})), file);
    const std::string text = fakeMapText(m.entities[0].brushes, m.planes);
    EXPECT_EQ(text.rfind("{\n\"classname\" \"worldspawn\"\n{\n", 0), 0u);
    size_t sides = 0;
    for (size_t at = text.find("notexture 0 0 0 1 1\n"); at != std::string::npos;
         at = text.find("notexture 0 0 0 1 1\n", at + 1))
        ++sides;
    EXPECT_EQ(sides, 6u);
    // The -X side: the huge base winding of the plane x = 0 starts at ( 0 131072 131072 ).
    EXPECT_NE(text.find("( 0 131072 131072 ) ( 0 -131072 131072 ) ( 0 -131072 -131072 ) notexture"),
              std::string::npos)
        << text;
    EXPECT_EQ(text.substr(text.size() - 4), "}\n}\n");
}

TEST(BspBrushes, ClonesShareTheirParentsModelAndLoseTheirBrushes) {
    auto brushEntity = [](const std::string& keys, double x) {
        return "{\n\"classname\" \"func_static\"\n" + keys + boxBrush({x, 0, 0}, {x + 32, 32, 32}) + "}\n";
    };
    const std::string text = worldspawn(boxBrush({0, 0, -16}, {512, 512, 0})) +
                             brushEntity("\"_clonename\" \"pillar\"\n", 0) +
                             brushEntity("\"_clone\" \"pillar\"\n\"origin\" \"64 0 0\"\n", 100) +
                             brushEntity("", 200) + brushEntity("\"_ins\" \"nobody\"\n", 300);
    map::MapFile file;
    LoadedMap m = load(text, file);
    ASSERT_EQ(m.entities.size(), 5u);
    EXPECT_EQ(m.entities[1].model, "*1");
    EXPECT_EQ(m.entities[2].model, "*1");  // the clone draws its parent's model
    EXPECT_TRUE(m.entities[2].brushes.empty());
    EXPECT_EQ(m.entities[3].model, "*2");  // clones take no number
    EXPECT_EQ(m.entities[4].model, "");    // no such parent: no model key, brushes kept
    EXPECT_EQ(m.entities[4].brushes.size(), 1u);
    MapLoadOptions onlyEnts;
    onlyEnts.resolveClones = false;
    map::MapFile file2;
    LoadedMap plain = load(text, file2, onlyEnts);
    EXPECT_EQ(plain.entities[2].model, "*2");
    EXPECT_EQ(plain.entities[4].model, "*4");
}

TEST(BspBrushes, ContentsFromShaders) {
    map::MapFile file;
    const std::string text = worldspawn(boxBrush({0, 0, 0}, {64, 64, 64}, "liquids/water") +
                                        boxBrush({100, 0, 0}, {164, 64, 64}, "common/hint") +
                                        boxBrush({200, 0, 0}, {264, 64, 64}, "base/detailwall") +
                                        boxBrush({300, 0, 0}, {364, 64, 64}, "common/caulk"));
    LoadedMap m = load(text, file);
    const auto& brushes = m.entities[0].brushes;
    ASSERT_EQ(brushes.size(), 4u);
    // Opaque brushes first, latest first; then translucent ones in file order.
    EXPECT_EQ(brushes[0].brushNum, 3);  // caulk
    EXPECT_EQ(brushes[1].brushNum, 2);  // detail wall
    EXPECT_EQ(brushes[2].brushNum, 0);  // water
    EXPECT_EQ(brushes[3].brushNum, 1);  // hint
    EXPECT_TRUE(brushes[0].opaque && !brushes[0].detail);
    EXPECT_TRUE(brushes[1].opaque && brushes[1].detail);
    EXPECT_TRUE(!brushes[2].opaque && brushes[2].detail);  // translucent, not structural: detail
    EXPECT_EQ(brushes[2].contentFlags, contents::Water | contents::Translucent);
    EXPECT_TRUE(!brushes[3].opaque && !brushes[3].detail);  // hint is structural
    EXPECT_TRUE(brushes[3].compileFlags & compileflags::Hint);
    EXPECT_EQ(m.counts.detailBrushes, 2);

    map::MapFile file2;
    MapLoadOptions noWater;
    noWater.noWater = true;
    noWater.noHint = true;
    EXPECT_EQ(load(text, file2, noWater).entities[0].brushes.size(), 2u);
}

TEST(BspBrushes, FuncGroupJoinsTheWorldAndBrushEntitiesStaySeparate) {
    const std::string text = worldspawn(boxBrush({0, 0, 0}, {64, 64, 64})) +
                             "{\n\"classname\" \"func_group\"\n" + boxBrush({100, 0, 0}, {164, 64, 64}) + "}\n" +
                             "{\n\"classname\" \"func_door\"\n" + boxBrush({200, 0, 0}, {264, 64, 64}) +
                             boxBrush({216, 16, 16}, {232, 32, 32}, "common/origin") + "}\n" +
                             test::pointEntity("info_player_deathmatch", {32, 32, 100});
    map::MapFile file;
    LoadedMap m = load(text, file);
    ASSERT_EQ(m.entities.size(), 3u);
    EXPECT_EQ(m.entities[0].brushes.size(), 2u);
    EXPECT_EQ(m.entities[0].brushes[0].bounds.mins.x, 100);  // merged opaque brush goes first
    EXPECT_EQ(m.entities[1].classname, "func_door");
    ASSERT_EQ(m.entities[1].brushes.size(), 1u);
    EXPECT_FALSE(m.entities[1].isPointEntity());
    // The origin brush is gone: the door is now relative to its centre (224 24 24).
    EXPECT_EQ(m.entities[1].origin, (DVec3{224, 24, 24}));
    EXPECT_EQ(m.entities[1].brushes[0].bounds.mins, (DVec3{-24, -24, -24}));
    EXPECT_TRUE(m.entities[2].isPointEntity());
    EXPECT_EQ(m.entities[2].origin, (DVec3{32, 32, 100}));
}

TEST(BspBrushes, DegenerateAndMirroredBrushesAreDropped) {
    const std::string mirrored = R"({
( 0 0 0 ) ( 0 1 0 ) ( 0 0 1 ) base/wall 0 0 0 0.5 0.5 0 0 0
( 0 0 0 ) ( 0 0 1 ) ( 0 1 0 ) base/wall 0 0 0 0.5 0.5 0 0 0
( 0 0 0 ) ( 1 0 0 ) ( 0 1 0 ) base/wall 0 0 0 0.5 0.5 0 0 0
( 0 0 64 ) ( 0 1 64 ) ( 1 0 64 ) base/wall 0 0 0 0.5 0.5 0 0 0
}
)";
    map::MapFile file;
    LoadedMap m = load(worldspawn(mirrored + boxBrush({0, 0, 0}, {8, 8, 8})), file);
    EXPECT_EQ(m.entities[0].brushes.size(), 1u);
}

}  // namespace
}  // namespace q3::bspstage
