// -json -unpack / -pack round trips and edits.
#include "json_test_util.h"

#include "file_io.h"
#include "json_writer.h"
#include "test_data.h"

#include <gtest/gtest.h>

#include <cstring>
#include <limits>

namespace q3 {
namespace {
namespace fs = std::filesystem;
using test::smallBsp;
using test::unpackThenPack;

TEST(JsonRoundTrip, PlainV46IsByteIdentical) {
    bsp::Bsp b = smallBsp();
    EXPECT_EQ(unpackThenPack(b, test::tempDir() / "small"), bsp::serializeBsp(b));
}

TEST(JsonRoundTrip, ShGridInLump18IsByteIdentical) {
    bsp::Bsp b = smallBsp();
    b.version = bsp::kVersionQL;
    b.headerLumps = 19;
    b.shGrid = sh::encodeGridLump(test::smallShGrid(3, 2, 2));
    fs::path folder = test::tempDir() / "sh";
    EXPECT_EQ(unpackThenPack(b, folder), bsp::serializeBsp(b));
    EXPECT_TRUE(fs::exists(folder / "GridPointsSH.json"));
}

TEST(JsonRoundTrip, ShGridInBspxIsByteIdentical) {
    bsp::Bsp b = smallBsp();
    b.setBspx("OTHER_LUMP", {1, 2, 3, 4, 5});
    b.setBspx(sh::kBspxLumpName, sh::encodeGridLump(test::smallShGrid(2, 2, 2)));
    b.setBspx("LAST", {9});
    EXPECT_EQ(unpackThenPack(b, test::tempDir() / "bspx"), bsp::serializeBsp(b));
}

TEST(JsonRoundTrip, EighteenEntryHeaderAndAdvertisements) {
    bsp::Bsp b = smallBsp();
    b.headerLumps = 18;
    EXPECT_EQ(unpackThenPack(b, test::tempDir() / "h18"), bsp::serializeBsp(b));
    b.version = bsp::kVersionQL;
    bsp::Advertisement ad{};
    ad.cellId = 7;
    ad.normal[2] = 1;
    ad.rect[3][1] = 12.5f;
    std::strcpy(ad.model, "*3");
    b.lump17.resize(sizeof(ad));
    std::memcpy(b.lump17.data(), &ad, sizeof(ad));
    EXPECT_EQ(unpackThenPack(b, test::tempDir() / "ql"), bsp::serializeBsp(b));
}

TEST(JsonRoundTrip, NonCanonicalEntityTextAndNameGarbageSurvive) {
    bsp::Bsp b = smallBsp();
    b.entities = "{\r\n  \"classname\"   \"worldspawn\"\n}\n{\n\"classname\" \"light\"\n\"origin\" \"0 0 64\"\n}";
    b.entities.push_back('\0');
    b.shaders[0].name[40] = 'x';  // bytes after the terminating NUL
    fs::path folder = test::tempDir() / "odd";
    EXPECT_EQ(unpackThenPack(b, folder), bsp::serializeBsp(b));
    EXPECT_TRUE(fs::exists(folder / "EntityText.json"));
}

TEST(JsonRoundTrip, NaNPayloadsSubnormalsAndInfinitiesSurvive) {
    bsp::Bsp b = smallBsp();
    const uint32_t payloadNaN = 0xFFC00000u;
    std::memcpy(&b.drawVerts[0].lightmap[1], &payloadNaN, 4);
    b.drawVerts[1].lightmap[0] = std::numeric_limits<float>::quiet_NaN();
    b.drawVerts[2].st[1] = std::numeric_limits<float>::denorm_min() * 3;
    b.drawVerts[3].st[0] = -std::numeric_limits<float>::infinity();
    EXPECT_EQ(unpackThenPack(b, test::tempDir() / "nan"), bsp::serializeBsp(b));
}

TEST(JsonRoundTrip, LightmapPagesAsPngImages) {
    bsp::Bsp b = smallBsp();
    json::JsonOptions options;
    options.lightmapImages = true;
    fs::path folder = test::tempDir() / "png";
    EXPECT_EQ(unpackThenPack(b, folder, options), bsp::serializeBsp(b));
    EXPECT_TRUE(fs::exists(folder / "lightmaps" / "lm_0000.png"));
    EXPECT_FALSE(fs::exists(folder / "LightBytes.json"));
}

TEST(JsonRoundTrip, FloatsAreWrittenInShortestForm) {
    EXPECT_EQ(json::formatFloat(160.0f), "160.0");
    EXPECT_EQ(json::formatFloat(0.1f), "0.1");
    EXPECT_EQ(json::formatFloat(-0.0f), "-0.0");
    EXPECT_EQ(json::formatFloat(1.0f / 3.0f), "0.33333334");
    for (float f : {1e-30f, 3.4028235e38f, 1.17549435e-38f, 123456.789f, 0.7872519493103027f}) {
        std::string text = json::formatFloat(f);
        EXPECT_EQ(std::strtof(text.c_str(), nullptr), f) << text;
    }
}

TEST(JsonEdit, OneLegacyGridValueChangesExactlyThatByte) {
    bsp::Bsp b = smallBsp();
    fs::path folder = test::tempDir() / "edit";
    Log log(false);
    json::unpackBsp(b, folder, {}, log);
    // GridPoint#4 ambient red is 4; set it to 200.
    std::string text = readFileText(folder / "GridPoints.json");
    size_t at = text.find("\"GridPoint#4\"");
    ASSERT_NE(at, std::string::npos);
    size_t ambient = text.find("\"ambient\": [[4, 2, 3]", at);
    ASSERT_NE(ambient, std::string::npos);
    text.replace(ambient, std::strlen("\"ambient\": [[4"), "\"ambient\": [[200");
    writeFileAtomic(folder / "GridPoints.json", text);

    std::vector<uint8_t> before = bsp::serializeBsp(b);
    std::vector<uint8_t> after = bsp::serializeBsp(json::packFolder(folder, {}, log));
    ASSERT_EQ(before.size(), after.size());
    std::vector<size_t> changed;
    for (size_t i = 0; i < before.size(); ++i)
        if (before[i] != after[i]) changed.push_back(i);
    ASSERT_EQ(changed.size(), 1u);
    bsp::Bsp packed = bsp::parseBsp(after, "packed");
    EXPECT_EQ(packed.lightGrid[4].ambient[0], 200);
}

TEST(JsonEdit, OneShCoefficientChangesExactlyThatFloat) {
    bsp::Bsp b = smallBsp();
    b.version = bsp::kVersionQL;
    b.headerLumps = 19;
    sh::GridSH grid = test::smallShGrid(2, 2, 1);
    b.shGrid = sh::encodeGridLump(grid);
    fs::path folder = test::tempDir() / "editsh";
    Log log(false);
    json::unpackBsp(b, folder, {}, log);
    // Point 2, coefficient 4, green channel.
    std::string old = json::formatFloat(grid.points[2].coeffs[4][1]);
    test::replaceInFile(folder / "GridPointsSH.json", old, "7.25");

    bsp::Bsp packed = json::packFolder(folder, {}, log);
    sh::GridSH out;
    std::string error;
    ASSERT_TRUE(sh::decodeGridLump(packed.shGrid.data(), packed.shGrid.size(), out, error)) << error;
    for (size_t p = 0; p < grid.points.size(); ++p)
        for (int k = 0; k < 9; ++k)
            for (int c = 0; c < 3; ++c) {
                float expected = (p == 2 && k == 4 && c == 1) ? 7.25f : grid.points[p].coeffs[k][c];
                EXPECT_EQ(out.points[p].coeffs[k][c], expected) << p << " " << k << " " << c;
            }
    EXPECT_EQ(bsp::lumpBytes(packed, bsp::LUMP_LIGHTGRID), bsp::lumpBytes(b, bsp::LUMP_LIGHTGRID));
}

TEST(JsonFlags, NamesDecomposeAndPackBackByValueOrByName) {
    bsp::Bsp b = smallBsp();
    fs::path folder = test::tempDir() / "flags";
    Log log(false);
    json::unpackBsp(b, folder, {}, log);
    std::string shaders = readFileText(folder / "shaders.json");
    EXPECT_NE(shaders.find("\"default\": \"0x00000001\""), std::string::npos) << shaders;
    EXPECT_NE(shaders.find("\"sky\": \"0x00000004\""), std::string::npos);
    EXPECT_NE(shaders.find("\"nodraw\": \"0x00000080\""), std::string::npos);

    // By value, a name's hex counts; by name, the table's bits count.
    test::replaceInFile(folder / "shaders.json", "\"sky\": \"0x00000004\"", "\"sky\": \"0x00000001\"");
    json::JsonOptions byValue;
    EXPECT_EQ(json::packFolder(folder, byValue, log).shaders[1].surfaceFlags, 0x1 | 0x80 | 0x2000);
    json::JsonOptions byName;
    byName.useFlagNames = true;
    EXPECT_EQ(json::packFolder(folder, byName, log).shaders[1].surfaceFlags, 0x4 | 0x80 | 0x2000);

    test::replaceInFile(folder / "shaders.json", "\"nodraw\"", "\"nodraww\"");
    EXPECT_THROW(json::packFolder(folder, byName, log), std::exception);
    byName.skipFlags = true;
    EXPECT_EQ(json::packFolder(folder, byName, log).shaders[1].surfaceFlags, 0x4 | 0x2000);
}

}  // namespace
}  // namespace q3
