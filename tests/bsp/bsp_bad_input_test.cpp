// Bad input to `q3map2 -bsp`, through the executable: each case gives q3map2's warning and a
// BSP without the broken primitive, or one ERROR line naming the file and exit status 1; never a
// crash. What q3map2 2.5.17n does with the same maps is noted at each test.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "bsp_test_maps.h"
#include "bspfile.h"
#include "file_io.h"
#include "test_data.h"

namespace q3::bspstage {
namespace {

namespace fs = std::filesystem;

const std::string kRoom = test::hollowRoom({0, 0, 0}, {512, 512, 256});
const std::string kPlayer = test::pointEntity("info_player_deathmatch", {128, 128, 64});
const std::string kFace = " base/wall 0 0 0 0.5 0.5 0 0 0\n";

struct Compiled {
    int status = -1;
    std::string output;
    fs::path bsp;
    std::vector<std::string> lines(const std::string& prefix) const {
        std::vector<std::string> found;
        std::istringstream in(output);
        for (std::string line; std::getline(in, line);)
            if (line.rfind(prefix, 0) == 0) found.push_back(line);
        return found;
    }
    bool says(const std::string& line) const {
        std::istringstream in(output);
        for (std::string l; std::getline(in, l);)
            if (l == line) return true;
        return false;
    }
};

// A game folder with the map (and any extra files, path relative to baseoa/), compiled with -bsp.
Compiled compile(const std::string& mapText, const std::vector<std::pair<std::string, std::string>>& files = {}) {
    const fs::path base = q3::test::tempDir();
    const fs::path game = base / "baseoa";
    fs::create_directories(game / "maps");
    for (const auto& [path, content] : files) {
        fs::create_directories((game / path).parent_path());
        writeFileAtomic(game / path, content);
    }
    Compiled run;
    const fs::path map = game / "maps" / "bad.map";
    writeFileAtomic(map, mapText);
    run.bsp = game / "maps" / "bad.bsp";
    run.status = q3::test::runCommand(q3::test::q3map2Exe().string() + " -threads 2 -fs_basepath " + q3::test::shellQuote(base) +
                                      " -fs_basegame baseoa -bsp " + q3::test::shellQuote(map),
                                  &run.output);
    return run;
}

// A sealed room around the player plus `extra` inside the worldspawn (and `entities` after it).
std::string roomWith(const std::string& extra, const std::string& entities = {}) {
    return test::worldspawn(kRoom + extra) + kPlayer + entities;
}

bsp::Bsp compiledOk(const Compiled& run) {
    EXPECT_EQ(run.status, 0) << run.output;
    EXPECT_TRUE(run.lines("ERROR").empty()) << run.output;
    return bsp::readBsp(run.bsp);
}

// One ERROR line that names the map file, exit status 1, no BSP.
void failsCleanly(const Compiled& run, const std::string& fragment) {
    EXPECT_EQ(run.status, 1) << run.output;
    const std::vector<std::string> errors = run.lines("ERROR");
    ASSERT_EQ(errors.size(), 1u) << run.output;
    EXPECT_NE(errors[0].find("bad.map"), std::string::npos) << errors[0];
    EXPECT_NE(errors[0].find(fragment), std::string::npos) << errors[0];
    EXPECT_FALSE(fs::exists(run.bsp));
}

// A box brush's six faces, as lines, to take sides out or add some.
std::vector<std::string> boxFaces(DVec3 mins, DVec3 maxs) {
    std::vector<std::string> faces;
    std::istringstream in(test::boxBrush(mins, maxs));
    for (std::string line; std::getline(in, line);)
        if (!line.empty() && line[0] == '(') faces.push_back(line + "\n");
    return faces;
}

std::string brushOf(const std::vector<std::string>& faces) {
    std::string s = "{\n";
    for (const std::string& f : faces) s += f;
    return s + "}\n";
}

// q3map2: no message; the brush has no closed volume and is dropped.
TEST(BspBadInput, ABrushOfThreePlanesIsDropped) {
    const std::string open = "{\n( 0 0 0 ) ( 0 1 0 ) ( 0 0 1 )" + kFace + "( 64 0 0 ) ( 64 0 1 ) ( 64 1 0 )" + kFace +
                             "( 0 0 0 ) ( 1 0 0 ) ( 0 1 0 )" + kFace + "}\n";
    const bsp::Bsp out = compiledOk(compile(roomWith(open)));
    EXPECT_EQ(out.brushes.size(), 6u);
}

// A box brush in the room with `face` put before its side `at` (an empty face: a copy of side 0);
// returns the compiled BSP's brushes after checking that q3map2's `message` was given.
std::vector<bsp::Brush> boxWithExtraFace(size_t at, std::string face, const std::string& message) {
    std::vector<std::string> faces = boxFaces({100, 100, 100}, {164, 164, 164});
    faces.insert(faces.begin() + std::ptrdiff_t(at), face.empty() ? faces[0] : face + kFace);
    const Compiled run = compile(roomWith(brushOf(faces)));
    EXPECT_TRUE(run.says("WARNING: Entity 0, Brush 6: " + message)) << run.output;
    return compiledOk(run).brushes;
}

// q3map2: "Entity 0, Brush 6: duplicate plane"; the brush keeps one copy of the plane.
TEST(BspBadInput, ACoincidentPlaneIsReportedAndRemoved) {
    const std::vector<bsp::Brush> brushes = boxWithExtraFace(1, "", "duplicate plane");
    ASSERT_EQ(brushes.size(), 7u);
    for (const bsp::Brush& b : brushes) EXPECT_EQ(b.numSides, 6);
}

// q3map2: "Entity 0, Brush 6: mirrored plane"; the brush is dropped.
TEST(BspBadInput, OppositePlanesDropTheBrush) {
    EXPECT_EQ(boxWithExtraFace(1, "( 100 0 0 ) ( 100 0 1 ) ( 100 1 0 )", "mirrored plane").size(), 6u);
}

// q3map2: "Entity 0, Brush 6: degenerate plane" (three points on a line); the side is removed.
TEST(BspBadInput, ASideOfCollinearPointsIsReportedAndRemoved) {
    const std::vector<bsp::Brush> brushes = boxWithExtraFace(3, "( 0 0 0 ) ( 1 0 0 ) ( 2 0 0 )", "degenerate plane");
    ASSERT_EQ(brushes.size(), 7u);
    for (const bsp::Brush& b : brushes) EXPECT_EQ(b.numSides, 6);
}

std::string patch3x3(const std::function<std::string(int, int)>& point) {
    std::string rows;
    for (int i = 0; i < 3; ++i) {
        rows += "( ";
        for (int j = 0; j < 3; ++j) rows += "( " + point(i, j) + " 0 0 ) ";
        rows += ")\n";
    }
    return "{\npatchDef2\n{\nbase/wall\n( 3 3 0 0 0 )\n(\n" + rows + ")\n}\n}\n";
}

// q3map2: "Entity 0, Brush 6: degenerate patch" for a patch of one point and for a flat line;
// neither is drawn.
TEST(BspBadInput, DegeneratePatchesAreReportedAndDropped) {
    for (const std::string& patch : {patch3x3([](int, int) { return std::string("200 200 50"); }),
                                     patch3x3([](int, int j) { return std::to_string(200 + 8 * j) + " 200 50"; })}) {
        const Compiled run = compile(roomWith(patch));
        const bsp::Bsp out = compiledOk(run);
        EXPECT_TRUE(run.says("WARNING: Entity 0, Brush 6: degenerate patch")) << run.output;
        for (const bsp::Surface& s : out.surfaces) EXPECT_NE(s.surfaceType, 2);  // no patch surface
    }
}

// q3map2: no message; brushes reaching past +-65536 are dropped, the rest compiles.
TEST(BspBadInput, BrushesPastTheWorldBoundsAreDropped) {
    const Compiled run = compile(roomWith(test::boxBrush({70000, 0, 0}, {70064, 64, 64}) +
                                     test::boxBrush({-1e9, 0, 0}, {1e9, 64, 64})));
    const bsp::Bsp out = compiledOk(run);
    EXPECT_EQ(out.brushes.size(), 6u);
    for (int k = 0; k < 3; ++k) {
        EXPECT_GE(out.models[0].mins[k], -16.f);
        EXPECT_LE(out.models[0].maxs[k], 528.f);
    }
}

// q3map2: "WARNING: Couldn't find image for shader textures/nope/missing"; the face is drawn.
TEST(BspBadInput, AMissingShaderIsAWarning) {
    const Compiled run = compile(roomWith(test::boxBrush({100, 100, 100}, {164, 164, 164}, "nope/missing")));
    const bsp::Bsp out = compiledOk(run);
    EXPECT_TRUE(run.says("WARNING: Couldn't find image for shader textures/nope/missing")) << run.output;
    bool drawn = false;
    for (const bsp::Surface& s : out.surfaces)
        drawn = drawn || std::string(out.shaders[size_t(s.shaderNum)].name) == "textures/nope/missing";
    EXPECT_TRUE(drawn);
}

std::string miscModel(const std::string& path) {
    return "{\n\"classname\" \"misc_model\"\n\"model\" \"" + path + "\"\n\"origin\" \"200 200 64\"\n}\n";
}

// The plain room's surface count (the model cases must add nothing to it).
size_t plainRoomSurfaces() {
    static const size_t count = compiledOk(compile(roomWith(""))).surfaces.size();
    return count;
}

// q3map2 prints Assimp's error ("ERROR: Unable to open file ...") and goes on without the model;
// this build names the entity and the file in a warning.
TEST(BspBadInput, AMissingModelFileIsAWarning) {
    const Compiled run = compile(roomWith("", miscModel("models/none/missing.md3")));
    const bsp::Bsp out = compiledOk(run);
    const std::vector<std::string> warnings = run.lines("WARNING: Entity 2 (misc_model)");
    ASSERT_EQ(warnings.size(), 1u) << run.output;
    EXPECT_NE(warnings[0].find("models/none/missing.md3"), std::string::npos) << warnings[0];
    EXPECT_EQ(out.surfaces.size(), plainRoomSurfaces());
}

// q3map2 prints Assimp's error for each ("Invalid MD3 header ...", "OBJ: Invalid face index.", a
// truncated ASE) and goes on; this build warns with the entity and the file.
TEST(BspBadInput, BrokenModelFilesAreWarnings) {
    const std::vector<std::pair<std::string, std::string>> models{
        {"models/broken.md3", "IDP3\x0f" + std::string(3, '\0') + std::string(200, '\xff')},
        {"models/short.md3", "IDP3"},
        {"models/empty.md3", ""},
        {"models/broken.obj", "v 1 2\nf 1 2 3 99\nf a b c\n"},
        {"models/broken.ase", "*3DSMAX_ASCIIEXPORT 200\n*GEOMOBJECT {\n*MESH {\n*MESH_NUMVERTEX 3\n*MESH_VERTEX_LIST {\n"
                              "*MESH_VERTEX 0 1 2\n"},
        {"models/noise.lwo", std::string("FORM\x7f\xff\xff\xffLWO2", 12) + std::string(64, '\x11')},
    };
    for (const auto& model : models) {
        const Compiled run = compile(roomWith("", miscModel(model.first)), {model});
        const bsp::Bsp out = compiledOk(run);
        const std::vector<std::string> warnings = run.lines("WARNING: Entity 2 (misc_model)");
        ASSERT_EQ(warnings.size(), 1u) << model.first << "\n" << run.output;
        EXPECT_NE(warnings[0].find(model.first), std::string::npos) << warnings[0];
        EXPECT_EQ(out.surfaces.size(), plainRoomSurfaces()) << model.first;
    }
}

// q3map2 crashes on an empty .map (signal 11) and writes an empty BSP without a worldspawn or when
// the first entity has no brushes; this build stops with one error line naming the file.
TEST(BspBadInput, NoWorldspawnIsAnError) {
    failsCleanly(compile(""), "no entities");
    failsCleanly(compile("// only a comment\n"), "no entities");
    failsCleanly(compile(kPlayer), "the world has no brushes");
    failsCleanly(compile(kPlayer + test::worldspawn(kRoom)), "the world has no brushes");
}

// Text that is not a .map: the parser's error names the file and the line.
TEST(BspBadInput, BrokenMapTextIsAnError) {
    failsCleanly(compile(test::worldspawn(kRoom).substr(0, 300)), "bad.map:");
    failsCleanly(compile("{\n\"classname\" \"worldspawn\"\n{\n( 0 0 0 ) ( 1 0 0 )\n}\n}\n"), "bad.map:");
    failsCleanly(compile(std::string("\x89PNG\r\n\x1a\n", 8) + std::string(100, '\0')), "bad.map:");
}

// A limit reached inside the compile steps: the error names the map too.
TEST(BspBadInput, TooManyDrawSurfacesIsAnErrorNamingTheMap) {
    const fs::path base = q3::test::tempDir();
    fs::create_directories(base / "baseoa" / "maps");
    const fs::path map = base / "baseoa" / "maps" / "bad.map";
    writeFileAtomic(map, roomWith(""));
    Compiled run;
    run.bsp = base / "baseoa" / "maps" / "bad.bsp";
    run.status = q3::test::runCommand(q3::test::q3map2Exe().string() + " -maxmapdrawsurfs 3 -fs_basepath " +
                                          q3::test::shellQuote(base) + " -bsp " + q3::test::shellQuote(map),
                                      &run.output);
    failsCleanly(run, "max_map_draw_surfs (3) exceeded");
}

TEST(BspBadInput, AMissingMapFileIsAnError) {
    const fs::path base = q3::test::tempDir();
    std::string output;
    const int status = q3::test::runCommand(q3::test::q3map2Exe().string() + " -fs_basepath " + q3::test::shellQuote(base) +
                                            " -bsp " + q3::test::shellQuote(base / "nowhere.map"),
                                        &output);
    EXPECT_EQ(status, 1) << output;
    EXPECT_NE(output.find("ERROR:"), std::string::npos) << output;
    EXPECT_NE(output.find("nowhere.map"), std::string::npos) << output;
}

// A func_group of one q3map_terrain brush with the index map keys given, its shader script and a
// 2x2 index map at maps/idx.tga.
Compiled compileTerrain(const std::string& keys) {
    const std::string group = "{\n\"classname\" \"func_group\"\n" + keys +
                              test::boxBrush({64, 64, 0}, {192, 192, 32}, "test/terrain") + "}\n";
    std::string tga(18, '\0');
    tga[2] = 2;    // uncompressed true colour
    tga[12] = 2;   // 2x2 pixels
    tga[14] = 2;
    tga[16] = 24;  // bits per pixel
    tga += std::string(12, '\x80');
    return compile(roomWith("", group), {{"scripts/terrain.shader", "textures/test/terrain\n{\n\tq3map_terrain\n}\n"},
                                         {"maps/idx.tga", tga}});
}

// The shader lump's names that start with `prefix` (brush sides name their own shaders there too).
std::vector<std::string> shadersStartingWith(const bsp::Bsp& out, const std::string& prefix) {
    std::vector<std::string> found;
    for (const bsp::Shader& s : out.shaders) {
        std::string name(s.name, strnlen(s.name, sizeof s.name));
        if (name.rfind(prefix, 0) == 0) found.push_back(std::move(name));
    }
    return found;
}

// q3map2: "Couldn't read maps/none.tga" and no BSP.
TEST(BspBadInput, AMissingIndexMapIsAnError) {
    failsCleanly(compileTerrain("\"_indexmap\" \"maps/none.tga\"\n\"_layers\" \"2\"\n\"_shader\" \"test/t\"\n"),
                 "index map \"maps/none.tga\" not found");
}

// q3map2 warns ("has < 1 layer", "has missing \"_shader\"") and leaves the entity unlayered; it takes
// any larger count, which the one-byte pixels cannot address: here that is refused the same way.
TEST(BspBadInput, BadIndexMapKeysAreWarningsAndLeaveTheTerrainUnlayered) {
    const struct {
        std::string keys, warning;
    } cases[] = {
        {"\"_layers\" \"0\"\n\"_shader\" \"test/t\"\n", "has 0 layers, not 1 to 256"},
        {"\"_layers\" \"300\"\n\"_shader\" \"test/t\"\n", "has 300 layers, not 1 to 256"},
        {"\"_shader\" \"test/t\"\n", "has no \"_layers\" or \"layers\" key"},
        {"\"layers\" \"2\"\n", "has no \"_shader\" or \"shader\" key"},
    };
    for (const auto& c : cases) {
        const Compiled run = compileTerrain("\"_indexmap\" \"maps/idx.tga\"\n" + c.keys);
        EXPECT_TRUE(run.says("WARNING: Entity 2 (func_group): index map \"maps/idx.tga\" " + c.warning +
                             ", the entity is not layered"))
            << run.output;
        const bsp::Bsp out = compiledOk(run);
        EXPECT_TRUE(shadersStartingWith(out, "textures/test/t_").empty()) << c.keys;
    }
}

// The same keys with a valid count layer the terrain: every pixel is 0x80, layer 1 of 2.
TEST(BspBadInput, ValidIndexMapKeysLayerTheTerrain) {
    const Compiled run = compileTerrain("\"_indexmap\" \"maps/idx.tga\"\n\"layers\" \"2\"\n\"shader\" \"test/t\"\n");
    const bsp::Bsp out = compiledOk(run);
    EXPECT_EQ(shadersStartingWith(out, "textures/test/t_"), std::vector<std::string>{"textures/test/t_1"});
}

}  // namespace
}  // namespace q3::bspstage
