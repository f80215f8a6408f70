// Floodlight: the per-sample fraction against a hand computation under a ceiling, sky and open space
// counting fully, the worldspawn key and shader directive, and the stage raising an unlit floor by
// exactly intensity x colour.
#include <gtest/gtest.h>

#include <cmath>

#include "color_pipeline.h"
#include "floodlight.h"
#include "log.h"
#include "../light/light_test_util.h"
#include "quality_scene.h"
#include "shader_info.h"

namespace q3::light {
namespace {

// A floor and a wide ceiling 64 units above the sample (z = 65 for a sample at z = 1).
std::vector<SceneSurface> ceilingScene(const LightingShader* ceilingShader = nullptr) {
    return {test::quad({-2048, -2048, 0}, {4096, 0, 0}, {0, 4096, 0}),
            test::quad({-2048, -2048, 65}, {0, 4096, 0}, {4096, 0, 0}, ceilingShader)};
}

// Mean over q3map2's 64 floodlight rays (16 azimuths x 4 elevations in 88 degrees), or every
// `stride`-th of them, of min(1, t / distance) for a ceiling `height` above the sample.
float expectedUnderCeiling(float height, float distance, int stride = 1) {
    double sum = 0;
    int n = 0;
    for (int k = 0; k < 64; k += stride) {
        const int j = k % 4;
        const double elevation = (j + 0.5) * 22.0 * M_PI / 180;
        sum += std::min(1.0, height / std::cos(elevation) / distance);
        ++n;
    }
    return static_cast<float>(sum / n);
}

TEST(Floodlight, OpenSampleSeesEverything) {
    HitScene scene({test::quad({-512, -512, 0}, {1024, 0, 0}, {0, 1024, 0})}, {});
    EXPECT_EQ(floodlightForSample({0, 0, 1}, {0, 0, 1}, scene, FloodlightSettings{}), 1.0f);
}

TEST(Floodlight, CeilingMatchesFormula) {
    HitScene scene(ceilingScene(), {});
    FloodlightSettings s;
    const float f = floodlightForSample({0, 0, 1}, {0, 0, 1}, scene, s);
    EXPECT_NEAR(f, expectedUnderCeiling(64, 1024), 1e-4f);
    EXPECT_LT(f, 0.2f);
    s.distance = 100;  // most rays now end before the ceiling
    EXPECT_NEAR(floodlightForSample({0, 0, 1}, {0, 0, 1}, scene, s), expectedUnderCeiling(64, 100), 1e-4f);
    s.distance = 1024;
    s.lowQuality = true;
    EXPECT_NEAR(floodlightForSample({0, 0, 1}, {0, 0, 1}, scene, s), expectedUnderCeiling(64, 1024, 10), 1e-4f);
}

TEST(Floodlight, SkyCountsAsOpen) {
    LightingShader sky;
    sky.sky = true;
    HitScene scene(ceilingScene(&sky), {});
    EXPECT_EQ(floodlightForSample({0, 0, 1}, {0, 0, 1}, scene, FloodlightSettings{}), 1.0f);
}

TEST(Floodlight, WorldspawnKeyAndOption) {
    bsp::Entity world;
    world.pairs = {{"classname", "worldspawn"}};
    EXPECT_FALSE(globalFloodlight(false, false, world, "maps/x.bsp"));
    auto byOption = globalFloodlight(true, true, world, "maps/x.bsp");
    ASSERT_TRUE(byOption);
    EXPECT_NEAR(byOption->color.x, 0.94f, 1e-6f);
    EXPECT_EQ(byOption->color.z, 1.0f);
    EXPECT_EQ(byOption->distance, 1024.0f);
    EXPECT_EQ(byOption->intensity, 128.0f);
    EXPECT_TRUE(byOption->lowQuality);

    world.pairs.push_back({"_floodlight", "2 1 0 512 64 0.5"});
    auto byKey = globalFloodlight(false, false, world, "maps/x.bsp");
    ASSERT_TRUE(byKey);
    EXPECT_EQ(byKey->color, (Vec3{1, 0.5f, 0}));
    EXPECT_EQ(byKey->distance, 512.0f);
    EXPECT_EQ(byKey->intensity, 64.0f);
    EXPECT_EQ(byKey->directionScale, 0.5f);

    world.pairs.back().second = "0 0 0 0 0 -1";
    auto defaults = globalFloodlight(false, false, world, "maps/x.bsp");
    ASSERT_TRUE(defaults);
    EXPECT_EQ(defaults->distance, 1024.0f);
    EXPECT_EQ(defaults->intensity, 128.0f);
    EXPECT_EQ(defaults->directionScale, 1.0f);
    EXPECT_NEAR(defaults->color.y, 0.94f, 1e-6f);

    world.pairs.back().second = "1 1 bright";
    try {
        globalFloodlight(false, false, world, "maps/x.bsp");
        FAIL() << "no error";
    } catch (const CompileError& e) {
        EXPECT_NE(std::string(e.what()).find("maps/x.bsp"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("_floodlight"), std::string::npos) << e.what();
    }
}

TEST(Floodlight, ShaderDirective) {
    EXPECT_FALSE(shaderFloodlight(std::nullopt));
    ShaderFloodLight d;
    d.color = {0, 0.5f, 0};
    d.distance = 300;
    d.intensity = 0;
    EXPECT_FALSE(shaderFloodlight(d));
    d.intensity = 40;
    auto s = shaderFloodlight(d);
    ASSERT_TRUE(s);
    EXPECT_EQ(s->color, (Vec3{0, 1, 0}));
    EXPECT_EQ(s->distance, 300.0f);
    EXPECT_EQ(s->intensity, 40.0f);
    EXPECT_FALSE(s->lowQuality);
}

// An unlit open floor (no lights, no ambient).
bsp::Bsp floorBsp(const std::string& shader, std::vector<std::pair<std::string, std::string>> world = {}) {
    bsp::Bsp b = quality::emptyBsp({shader});
    quality::addQuad(b, {0, 0, 0}, {0, 512, 0}, {512, 0, 0}, 0);
    quality::finish(b, std::move(world));
    return b;
}

std::array<int, 3> bytesOf(Vec3 c) {
    const Rgb8 r = colorToBytes(c, 1, ColorOptions{});
    return {r[0], r[1], r[2]};
}

TEST(FloodlightStage, RaisesUnlitFloorByIntensityTimesColour) {
    const bsp::Bsp b = floorBsp("textures/test/floor");
    const auto middle = quality::luxelNear(b, 0, {256, 256, 0});
    const auto path = quality::writeScene(b, "flood");
    ASSERT_EQ(quality::runLight(path, {}), 0);
    EXPECT_EQ(quality::texel(bsp::readBsp(path), 0, middle[0], middle[1]), (std::array<int, 3>{0, 0, 0}));

    writeFileAtomic(path, bsp::serializeBsp(b));
    ASSERT_EQ(quality::runLight(path, {"-floodlight"}), 0);
    const auto lit = quality::texel(bsp::readBsp(path), 0, middle[0], middle[1]);
    EXPECT_EQ(lit, bytesOf(Vec3{0.94f, 0.94f, 1.0f} * 128.0f));
    EXPECT_EQ(lit[2], 128);
}

TEST(FloodlightStage, WorldspawnKeyAndShaderDirective) {
    const bsp::Bsp keyed = floorBsp("textures/test/floor", {{"_floodlight", "1 0 0 1024 64"}});
    const auto middle = quality::luxelNear(keyed, 0, {256, 256, 0});
    auto path = quality::writeScene(keyed, "keyed");
    ASSERT_EQ(quality::runLight(path, {}), 0);
    EXPECT_EQ(quality::texel(bsp::readBsp(path), 0, middle[0], middle[1]), bytesOf({64, 0, 0}));

    const bsp::Bsp shaded = floorBsp("textures/test/glow");
    path = quality::writeScene(shaded, "shaded", "textures/test/glow\n{\n\tq3map_floodLight 0 1 0 1024 50 1\n}\n");
    ASSERT_EQ(quality::runLight(path, {}), 0);
    EXPECT_EQ(quality::texel(bsp::readBsp(path), 0, middle[0], middle[1]), bytesOf({0, 50, 0}));

    // Both: the global floodlight and the shader's add up.
    writeFileAtomic(path, bsp::serializeBsp(shaded));
    ASSERT_EQ(quality::runLight(path, {"-floodlight"}), 0);
    EXPECT_EQ(quality::texel(bsp::readBsp(path), 0, middle[0], middle[1]),
              bytesOf(Vec3{0.94f, 0.94f, 1.0f} * 128.0f + Vec3{0, 50, 0}));
}

}  // namespace
}  // namespace q3::light
