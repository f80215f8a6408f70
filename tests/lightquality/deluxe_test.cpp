// Deluxe maps through the whole stage: interleaved direction pages with even lightmap numbers, the
// worldspawn key engines read, directions pointing at the light (model and tangent space), and
// the encoding helpers.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "deluxe.h"
#include "quality_scene.h"

namespace q3::light {
namespace {

const Vec3 kLight{200, 300, 96};

// A lit floor (surface 0); `addMore` may add surfaces after it.
std::filesystem::path floorScene(const std::string& name, const std::function<void(bsp::Bsp&)>& addMore = {}) {
    bsp::Bsp b = quality::emptyBsp({"textures/test/floor"});
    quality::addQuad(b, {0, 0, 0}, {0, 512, 0}, {512, 0, 0}, 0);  // normal +z, s along +y, t along +x
    if (addMore) addMore(b);
    quality::finish(b, {});
    std::vector<bsp::Entity> ents = bsp::parseEntities(b.entities, name);
    bsp::Entity light;
    light.pairs = {{"classname", "light"}, {"origin", "200 300 96"}, {"light", "400"}};
    ents.push_back(light);
    b.entities = bsp::unparseEntities(ents);
    return quality::writeScene(b, name);
}

// Decoded texel of the page after the surface's light page.
Vec3 directionAt(const bsp::Bsp& b, int s, int x, int y) {
    const bsp::Surface& surface = b.surfaces[size_t(s)];
    const size_t page = size_t(surface.lightmapNum + 1) * 128 * 128 * 3;
    const size_t at = page + (size_t(surface.lightmapY + y) * 128 + size_t(surface.lightmapX + x)) * 3;
    EXPECT_LT(at + 2, b.lightmaps.size());
    if (at + 2 >= b.lightmaps.size()) return {};
    return Vec3{float(b.lightmaps[at]), float(b.lightmaps[at + 1]), float(b.lightmaps[at + 2])} / 127.5f - Vec3{1, 1, 1};
}

float angleDegrees(Vec3 a, Vec3 b) {
    return float(180.0 / M_PI) * (std::acos(std::clamp(dot(normalize(a), normalize(b)), -1.0f, 1.0f)));
}

TEST(DeluxeStage, InterleavedPagesPointAtTheLight) {
    const auto path = floorScene("deluxe0");
    ASSERT_EQ(quality::runLight(path, {"-deluxe"}), 0);
    const bsp::Bsp b = bsp::readBsp(path);
    EXPECT_EQ(b.lightmaps.size(), 2u * 128 * 128 * 3);
    EXPECT_EQ(b.surfaces[0].lightmapNum % 2, 0);
    const std::vector<bsp::Entity> ents = bsp::parseEntities(b.entities, "deluxe0");
    EXPECT_EQ(ents[0].value("deluxeMaps"), "1");
    int checked = 0;
    for (Vec3 where : {Vec3{200, 300, 0}, Vec3{64, 64, 0}, Vec3{448, 480, 0}, Vec3{400, 100, 0}}) {
        const auto l = quality::luxelNear(b, 0, where);
        const Vec3 dir = directionAt(b, 0, l[0], l[1]);
        EXPECT_LT(angleDegrees(dir, kLight - where), 6.0f) << where.x << " " << where.y;
        ++checked;
    }
    EXPECT_EQ(checked, 4);
}

TEST(DeluxeStage, LightPagesMatchTheRunWithoutDeluxe) {
    // Each scene gets a fresh folder: read every result before the next scene is written.
    const auto plainPath = floorScene("deluxeoff");
    ASSERT_EQ(quality::runLight(plainPath, {}), 0);
    const bsp::Bsp plain = bsp::readBsp(plainPath);
    const auto deluxePath = floorScene("deluxeon");
    ASSERT_EQ(quality::runLight(deluxePath, {"-deluxe"}), 0);
    const bsp::Bsp deluxe = bsp::readBsp(deluxePath);
    ASSERT_EQ(deluxe.lightmaps.size(), 2 * plain.lightmaps.size());
    EXPECT_TRUE(std::equal(plain.lightmaps.begin(), plain.lightmaps.end(), deluxe.lightmaps.begin()));
    const auto noDeluxe = floorScene("nodeluxe");
    ASSERT_EQ(quality::runLight(noDeluxe, {"-deluxe", "-nodeluxe"}), 0);
    EXPECT_EQ(bsp::readBsp(noDeluxe).lightmaps.size(), 128u * 128 * 3);
}

// q3map2 merges no twins with deluxe maps but still stores a lightmap of at most 2 x 2 luxels as
// one texel; that texel's direction is its first luxel's.
TEST(DeluxeStage, SmallLightmapsAreOneTexelWithTheirDirection) {
    const Vec3 smallCorner{600, 0, 0};
    const auto path = floorScene("deluxesolid", [&](bsp::Bsp& b) {
        quality::addQuad(b, smallCorner, {0, 8, 0}, {8, 0, 0}, 0);  // at most 2 x 2 luxels at the default sample size
    });
    ASSERT_EQ(quality::runLight(path, {"-deluxe"}), 0);
    const bsp::Bsp lit = bsp::readBsp(path);
    const bsp::Surface& small = lit.surfaces[1];
    ASSERT_GE(small.lightmapNum, 0);
    EXPECT_EQ(small.lightmapNum % 2, 0);
    // Every vertex samples the centre of one texel.
    const bsp::DrawVert& first = lit.drawVerts[size_t(small.firstVert)];
    for (int v = 0; v < small.numVerts; ++v) {
        const bsp::DrawVert& dv = lit.drawVerts[size_t(small.firstVert + v)];
        EXPECT_EQ(dv.lightmap[0], first.lightmap[0]);
        EXPECT_EQ(dv.lightmap[1], first.lightmap[1]);
    }
    // That texel is the surface's placement.
    EXPECT_EQ(int(first.lightmap[0] * 128), small.lightmapX);
    EXPECT_EQ(int(first.lightmap[1] * 128), small.lightmapY);
    EXPECT_LT(angleDegrees(directionAt(lit, 1, 0, 0), kLight - (smallCorner + Vec3{4, 4, 0})), 6.0f);
}

TEST(DeluxeStage, TangentSpaceModeUsesTheTextureFrame) {
    const auto path = floorScene("deluxe1");
    ASSERT_EQ(quality::runLight(path, {"-deluxe", "-deluxemode", "1"}), 0);
    const bsp::Bsp b = bsp::readBsp(path);
    EXPECT_EQ(bsp::parseEntities(b.entities, "deluxe1")[0].value("deluxeMaps"), "2");
    for (Vec3 where : {Vec3{64, 64, 0}, Vec3{448, 480, 0}}) {
        const auto l = quality::luxelNear(b, 0, where);
        const Vec3 local = directionAt(b, 0, l[0], l[1]);
        const Vec3 world = normalize(kLight - where);
        // Tangent = +y (texture s), bitangent = +x (texture t), normal = +z.
        EXPECT_LT(angleDegrees(local, {world.y, world.x, world.z}), 6.0f) << where.x;
    }
}

TEST(DeluxeStage, DebugDeluxeShowsDirectionsAsLight) {
    const auto path = floorScene("debugdeluxe");
    ASSERT_EQ(quality::runLight(path, {"-deluxe", "-debugdeluxe"}), 0);
    const bsp::Bsp b = bsp::readBsp(path);
    const auto l = quality::luxelNear(b, 0, {64, 64, 0});
    const auto light = quality::texel(b, 0, l[0], l[1]);
    const Vec3 dir = directionAt(b, 0, l[0], l[1]);
    EXPECT_NEAR((light[2] / 127.5f) - 1, dir.z, 0.01f);
}

TEST(Deluxe, EncodingAndTangentSpace) {
    const Rgb8 up = encodeDirection({0, 0, 5}, {1, 0, 0});
    EXPECT_EQ(up, (Rgb8{127, 127, 255}));
    EXPECT_EQ(encodeDirection({}, {1, 0, 0}), (Rgb8{255, 127, 127}));  // no light: the fallback
    const TangentFrame frame{{0, 1, 0}, {1, 0, 0}};
    const Vec3 t = toTangentSpace(normalize(Vec3{1, 2, 3}), {0, 0, 1}, frame);
    const Vec3 expected = normalize(Vec3{2, 1, 3});
    EXPECT_NEAR(t.x, expected.x, 1e-5f);
    EXPECT_NEAR(t.y, expected.y, 1e-5f);
    EXPECT_NEAR(t.z, expected.z, 1e-5f);
}

}  // namespace
}  // namespace q3::light
