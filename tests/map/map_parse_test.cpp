// Parsing of hand-written .map snippets: every primitive form, entity key/values, tolerance.
#include <gtest/gtest.h>

#include <cmath>

#include "map_file.h"
#include "script.h"

using namespace q3;
using namespace q3::map;

namespace {

const char* kClassicBox = R"(// entity 0
{
"classname" "worldspawn"
"message" "box"
// brush 0
{
( 0 0 64 ) ( 0 1 64 ) ( 1 0 64 ) base_wall/concrete 16 -8 45 0.5 0.25 0 0 0
( 0 0 0 ) ( 1 0 0 ) ( 0 1 0 ) base_wall/concrete 0 0 0 0.5 0.5
( 0 0 0 ) ( 0 1 0 ) ( 0 0 1 ) common/caulk 0 0 0 0.5 0.5 134217728 128 7
( 64 0 0 ) ( 64 0 1 ) ( 64 1 0 ) common/caulk 0 0 0 0.5 0.5 0 0 0
( 0 0 0 ) ( 0 0 1 ) ( 1 0 0 ) common/caulk 0 0 0 0.5 0.5 0 0 0
( 0 64 0 ) ( 1 64 0 ) ( 0 64 1 ) common/caulk 0 0 0 0.5 0.5 0 0 0
}
}
)";

}  // namespace

TEST(MapParse, ClassicBrushFacesKeepPointsTextureAndProjection) {
    MapFile map = parseMap(kClassicBox, "box.map");
    ASSERT_EQ(map.entities.size(), 1u);
    const MapEntity& world = map.entities[0];
    EXPECT_EQ(world.classname(), "worldspawn");
    ASSERT_EQ(world.brushes.size(), 1u);
    const MapBrush& brush = world.brushes[0];
    EXPECT_FALSE(brush.brushPrimitive);
    EXPECT_EQ(brush.line, 6);
    ASSERT_EQ(brush.faces.size(), 6u);

    const BrushFace& top = brush.faces[0];
    EXPECT_EQ(top.line, 7);
    EXPECT_EQ(top.points[1], Vec3(0, 1, 64));
    EXPECT_EQ(top.texture, "base_wall/concrete");
    EXPECT_EQ(top.projection, TexProjection::Standard);
    EXPECT_FLOAT_EQ(top.standard.shift[0], 16);
    EXPECT_FLOAT_EQ(top.standard.shift[1], -8);
    EXPECT_FLOAT_EQ(top.standard.rotate, 45);
    EXPECT_FLOAT_EQ(top.standard.scale[0], 0.5f);
    EXPECT_FLOAT_EQ(top.standard.scale[1], 0.25f);
    EXPECT_TRUE(top.hasFlags);
    // The plane faces out of the box: up, at height 64.
    ASSERT_TRUE(top.planeValid);
    EXPECT_DOUBLE_EQ(top.plane.normal[2], 1.0);
    EXPECT_DOUBLE_EQ(top.plane.dist, 64.0);

    EXPECT_FALSE(brush.faces[1].hasFlags);  // the optional triple is absent on that line
    EXPECT_DOUBLE_EQ(brush.faces[1].plane.normal[2], -1.0);
    EXPECT_DOUBLE_EQ(brush.faces[1].plane.dist, 0.0);

    const BrushFace& flagged = brush.faces[2];
    EXPECT_EQ(flagged.contentFlags, 134217728);
    EXPECT_EQ(flagged.surfaceFlags, 128);
    EXPECT_EQ(flagged.value, 7);
    EXPECT_DOUBLE_EQ(flagged.plane.normal[0], -1.0);

    // Every plane of the box faces outwards: the centre is behind all of them.
    for (const BrushFace& f : brush.faces) {
        ASSERT_TRUE(f.planeValid);
        double side = f.plane.normal[0] * 32 + f.plane.normal[1] * 32 + f.plane.normal[2] * 32 - f.plane.dist;
        EXPECT_LT(side, 0) << "face on line " << f.line;
    }
}

TEST(MapParse, PlaneFromPointsMatchesQuakeOrientation) {
    MapPlane p;
    ASSERT_TRUE(planeFromPoints({608, 3394, 224}, {480, 3394, 224}, {480, 3378, 224}, p));
    EXPECT_DOUBLE_EQ(p.normal[0], 0);
    EXPECT_DOUBLE_EQ(p.normal[1], 0);
    EXPECT_DOUBLE_EQ(p.normal[2], -1);
    EXPECT_DOUBLE_EQ(p.dist, -224);
    ASSERT_TRUE(planeFromPoints({0, 0, 0}, {1, 1, 0}, {0, 0, 5}, p));
    EXPECT_NEAR(p.normal[0], -std::sqrt(0.5), 1e-12);
    EXPECT_NEAR(p.normal[1], std::sqrt(0.5), 1e-12);
    EXPECT_FALSE(planeFromPoints({0, 0, 0}, {1, 1, 1}, {2, 2, 2}, p));
    EXPECT_FALSE(planeFromPoints({3, 3, 3}, {3, 3, 3}, {3, 3, 3}, p));
}

TEST(MapParse, CollinearFaceIsKeptWithoutPlane) {
    MapFile map = parseMap("{\n{\n( 0 0 0 ) ( 1 0 0 ) ( 2 0 0 ) a 0 0 0 1 1\n}\n}\n", "line.map");
    ASSERT_EQ(map.entities[0].brushes[0].faces.size(), 1u);
    EXPECT_FALSE(map.entities[0].brushes[0].faces[0].planeValid);
}

TEST(MapParse, ValveFaces) {
    MapFile map = parseMap(
        "{\n{\n( 0 0 0 ) ( 0 1 0 ) ( 1 0 0 ) tex [ 1 0 0 8 ] [ 0 -1 0 -4 ] 30 0.5 2 1 2 3\n}\n}\n", "valve.map");
    const BrushFace& f = map.entities[0].brushes[0].faces[0];
    EXPECT_EQ(f.projection, TexProjection::Valve220);
    EXPECT_EQ(f.valve.axis[0], Vec3(1, 0, 0));
    EXPECT_EQ(f.valve.axis[1], Vec3(0, -1, 0));
    EXPECT_FLOAT_EQ(f.valve.offset[0], 8);
    EXPECT_FLOAT_EQ(f.valve.offset[1], -4);
    EXPECT_FLOAT_EQ(f.valve.rotate, 30);
    EXPECT_FLOAT_EQ(f.valve.scale[0], 0.5f);
    EXPECT_FLOAT_EQ(f.valve.scale[1], 2);
    EXPECT_TRUE(f.hasFlags);
    EXPECT_EQ(f.value, 3);
}

TEST(MapParse, BrushDefKeepsTextureMatrix) {
    const char* text = R"({
"classname" "worldspawn"
{
brushDef
{
"editor_note" "kept by radiant"
( 0 0 64 ) ( 0 1 64 ) ( 1 0 64 ) ( ( 0.0078125 0 0.5 ) ( 0 0.015625 -0.25 ) ) gothic_block/blocks18c 0 4 0
( 0 0 0 ) ( 0 1 0 ) ( 1 0 0 ) ( ( 0.0078125 0 0 ) ( 0 0.0078125 0 ) ) common/caulk
}
}
}
)";
    MapFile map = parseMap(text, "bp.map");
    const MapBrush& b = map.entities[0].brushes[0];
    EXPECT_TRUE(b.brushPrimitive);
    ASSERT_EQ(b.faces.size(), 2u);
    EXPECT_EQ(b.faces[0].projection, TexProjection::BrushPrimitive);
    EXPECT_FLOAT_EQ(b.faces[0].primitive.matrix[0][0], 0.0078125f);
    EXPECT_FLOAT_EQ(b.faces[0].primitive.matrix[0][2], 0.5f);
    EXPECT_FLOAT_EQ(b.faces[0].primitive.matrix[1][1], 0.015625f);
    EXPECT_FLOAT_EQ(b.faces[0].primitive.matrix[1][2], -0.25f);
    EXPECT_EQ(b.faces[0].texture, "gothic_block/blocks18c");
    EXPECT_TRUE(b.faces[0].hasFlags);
    EXPECT_EQ(b.faces[0].surfaceFlags, 4);
    EXPECT_FALSE(b.faces[1].hasFlags);
    EXPECT_EQ(b.faces[1].texture, "common/caulk");
    EXPECT_DOUBLE_EQ(b.faces[0].plane.dist, 64);
}

TEST(MapParse, PatchDef2ColumnsAreFileGroups) {
    const char* text = R"({
"classname" "worldspawn"
{
patchDef2
{
base_trim/pewter
( 5 3 0 0 0 )
(
( ( 0 0 0 0 0 ) ( 0 10 0 0 1 ) ( 0 20 0 0 2 ) )
( ( 1 0 0 1 0 ) ( 1 10 0 1 1 ) ( 1 20 0 1 2 ) )
( ( 2 0 5 2 0 ) ( 2 10 5 2 1 ) ( 2 20 5 2 2 ) )
( ( 3 0 0 3 0 ) ( 3 10 0 3 1 ) ( 3 20 0 3 2 ) )
( ( 4 0 0 4 0 ) ( 4 10 0 4 1 ) ( 4 20 0 4 2 ) )
)
}
}
}
)";
    MapFile map = parseMap(text, "patch.map");
    ASSERT_EQ(map.entities[0].patches.size(), 1u);
    const MapPatch& p = map.entities[0].patches[0];
    EXPECT_FALSE(p.patchDef3);
    EXPECT_EQ(p.texture, "base_trim/pewter");
    EXPECT_EQ(shaderNameForTexture(p.texture), "textures/base_trim/pewter");
    EXPECT_EQ(p.width, 5);
    EXPECT_EQ(p.height, 3);
    EXPECT_EQ(p.line, 3);
    ASSERT_EQ(p.control.size(), 15u);
    for (int column = 0; column < 5; ++column) {
        for (int row = 0; row < 3; ++row) {
            EXPECT_FLOAT_EQ(p.at(column, row).xyz.x, float(column));
            EXPECT_FLOAT_EQ(p.at(column, row).xyz.y, float(row * 10));
            EXPECT_FLOAT_EQ(p.at(column, row).st[0], float(column));
            EXPECT_FLOAT_EQ(p.at(column, row).st[1], float(row));
        }
    }
    EXPECT_FLOAT_EQ(p.at(2, 1).xyz.z, 5);
}

TEST(MapParse, PatchDef3AndTrailingPairs) {
    const char* text = R"(Version 2
{
"classname" "func_group"
{
patchDef3
{
"textures/common/caulk"
( 3 3 4 6 1 2 3 )
(
( ( 0 0 0 0 0 ) ( 0 1 0 0 1 ) ( 0 2 0 0 2 ) )
( ( 1 0 0 1 0 ) ( 1 1 0 1 1 ) ( 1 2 0 1 2 ) )
( ( 2 0 0 2 0 ) ( 2 1 0 2 1 ) ( 2 2 0 2 2 ) )
)
"note" "ignored"
}
}
}
)";
    MapFile map = parseMap(text, "p3.map");
    EXPECT_EQ(map.version, 2);
    const MapPatch& p = map.entities[0].patches[0];
    EXPECT_TRUE(p.patchDef3);
    EXPECT_EQ(p.texture, "textures/common/caulk");
    EXPECT_EQ(p.subdivisions[0], 4);
    EXPECT_EQ(p.subdivisions[1], 6);
    EXPECT_EQ(p.contentFlags, 1);
    EXPECT_EQ(p.surfaceFlags, 2);
    EXPECT_EQ(p.value, 3);
}

TEST(MapParse, EntityPairsKeepOrderAndDuplicates) {
    const char* text = "{\r\n\"classname\" \"light\"\r\n\"origin\" \"1 -2 3.5\"\r\n\"target\" \"a\"\r\n"
                       "\"target\" \"b\"\r\n\"_color  \" \"1 0.5 0  \"\r\nunquoted value\r\n}\r\n";
    MapFile map = parseMap(text, "crlf.map");
    const MapEntity& e = map.entities[0];
    ASSERT_EQ(e.pairs.size(), 6u);
    EXPECT_EQ(e.pairs[2].second, "a");
    EXPECT_EQ(e.pairs[3].second, "b");
    EXPECT_EQ(*e.find("TARGET"), "a");
    EXPECT_EQ(e.pairs[4].first, "_color");
    EXPECT_EQ(e.value("_color"), "1 0.5 0");
    EXPECT_EQ(e.value("unquoted"), "value");
    EXPECT_EQ(e.value("missing", "fallback"), "fallback");
    Vec3 origin;
    ASSERT_TRUE(e.origin(origin));
    EXPECT_EQ(origin, Vec3(1, -2, 3.5f));
    EXPECT_TRUE(isLightEntity(e));
}

TEST(MapParse, LightEntitiesByClassnamePrefix) {
    const char* text = R"({ "classname" "worldspawn" }
{ "classname" "light" "light" "300" }
{ "classname" "info_player_start" }
{ "classname" "Light_Spot" }
{ "classname" "lightJunior" }
{ "classname" "target_light" }
{ "classname" "lig" }
)";
    MapFile map = parseMap(text, "lights.map");
    ASSERT_EQ(map.entities.size(), 7u);
    std::vector<const MapEntity*> lights = lightEntities(map);
    ASSERT_EQ(lights.size(), 3u);
    EXPECT_EQ(lights[0]->number, 1);
    EXPECT_EQ(lights[1]->number, 3);
    EXPECT_EQ(lights[2]->number, 4);
    EXPECT_EQ(lights[0]->value("light"), "300");
}

TEST(MapParse, CommentsEmptyFileAndEmptyBrush) {
    EXPECT_TRUE(parseMap("", "empty.map").entities.empty());
    EXPECT_TRUE(parseMap("// nothing here\n/* block\ncomment */\n", "c.map").entities.empty());
    MapFile map = parseMap("// entity 0\n{\n// brush 0\n{\n}\n/* b */ \"k\" \"v\"\n}\n", "e.map");
    ASSERT_EQ(map.entities[0].brushes.size(), 1u);
    EXPECT_TRUE(map.entities[0].brushes[0].faces.empty());
    EXPECT_EQ(map.entities[0].value("k"), "v");
}

TEST(MapParse, PrimitivesNumberedInFileOrder) {
    const char* text = R"({
{
( 0 0 0 ) ( 0 1 0 ) ( 1 0 0 ) a 0 0 0 1 1
}
{
patchDef2
{
b
( 3 3 0 0 0 )
( ( ( 0 0 0 0 0 ) ( 0 1 0 0 1 ) ( 0 2 0 0 2 ) )
( ( 1 0 0 1 0 ) ( 1 1 0 1 1 ) ( 1 2 0 1 2 ) )
( ( 2 0 0 2 0 ) ( 2 1 0 2 1 ) ( 2 2 0 2 2 ) ) )
}
}
{
( 0 0 0 ) ( 0 1 0 ) ( 1 0 0 ) c 0 0 0 1 1
}
}
)";
    MapFile map = parseMap(text, "order.map");
    const MapEntity& e = map.entities[0];
    ASSERT_EQ(e.brushes.size(), 2u);
    ASSERT_EQ(e.patches.size(), 1u);
    EXPECT_EQ(e.brushes[0].primitiveNum, 0);
    EXPECT_EQ(e.patches[0].primitiveNum, 1);
    EXPECT_EQ(e.brushes[1].primitiveNum, 2);
    EXPECT_EQ(e.primitiveCount(), 3);
}
