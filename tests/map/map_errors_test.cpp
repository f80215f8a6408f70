// Malformed .map input: each mistake gives one ScriptError naming the file and the line.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "file_io.h"
#include "map_file.h"
#include "script.h"
#include "test_data.h"

using namespace q3;
using namespace q3::map;

namespace {

// Parses `text` expecting failure; returns the message.
std::string errorOf(const std::string& text) {
    try {
        parseMap(text, "bad.map");
    } catch (const ScriptError& e) {
        return e.what();
    }
    ADD_FAILURE() << "no error for:\n" << text;
    return {};
}

void expectErrorAt(const std::string& text, int line, const std::string& fragment) {
    const std::string message = errorOf(text);
    const std::string prefix = "bad.map:" + std::to_string(line) + ": ";
    EXPECT_EQ(message.rfind(prefix, 0), 0u) << "message: " << message << "\nexpected prefix: " << prefix;
    EXPECT_NE(message.find(fragment), std::string::npos) << "message: " << message << "\nexpected: " << fragment;
    EXPECT_EQ(message.find('\n'), std::string::npos) << "message spans lines: " << message;
}

const char* kPatchHead = "{\n{\npatchDef2\n{\ntex\n( 3 3 0 0 0 )\n(\n";

}  // namespace

TEST(MapErrors, MissingClosingBraceOfEntity) {
    expectErrorAt("{\n\"classname\" \"worldspawn\"\n{\n( 0 0 0 ) ( 0 1 0 ) ( 1 0 0 ) a 0 0 0 1 1\n}\n", 5,
                  "missing '}'");
}

TEST(MapErrors, MissingClosingBraceOfBrush) {
    expectErrorAt("{\n{\n( 0 0 0 ) ( 0 1 0 ) ( 1 0 0 ) a 0 0 0 1 1\n", 3, "missing '}'");
}

TEST(MapErrors, ExtraClosingBrace) {
    expectErrorAt("{\n\"classname\" \"worldspawn\"\n}\n}\n", 4, "expected '{' to open entity 1");
}

TEST(MapErrors, TextOutsideEntities) {
    expectErrorAt("\"classname\" \"worldspawn\"\n", 1, "expected '{'");
}

TEST(MapErrors, MissingPlanePoint) {
    expectErrorAt("{\n{\n( 0 0 0 ) ( 0 1 0 ) a 0 0 0 1 1\n}\n}\n", 3, "plane point 3");
}

TEST(MapErrors, PlanePointWithTwoCoordinates) {
    expectErrorAt("{\n{\n( 0 0 0 ) ( 0 1 ) ( 1 0 0 ) a 0 0 0 1 1\n}\n}\n", 3, "plane point 2");
}

TEST(MapErrors, BadNumberInPlanePoint) {
    expectErrorAt("{\n{\n( 0 0 0 ) ( 0 1 0 ) ( 1 0 zero ) a 0 0 0 1 1\n}\n}\n", 3, "found 'zero'");
}

TEST(MapErrors, BadTextureScale) {
    expectErrorAt("{\n{\n( 0 0 0 ) ( 0 1 0 ) ( 1 0 0 ) a 0 0 0 1 1x\n}\n}\n", 3, "texture scale T");
}

TEST(MapErrors, MissingTextureShift) {
    expectErrorAt("{\n{\n( 0 0 0 ) ( 0 1 0 ) ( 1 0 0 ) a\n( 0 0 0 ) ( 0 1 0 ) ( 1 0 0 ) a 0 0 0 1 1\n}\n}\n", 3,
                  "line ends before the texture shift");
}

TEST(MapErrors, IncompleteFlags) {
    expectErrorAt("{\n{\n( 0 0 0 ) ( 0 1 0 ) ( 1 0 0 ) a 0 0 0 1 1 0 0\n}\n}\n", 3, "surface value");
}

TEST(MapErrors, FractionalFlags) {
    expectErrorAt("{\n{\n( 0 0 0 ) ( 0 1 0 ) ( 1 0 0 ) a 0 0 0 1 1 0 0.5 0\n}\n}\n", 3, "integer");
}

TEST(MapErrors, MissingTextureName) {
    expectErrorAt("{\n{\n( 0 0 0 ) ( 0 1 0 ) ( 1 0 0 )\n( 0 0 0 ) ( 0 1 0 ) ( 1 0 0 ) a 0 0 0 1 1\n}\n}\n", 4,
                  "missing texture name");
}

TEST(MapErrors, UnknownBlock) {
    expectErrorAt("{\n\"classname\" \"worldspawn\"\n{\nterrainDef\n{\n}\n}\n}\n", 4, "unknown primitive 'terrainDef'");
}

TEST(MapErrors, FaceOutsideBrush) {
    expectErrorAt("{\n( 0 0 0 ) ( 0 1 0 ) ( 1 0 0 ) a 0 0 0 1 1\n}\n", 2, "unexpected '('");
}

TEST(MapErrors, KeyWithoutValue) {
    expectErrorAt("{\n\"classname\"\n\"origin\" \"0 0 0\"\n}\n", 2, "key 'classname' of entity 0 has no value");
}

TEST(MapErrors, TruncatedPatch) {
    std::string text = std::string(kPatchHead) + "( ( 0 0 0 0 0 ) ( 0 1 0 0 1 ) ( 0 2 0 0 2 ) )\n( ( 1 0 0 1 0 ) ( 1 1";
    expectErrorAt(text, 9, "unexpected end of file");
}

TEST(MapErrors, PatchRowTooShort) {
    std::string text = std::string(kPatchHead) +
                       "( ( 0 0 0 0 0 ) ( 0 1 0 0 1 ) ( 0 2 0 0 2 ) )\n( ( 1 0 0 1 0 ) ( 1 1 0 1 1 ) )\n"
                       "( ( 2 0 0 2 0 ) ( 2 1 0 2 1 ) ( 2 2 0 2 2 ) )\n)\n}\n}\n}\n";
    expectErrorAt(text, 9, "control point 2 of column 1");
}

TEST(MapErrors, PatchControlPointMissingTexCoord) {
    std::string text = std::string(kPatchHead) + "( ( 0 0 0 0 ) ( 0 1 0 0 1 ) ( 0 2 0 0 2 ) )\n";
    expectErrorAt(text, 8, "control point 0 of column 0");
}

TEST(MapErrors, EvenPatchWidth) {
    expectErrorAt("{\n{\npatchDef2\n{\ntex\n( 4 3 0 0 0 )\n", 6, "width");
}

TEST(MapErrors, OversizedPatch) {
    expectErrorAt("{\n{\npatchDef2\n{\ntex\n( 3 33 0 0 0 )\n", 6, "height");
}

TEST(MapErrors, PatchMissingClosingBraces) {
    std::string text = std::string(kPatchHead) +
                       "( ( 0 0 0 0 0 ) ( 0 1 0 0 1 ) ( 0 2 0 0 2 ) )\n( ( 1 0 0 1 0 ) ( 1 1 0 1 1 ) ( 1 2 0 1 2 ) )\n"
                       "( ( 2 0 0 2 0 ) ( 2 1 0 2 1 ) ( 2 2 0 2 2 ) )\n)\n}\n";
    expectErrorAt(text, 12, "unexpected end of file");
}

TEST(MapErrors, BrushDefMissingMatrix) {
    expectErrorAt("{\n{\nbrushDef\n{\n( 0 0 0 ) ( 0 1 0 ) ( 1 0 0 ) common/caulk 0 0 0\n}\n}\n}\n", 5,
                  "texture matrix");
}

TEST(MapErrors, UnterminatedQuote) {
    expectErrorAt("{\n\"classname\" \"worldspawn\n}\n", 2, "unterminated");
}

TEST(MapErrors, MissingFileIsFileError) {
    const std::filesystem::path dir = q3::test::tempDir();
    EXPECT_THROW(loadMap(dir / "absent.map"), FileError);
}

TEST(MapErrors, LoadMapNamesThePath) {
    const std::filesystem::path dir = q3::test::tempDir();
    const std::filesystem::path file = dir / "broken.map";
    writeFileAtomic(file, std::string("{\n\"a\" \"b\"\n"));
    try {
        loadMap(file);
        FAIL() << "no error";
    } catch (const ScriptError& e) {
        EXPECT_EQ(std::string(e.what()).rfind(file.string() + ":2: ", 0), 0u) << e.what();
    }
}

TEST(MapErrors, TextureScaleOnNextLine) {
    expectErrorAt("{\n{\n( 0 0 0 ) ( 0 1 0 ) ( 1 0 0 ) a 0 0 0 1\n1\n}\n}\n", 3, "line ends before texture scale T");
}

// Messages are composed only when reported: the whole text still names the face, point and axis.
TEST(MapErrors, ComposedMessagesNameEveryPart) {
    EXPECT_NE(errorOf("{\n{\n( 0 0 0 ) ( 0 1 0 ) ( 1 0 zero ) a 0 0 0 1 1\n}\n}\n")
                  .find("expected a number for plane point 3 in face 0 of entity 0, primitive 0 z, found 'zero'"),
              std::string::npos)
        << errorOf("{\n{\n( 0 0 0 ) ( 0 1 0 ) ( 1 0 zero ) a 0 0 0 1 1\n}\n}\n");
    const std::string patch = errorOf(std::string(kPatchHead) + "( ( 0 0 0 0 0 ) ( 0 1 0 0 0 ) ( 0 2 0 0 x ) )\n");
    EXPECT_NE(patch.find("control point 2 of column 0 of patchDef2 in entity 0, primitive 0 t"), std::string::npos)
        << patch;
    const std::string valve = errorOf("{\n{\n( 0 0 0 ) ( 0 1 0 ) ( 1 0 0 ) a [ 1 0 0 0 ] [ 0 1 0 q ] 0 1 1\n}\n}\n");
    EXPECT_NE(valve.find("T texture axis in face 0 of entity 0, primitive 0 offset, found 'q'"), std::string::npos) << valve;
}
