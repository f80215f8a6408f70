// Malformed hand-edited JSON: one clear error naming file, line, column and field; nothing written.
// Also a folder in q3map2 2.5.17n's own layout, written by hand from its observed output.
#include "json_test_util.h"

#include "file_io.h"
#include "json_error.h"
#include "test_data.h"

#include <gtest/gtest.h>

namespace q3 {
namespace {
namespace fs = std::filesystem;

struct BadCase {
    const char* name;
    const char* file;
    const char* from;
    const char* to;
    const char* expected;  // fragment of the message
};

const BadCase kBadCases[] = {
    {"syntax", "planes.json", "\"plane#1\": [", "\"plane#1\" [", "planes.json:3:"},
    {"unterminated", "entities.json", "\"worldspawn\"", "\"worldspawn", "entities.json:"},
    {"missingMember", "DrawVert.json", "\"normal\": [0.0, 0.0, 1.0],", "", "DrawVert#0: missing member \"normal\""},
    {"wrongType", "Brushes.json", "\"numSides\": 1", "\"numSides\": \"one\"", "Brush#0.numSides: expected an integer, found a string"},
    {"shortArray", "planes.json", "[0.0, 0.0, 1.0, 0.0]", "[0.0, 0.0, 1.0]", "plane#0: expected an array of 4 elements, found 3"},
    {"byteRange", "GridPoints.json", "[[0, 2, 3]", "[[256, 2, 3]", "GridPoint#0.ambient: byte value 256 is out of range"},
    {"numRange", "LightBytes.json", "\"Num\": 3", "\"Num\": 300", "LightByte#0: \"Num\" 300 is out of range 0..255"},
    {"numType", "DrawIndexes.json", "\"Num\": 0", "\"Num\": 0.5", "\"Num\" must be an integer"},
    {"shaderIndex", "DrawSurfaces.json", "\"shaderNum\": 0", "\"shaderNum\": 9", "DrawSurface#0.shaderNum: 9 is out of range (shaders.json has 2)"},
    {"vertRange", "DrawSurfaces.json", "\"numVerts\": 4", "\"numVerts\": 40", "DrawSurface#0.firstVert: range 0+40 is out of range"},
    {"planeIndex", "BrushSides.json", "\"planeNum\": 1", "\"planeNum\": -5", "BrushSide#0.planeNum: -5 is out of range"},
    {"badFlagHex", "shaders.json", "\"0x00000001\"", "\"one\"", "shader#0.contentFlags.default: expected a hexadecimal string"},
    {"shCount", "GridPointsSH.json", "\"gridBounds\": [2, 2, 1]", "\"gridBounds\": [2, 2, 2]", "points: count 4 does not match gridBounds (8 points)"},
    {"shNotNumber", "GridPointsSH.json", "0.33333334", "\"x\"", "points[0]: expected a number, found a string"},
    {"entityMember", "entities.json", "\"KeyValue\": [\"message\"", "\"Key\": [\"message\"", "entity#0: unexpected member \"Key\""},
    {"floatRange", "models.json", "\"mins\": [-64.0", "\"mins\": [1e99", "does not fit a float"},
    {"childIndex", "nodes.json", "\"children\": [-1, -2]", "\"children\": [-1, -9]", "node#0.children: 8 is out of range (leafs.json has 2)"},
    {"notObject", "fogs.json", "{}", "[]", "fogs.json: expected an object, found an array"},
};

class JsonBadInput : public ::testing::TestWithParam<BadCase> {};

TEST_P(JsonBadInput, ClearErrorAndNothingWritten) {
    const BadCase& c = GetParam();
    fs::path dir = test::tempDir();
    bsp::Bsp b = test::smallBsp();
    b.version = bsp::kVersionQL;
    b.headerLumps = 19;
    b.shGrid = sh::encodeGridLump(test::smallShGrid(2, 2, 1));
    fs::path map = test::writeMap(dir, "bad", b);
    Log log(false);
    CommonOptions common;
    common.mapPath = map;
    json::JsonOptions unpack;
    unpack.unpack = true;
    ASSERT_EQ(json::runJsonStage(unpack, common, log), 0);
    fs::path folder = dir / "maps" / "bad";
    test::replaceInFile(folder / c.file, c.from, c.to);

    json::JsonOptions pack;
    pack.pack = true;
    std::string message;
    try {
        json::runJsonStage(pack, common, log);
    } catch (const std::exception& e) {
        message = e.what();
    }
    EXPECT_NE(message.find(c.expected), std::string::npos) << "message: " << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_NE(message.find(c.file), std::string::npos) << message;
    EXPECT_FALSE(fs::exists(dir / "maps" / "bad_json.bsp"));
}

INSTANTIATE_TEST_SUITE_P(Cases, JsonBadInput, ::testing::ValuesIn(kBadCases),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(JsonQ3map2Folder, HandMadeQ3map2LayoutPacks) {
    fs::path dir = test::tempDir();
    fs::path folder = dir / "maps" / "hand";
    fs::create_directories(folder);
    auto put = [&](const char* name, const std::string& text) { writeFileAtomic(folder / name, text); };
    put("shaders.json", R"({
    "shader#0": {
        "shader": "textures/stone/marble02b_floor",
        "surfaceFlags": {},
        "contentFlags": {
            "default": "0x00000001"
        }
    }
})");
    put("models.json", R"({
    "model#0": {
        "minmax": {
            "mins": [-632.0, -560.0, 152.0],
            "maxs": [-504.0, -400.0, 160.0]
        },
        "firstBSPSurface": 0,
        "numBSPSurfaces": 1,
        "firstBSPBrush": 0,
        "numBSPBrushes": 0
    }
})");
    put("planes.json", "{\n    \"plane#0\": [0.0, 0.0, 1.0, 800.0],\n    \"plane#1\": [0.0, 0.0, -1.0, -800.0]\n}");
    put("leafs.json", R"({
    "leaf#0": {
        "cluster": -1, "area": 0,
        "minmax": { "mins": [0, 0, 0], "maxs": [0, 0, 0] },
        "firstBSPLeafSurface": 0, "numBSPLeafSurfaces": 0,
        "firstBSPLeafBrush": 0, "numBSPLeafBrushes": 0
    },
    "leaf#1": {
        "cluster": 0, "area": 0,
        "minmax": { "mins": [0, 1024, 0], "maxs": [1024, 1528, 792] },
        "firstBSPLeafSurface": 0, "numBSPLeafSurfaces": 1,
        "firstBSPLeafBrush": 0, "numBSPLeafBrushes": 0
    }
})");
    put("nodes.json", R"({
    "node#0": { "planeNum": 0, "children": [-1, -2],
        "minmax": { "mins": [-7136, -1624, -784], "maxs": [1024, 1528, 792] } }
})");
    put("LeafSurfaces.json", "{\n    \"LeafSurface#0\": {\n        \"Num\": 0\n    }\n}");
    put("LeafBrushes.json", "{}");
    put("Brushes.json", "{}");
    put("BrushSides.json", "{}");
    put("DrawVert.json", R"({
    "DrawVert#0": {
        "xyz": [-504.0, -400.0, 160.0],
        "st": [0.7872519493103027, 0.327178955078125],
        "lightmap": [[0.61328125, 0.64453125], [0.0, 0.0], [0.0, 0.0], [0.0, 0.0]],
        "normal": [0.0, 0.0, 1.0],
        "color": [[55, 55, 51, 255], [0, 0, 0, 0], [0, 0, 0, 0], [0, 0, 0, 0]]
    },
    "DrawVert#1": {
        "xyz": [-632.0, -400.0, 160.0],
        "st": [0.7872509956359863, 1.3072700500488281],
        "lightmap": [[0.55078125, 0.64453125], [0.0, 0.0], [0.0, 0.0], [0.0, 0.0]],
        "normal": [0.0, 0.0, 1.0],
        "color": [[55, 55, 50, 255], [0, 0, 0, 0], [0, 0, 0, 0], [0, 0, 0, 0]]
    },
    "DrawVert#2": {
        "xyz": [-632.0, -560.0, 160.0],
        "st": [0.5, 0.25],
        "lightmap": [[0.5, 0.5], [0.0, 0.0], [0.0, 0.0], [0.0, 0.0]],
        "normal": [0.0, 0.0, 1.0],
        "color": [[1, 2, 3, 4], [0, 0, 0, 0], [0, 0, 0, 0], [0, 0, 0, 0]]
    }
})");
    put("DrawSurfaces.json", R"({
    "DrawSurface#0": {
        "shaderNum": 0,
        "fogNum": -1,
        "surfaceType": 3,
        "firstVert": 0,
        "numVerts": 3,
        "firstIndex": 0,
        "numIndexes": 3,
        "lightmapStyles": [0, 255, 255, 255],
        "vertexStyles": [0, 255, 255, 255],
        "lightmapNum": [-3, -3, -3, -3],
        "lightmapX": [0, 0, 0, 0],
        "lightmapY": [0, 0, 0, 0],
        "lightmapWidth": 0,
        "lightmapHeight": 0,
        "lightmapOrigin": [-632.0, -560.0, 160.0],
        "lightmapVecs": [[-632.0, -560.0, 152.0], [-504.0, -400.0, 160.0], [0.0, 0.0, 1.0]],
        "patchWidth": 0,
        "patchHeight": 0
    }
})");
    put("fogs.json", "{}");
    put("DrawIndexes.json", R"({ "DrawIndex#0": { "Num": 0 }, "DrawIndex#1": { "Num": 1 }, "DrawIndex#2": { "Num": 2 } })");
    put("VisBytes.json", "{}");
    put("LightBytes.json", "{}");
    put("entities.json", R"({
    "entity#0": {
        "KeyValue": ["classname", "worldspawn"],
        "KeyValue": ["message", "Uphill Battle"],
        "KeyValue": ["music", "music/OA03.ogg"]
    },
    "entity#1": {
        "KeyValue": ["classname", "weapon_rocketlauncher"],
        "KeyValue": ["origin", "-6000.000000 -416.000000 160.000000"],
        "KeyValue": ["angle", "180.000000"]
    }
})");
    put("GridPoints.json", R"({
    "GridPoint#0": {
        "ambient": [[1, 2, 3], [0, 0, 0], [0, 0, 0], [0, 0, 0]],
        "directed": [[4, 5, 6], [0, 0, 0], [0, 0, 0], [0, 0, 0]],
        "styles": [0, 255, 255, 255],
        "latLong": [7, 8]
    }
})");
    Log log(false);
    CommonOptions common;
    common.mapPath = dir / "maps" / "hand.bsp";
    json::JsonOptions pack;
    pack.pack = true;
    ASSERT_EQ(json::runJsonStage(pack, common, log), 0);
    bsp::Bsp b = bsp::readBsp(dir / "maps" / "hand_json.bsp");
    EXPECT_EQ(b.version, 46);
    ASSERT_EQ(b.shaders.size(), 1u);
    EXPECT_STREQ(b.shaders[0].name, "textures/stone/marble02b_floor");
    EXPECT_EQ(b.shaders[0].contentFlags, 1);
    ASSERT_EQ(b.planes.size(), 2u);
    EXPECT_EQ(b.planes[1].dist, -800.0f);
    ASSERT_EQ(b.drawVerts.size(), 3u);
    EXPECT_EQ(b.drawVerts[0].st[0], 0.7872519493103027f);
    EXPECT_EQ(b.drawVerts[1].lightmap[0], 0.55078125f);
    EXPECT_EQ(b.drawVerts[0].color[2], 51);
    EXPECT_EQ(b.surfaces[0].lightmapNum, -3);
    EXPECT_EQ(b.surfaces[0].lightmapVecs[1][0], -504.0f);
    ASSERT_EQ(b.lightGrid.size(), 1u);
    EXPECT_EQ(b.lightGrid[0].directed[2], 6);
    EXPECT_EQ(b.lightGrid[0].latLong[1], 8);
    std::vector<bsp::Entity> entities = bsp::parseEntities(b.entities, "hand");
    ASSERT_EQ(entities.size(), 2u);
    EXPECT_EQ(entities[0].value("music"), "music/OA03.ogg");
    EXPECT_EQ(entities[1].value("angle"), "180.000000");
}

}  // namespace
}  // namespace q3
