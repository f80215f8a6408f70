// Radiosity through the whole stage: a floor lit by a downward spotlight bounces light of its own
// colour onto a ceiling no light reaches, by the amount the floor's light and the form factor
// predict; -bouncegrid adds the bounce to the legacy and SH grids; -bounceonly, -bouncescale,
// -dump and the between-bounce store.
#include <gtest/gtest.h>

#include <cmath>

#include "file_io.h"
#include "image.h"
#include "light_styles.h"
#include "lightmap_pack.h"
#include "light_contribution.h"
#include "quality_scene.h"
#include "sh.h"
#include "sh_grid_lump.h"

namespace q3::light {
namespace {

constexpr float kRoom = 512, kHeight = 256;

// 4 x 4 TGA of one colour (uncompressed, 24-bit).
std::vector<uint8_t> solidTga(uint8_t r, uint8_t g, uint8_t b) {
    std::vector<uint8_t> out(18, 0);
    out[2] = 2;
    out[12] = 4;
    out[14] = 4;
    out[16] = 24;
    for (int i = 0; i < 16; ++i) out.insert(out.end(), {b, g, r});
    return out;
}

// Floor (textured 200/100/50) at z = 0 facing up, ceiling at z = 256 facing down, a spotlight under
// the ceiling pointing at the floor: the ceiling is behind the spot and gets no direct light.
std::filesystem::path roomScene(const std::string& name, const std::string& spotStyle = "",
                                const std::string& spotLight = "900", const std::string& floorDirectives = "") {
    bsp::Bsp b = quality::emptyBsp({"textures/test/floor", "textures/test/ceiling"});
    quality::addQuad(b, {0, 0, 0}, {0, kRoom, 0}, {kRoom, 0, 0}, 0);           // normal +z
    quality::addQuad(b, {0, 0, kHeight}, {kRoom, 0, 0}, {0, kRoom, 0}, 1);     // normal -z
    quality::finish(b, {});
    std::vector<bsp::Entity> ents = bsp::parseEntities(b.entities, name);
    bsp::Entity spot;
    spot.pairs = {{"classname", "light"}, {"origin", "256 256 240"}, {"light", spotLight}, {"target", "down"},
                  {"radius", "600"}};
    if (!spotStyle.empty()) spot.pairs.push_back({"_style", spotStyle});
    bsp::Entity target;
    target.pairs = {{"classname", "info_null"}, {"origin", "256 256 0"}, {"targetname", "down"}};
    ents.push_back(spot);
    ents.push_back(target);
    b.entities = bsp::unparseEntities(ents);
    const auto path = quality::writeScene(b, name,
                                          "textures/test/floor\n{\n\tqer_editorimage textures/test/floor.tga\n" +
                                              floorDirectives + "}\n");
    std::filesystem::create_directories(path.parent_path().parent_path() / "textures" / "test");
    writeFileAtomic(path.parent_path().parent_path() / "textures" / "test" / "floor.tga", solidTga(200, 100, 50));
    return path;
}

Vec3 texelColor(const bsp::Bsp& b, int surface, int x, int y) {
    const auto t = quality::texel(b, surface, x, y);
    return {float(t[0]), float(t[1]), float(t[2])};
}

// What the ceiling luxel at `p` should receive: the floor's stored light times its albedo, re-emitted
// with q3map2's radiosity value (500 * 0.375 * 3 * bounceScale / 255^2 per unit of albedo * light),
// integrated over the floor with the differential form factor cos * cos / (pi r^2).
Vec3 expectedBounce(const bsp::Bsp& lit, Vec3 p, float bounceScale) {
    const Vec3 albedo{200 / 255.0f, 100 / 255.0f, 50 / 255.0f};
    const float add = 500 * 0.375f * 3 * bounceScale;
    const bsp::Surface& floor = lit.surfaces[0];
    const float luxelW = kRoom / float(floor.lightmapWidth - 1), luxelH = kRoom / float(floor.lightmapHeight - 1);
    Vec3 sum;
    for (int y = 0; y < floor.lightmapHeight; ++y)
        for (int x = 0; x < floor.lightmapWidth; ++x) {
            const Vec3 at = {std::min(kRoom, x * luxelW), std::min(kRoom, y * luxelH), 0};
            const Vec3 d = at - p;
            const float r2 = dot(d, d);
            const float cosCeiling = dot(normalize(d), Vec3{0, 0, -1}), cosFloor = dot(normalize(-d), Vec3{0, 0, 1});
            const float area = luxelW * luxelH * (x == 0 || x == floor.lightmapWidth - 1 ? 0.5f : 1.0f) *
                               (y == 0 || y == floor.lightmapHeight - 1 ? 0.5f : 1.0f);
            const float ff = cosCeiling * cosFloor * area / (float(M_PI) * r2);
            const Vec3 light = texelColor(lit, 0, x, y) / 255.0f;
            sum += Vec3{albedo.x * light.x, albedo.y * light.y, albedo.z * light.z} * (add * ff);
        }
    return sum;
}

struct RoomRun {
    bsp::Bsp bsp;
    Vec3 ceilingCentre;
};

RoomRun lightRoom(const std::string& name, const std::vector<std::string>& args,
                  const std::string& spotLight = "900", const std::string& floorDirectives = "") {
    const auto path = roomScene(name, "", spotLight, floorDirectives);
    EXPECT_EQ(quality::runLight(path, args), 0);
    RoomRun run{bsp::readBsp(path), {}};
    const auto c = quality::luxelNear(run.bsp, 1, {256, 256, kHeight});
    run.ceilingCentre = texelColor(run.bsp, 1, c[0], c[1]);
    return run;
}

TEST(RadiosityStage, CeilingIsDarkWithoutBounce) {
    const RoomRun direct = lightRoom("nobounce", {});
    EXPECT_EQ(direct.ceilingCentre, (Vec3{0, 0, 0}));
    const auto f = quality::luxelNear(direct.bsp, 0, {256, 256, 0});
    EXPECT_GT(texelColor(direct.bsp, 0, f[0], f[1]).x, 100);  // the floor is lit
}

TEST(RadiosityStage, FloorBouncesItsColourOntoCeilingByFormFactor) {
    const RoomRun bounced = lightRoom("bounce1", {"-bounce", "1"});
    const Vec3 expected = expectedBounce(bounced.bsp, {256, 256, kHeight - 1}, 0.25f);
    const Vec3 got = bounced.ceilingCentre;
    ASSERT_GT(expected.x, 5);
    // Emitters are the floor chopped into pieces with one averaged colour each: 25 % covers that
    // averaging and byte rounding.
    EXPECT_NEAR(got.x, expected.x, 0.25f * expected.x + 1);
    EXPECT_NEAR(got.y, expected.y, 0.25f * expected.y + 1);
    // The floor's colour: red twice green, green twice blue (within rounding of small values).
    EXPECT_NEAR(got.x / std::max(1.0f, got.y), 2.0f, 0.3f);
    EXPECT_GT(got.y, got.z);
}

// -fast cuts a contribution whose form factor times the emitter's add is at or below the falloff
// tolerance; q3map2 leaves the emitter's colour (the reflected light, well below 1) out of that
// test. A dim floor chopped into 16-unit pieces: each piece gives the ceiling well under one unit
// (add * factor * colour < 1, which a cut on the coloured value would drop, leaving it black) while
// add * factor passes over most of the floor, so the fast run keeps nearly the exact run's light.
TEST(RadiosityStage, FastBounceCutsOnTheFormFactorNotTheColour) {
    const std::vector<std::string> common = {"-bounce", "1", "-bouncescale", "32"};
    std::vector<std::string> fastArgs = common;
    fastArgs.push_back("-fast");
    const std::string smallPieces = "\tq3map_lightSubdivide 16\n";
    const RoomRun exact = lightRoom("fastcut0", common, "100", smallPieces);
    const RoomRun fast = lightRoom("fastcut1", fastArgs, "100", smallPieces);
    ASSERT_GT(exact.ceilingCentre.x, 40);
    EXPECT_NEAR(fast.ceilingCentre.x, exact.ceilingCentre.x, 0.1f * exact.ceilingCentre.x);
    EXPECT_NEAR(fast.ceilingCentre.y, exact.ceilingCentre.y, 0.1f * exact.ceilingCentre.y + 1);
}

TEST(RadiosityStage, BounceScaleMultipliesAndBounceOnlyDropsDirectLight) {
    const RoomRun single = lightRoom("scale1", {"-bounce", "1"});
    const RoomRun doubled = lightRoom("scale2", {"-bounce", "1", "-bouncescale", "2"});
    EXPECT_NEAR(doubled.ceilingCentre.x, 2 * single.ceilingCentre.x, 0.1f * single.ceilingCentre.x + 2);

    const RoomRun only = lightRoom("only", {"-bounce", "1", "-bounceonly"});
    const auto f = quality::luxelNear(only.bsp, 0, {256, 256, 0});
    // The floor keeps only what the ceiling sent back: far below its direct light.
    EXPECT_LT(texelColor(only.bsp, 0, f[0], f[1]).x, 0.5f * texelColor(single.bsp, 0, f[0], f[1]).x);
    EXPECT_NEAR(only.ceilingCentre.x, single.ceilingCentre.x, 2);
}

TEST(RadiosityStage, SecondBounceAddsToTheFloor) {
    const RoomRun one = lightRoom("two1", {"-bounce", "1", "-nobouncestore"});
    const RoomRun two = lightRoom("two2", {"-bounce", "2", "-nobouncestore"});
    const auto corner = quality::luxelNear(one.bsp, 0, {16, 16, 0});
    EXPECT_GT(texelColor(two.bsp, 0, corner[0], corner[1]).x, texelColor(one.bsp, 0, corner[0], corner[1]).x);
}

TEST(RadiosityStage, DumpWritesEachPassAsMapPrefab) {
    const auto path = roomScene("dump");
    ASSERT_EQ(quality::runLight(path, {"-bounce", "2", "-dump"}), 0);
    auto prefab = path;
    prefab.replace_extension();
    const std::string first = readFileText(prefab.string() + "_bounce_000.map");
    EXPECT_NE(first.find("\"classname\" \"light\""), std::string::npos);
    EXPECT_NE(first.find("\"_color\""), std::string::npos);
    EXPECT_TRUE(std::filesystem::exists(prefab.string() + "_bounce_001.map"));
}

// q3map2 bounced styled light into style 0 (lighting surfaces that must stay dark while the light
// is off); here the emitters made from a style's light keep that style.
TEST(RadiosityStage, StyledLightBouncesOnlyIntoItsStyle) {
    const auto path = roomScene("styledbounce", "1");
    ASSERT_EQ(quality::runLight(path, {"-bounce", "1"}), 0);
    const bsp::Bsp lit = bsp::readBsp(path);
    const auto c = quality::luxelNear(lit, 1, {256, 256, kHeight});
    EXPECT_EQ(texelColor(lit, 1, c[0], c[1]), (Vec3{0, 0, 0}));  // style 0 of the ceiling stays dark
    const auto f = quality::luxelNear(lit, 0, {256, 256, 0});
    EXPECT_EQ(texelColor(lit, 0, f[0], f[1]), (Vec3{0, 0, 0}));  // and of the floor

    // The styled page holds the ceiling's bounce at the ceiling's texels.
    const auto page = externalLightmapDir(path, "") / externalLightmapName(0);
    ASSERT_TRUE(std::filesystem::exists(page));
    const Image picture = decodeTga(readFileBytes(page), page.string());
    const bsp::Surface& ceiling = lit.surfaces[1];
    const int x = std::min(ceiling.lightmapX + c[0], picture.width - 1);
    const int y = std::min(ceiling.lightmapY + c[1], picture.height - 1);
    const uint8_t* texel = &picture.rgba[(size_t(y) * size_t(picture.width) + size_t(x)) * 4];
    EXPECT_GT(int(texel[0]), 5);
    EXPECT_GT(int(texel[0]), int(texel[2]));  // the floor's colour
}

// A vertex-lit tile on the floor, one corner (400, 200) in the shadow a 4-unit blocker at z = 8 casts
// from the spotlight, so the direct pass lights that vertex from a nudged point; a wall at x = 512,
// lit by the spot, bounces light onto the tile. q3map2 relights vertexes pass by pass, each pass
// searching for its own lit point: the bounce, which reaches the corner where it stands, must not
// end the search the direct pass needs. Every vertex keeps at least its direct light.
TEST(RadiosityStage, BounceOnlyAddsToVertexLight) {
    bsp::Bsp b = quality::emptyBsp({"textures/test/floor", "textures/test/wall", "textures/test/vertex"});
    quality::addQuad(b, {0, 0, 0}, {0, kRoom, 0}, {kRoom, 0, 0}, 0);         // floor, normal +z
    quality::addQuad(b, {kRoom, 0, 0}, {0, kRoom, 0}, {0, 0, kHeight}, 1);   // wall, normal -x
    quality::addQuad(b, {393.5f, 199.75f, 8}, {4, 0, 0}, {0, 4, 0}, 1);     // blocker, normal -z
    quality::addQuad(b, {400, 200, 0.5f}, {0, 16, 0}, {16, 0, 0}, 2);        // tile, normal +z
    b.surfaces.back().lightmapNum = bsp::kLightmapByVertex;
    const size_t tile = b.surfaces.size() - 1;
    quality::finish(b, {});
    std::vector<bsp::Entity> ents = bsp::parseEntities(b.entities, "vertexbounce");
    bsp::Entity spot, target;
    spot.pairs = {{"classname", "light"}, {"origin", "256 256 240"}, {"light", "900"}, {"target", "down"},
                  {"radius", "600"}};
    target.pairs = {{"classname", "info_null"}, {"origin", "256 256 0"}, {"targetname", "down"}};
    ents.push_back(spot);
    ents.push_back(target);
    b.entities = bsp::unparseEntities(ents);
    const auto path =
        quality::writeScene(b, "vertexbounce", "textures/test/vertex\n{\n\tsurfaceparm nolightmap\n}\n");
    ASSERT_EQ(quality::runLight(path, {}), 0);
    const bsp::Bsp direct = bsp::readBsp(path);
    writeFileAtomic(path, bsp::serializeBsp(b));
    ASSERT_EQ(quality::runLight(path, {"-bounce", "1"}), 0);
    const bsp::Bsp bounced = bsp::readBsp(path);
    const bsp::Surface& s = bounced.surfaces[tile];
    ASSERT_LT(s.lightmapNum, 0);
    for (int v = 0; v < s.numVerts; ++v) {
        const size_t i = static_cast<size_t>(s.firstVert + v);
        EXPECT_GT(direct.drawVerts[i].color[0], 50) << "vertex " << v;
        for (int c = 0; c < 3; ++c)
            EXPECT_GE(bounced.drawVerts[i].color[c], direct.drawVerts[i].color[c]) << "vertex " << v;
    }
}

// Sum of the legacy grid bytes, and the SH irradiance towards +z (what faces the ceiling).
struct GridTotals {
    long legacy = 0;
    double shUp = 0;
};

GridTotals gridTotals(const bsp::Bsp& b) {
    GridTotals t;
    for (const bsp::GridPoint& p : b.lightGrid)
        for (int c = 0; c < 3; ++c) t.legacy += p.ambient[c] + p.directed[c];
    sh::GridSH grid;
    std::string error;
    EXPECT_TRUE(sh::decodeGridLump(b.shGrid.data(), b.shGrid.size(), grid, error)) << error;
    for (const sh::GridPointSH& p : grid.points) {
        sh::SH9Color c;
        for (int i = 0; i < 9; ++i)
            for (int k = 0; k < 3; ++k) c.c[i][k] = p.coeffs[i][k];
        t.shUp += sh::evalIrradianceClamped(c, {0, 0, -1}).r;  // facing down: sees the floor
    }
    return t;
}

TEST(RadiosityStage, BounceGridRaisesBothGridsOnlyWhenAsked) {
    const RoomRun plain = lightRoom("grid0", {"-bounce", "1", "-sh"});
    const RoomRun grid = lightRoom("grid1", {"-bounce", "1", "-sh", "-bouncegrid"});
    const GridTotals without = gridTotals(plain.bsp), with = gridTotals(grid.bsp);
    const RoomRun none = lightRoom("grid2", {"-sh"});
    const GridTotals direct = gridTotals(none.bsp);
    EXPECT_EQ(without.legacy, direct.legacy);  // bounce without -bouncegrid leaves the grids alone
    EXPECT_DOUBLE_EQ(without.shUp, direct.shUp);
    EXPECT_GT(with.legacy, direct.legacy + 100);
    EXPECT_GT(with.shUp, direct.shUp * 1.05);
}

}  // namespace
}  // namespace q3::light
