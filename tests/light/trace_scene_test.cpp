// The Embree shadow scene: opaque walls, sky masking, alpha shadows and light filters.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <limits>
#include <span>

#include <algorithm>

#include "light_test_util.h"
#include "trace_scene.h"

namespace q3::light {
namespace {

using test::quad;

LightImage solidImage(uint8_t r, uint8_t g, uint8_t b, uint8_t a) {
    LightImage img;
    img.width = 1;
    img.height = 1;
    img.rgba = {r, g, b, a};
    return img;
}

// A 2x1 image: left half transparent, right half opaque.
LightImage halfImage() {
    LightImage img;
    img.width = 2;
    img.height = 1;
    img.rgba = {255, 255, 255, 0, 255, 255, 255, 255};
    return img;
}

TEST(TraceScene, WallBlocksAndOpenSpaceDoesNot) {
    std::vector<SceneSurface> s{quad({-64, 50, -64}, {128, 0, 0}, {0, 0, 128})};  // plane y = 50
    TraceScene scene(s, {});
    EXPECT_EQ(scene.transmission({0, 0, 0}, {0, 100, 0}), (Vec3{0, 0, 0}));
    EXPECT_EQ(scene.transmission({0, 0, 0}, {0, 40, 0}), (Vec3{1, 1, 1}));
    EXPECT_EQ(scene.transmission({200, 0, 0}, {200, 100, 0}), (Vec3{1, 1, 1}));  // beside the wall
    // The wall is closer than ignoreNear: ignored.
    EXPECT_EQ(scene.transmission({0, 49, 0}, {0, 100, 0}, 1.5f), (Vec3{1, 1, 1}));
    EXPECT_GE(scene.raysTraced(), 4u);
}

TEST(TraceScene, NonCastingSurfaces) {
    LightingShader trans, nodraw, filter;
    trans.translucent = true;
    nodraw.nodraw = true;
    filter.translucent = true;
    filter.alphaShadow = true;
    SceneSurface patch = quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
    patch.isPatch = true;
    EXPECT_FALSE(TraceScene::castsShadow(quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, &trans), {}));
    EXPECT_FALSE(TraceScene::castsShadow(quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, &nodraw), {}));
    EXPECT_TRUE(TraceScene::castsShadow(quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, &filter), {}));
    EXPECT_FALSE(TraceScene::castsShadow(patch, {}));
    SceneSurface quiet = quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
    quiet.castShadows = 0;
    EXPECT_FALSE(TraceScene::castsShadow(quiet, {}));
    TraceSceneOptions patchShadows;
    patchShadows.patchShadows = true;
    EXPECT_TRUE(TraceScene::castsShadow(patch, patchShadows));

    std::vector<SceneSurface> s{quad({-64, 50, -64}, {128, 0, 0}, {0, 0, 128}, &trans)};
    TraceScene scene(s, {});
    EXPECT_EQ(scene.casterCount(), 0u);
    EXPECT_EQ(scene.transmission({0, 0, 0}, {0, 100, 0}), (Vec3{1, 1, 1}));
}

// q3map2's shadow groups: which casters block a receiver of each _receiveShadows value.
TEST(TraceScene, ShadowGroupsPickTheCasters) {
    SceneSurface world = quad({-64, 50, -64}, {128, 0, 0}, {0, 0, 128});     // plane y = 50, group 1
    SceneSurface grouped = quad({-64, 150, -64}, {128, 0, 0}, {0, 0, 128});  // plane y = 150, group 2
    grouped.castShadows = 2;
    TraceScene scene({world, grouped}, {});
    auto blockedBy = [&](int receive, Vec3 from, Vec3 to) {
        return scene.transmission(from, to, 0, scene.receiverMask(receive)) == Vec3{};
    };
    const Vec3 o{0, 0, 0}, pastWorld{0, 100, 0}, pastGroup{0, 200, 0}, betweenWalls{0, 100, 0};
    // Group 1 (the world) receives from world casters only.
    EXPECT_TRUE(blockedBy(1, o, pastWorld));
    EXPECT_FALSE(blockedBy(1, betweenWalls, pastGroup));
    // Group 2 receives from the world and from its own group; group 3 from the world only.
    EXPECT_TRUE(blockedBy(2, o, pastWorld));
    EXPECT_TRUE(blockedBy(2, betweenWalls, pastGroup));
    EXPECT_TRUE(blockedBy(3, o, pastWorld));
    EXPECT_FALSE(blockedBy(3, betweenWalls, pastGroup));
    // Negative groups receive from casters of the same magnitude only.
    EXPECT_TRUE(blockedBy(-2, betweenWalls, pastGroup));
    EXPECT_FALSE(blockedBy(-2, o, pastWorld));
    EXPECT_TRUE(blockedBy(-1, o, pastWorld));
    // Group 0 receives no shadows; the default mask sees every caster.
    EXPECT_EQ(scene.receiverMask(0), 0u);
    EXPECT_EQ(scene.transmission(betweenWalls, pastGroup), (Vec3{0, 0, 0}));
    // Batches carry each ray's mask.
    std::vector<ShadowRay> batch;
    for (int receive : {1, 2, 3, -2}) {
        ShadowRay r = *TraceScene::segmentRay(betweenWalls, pastGroup);
        r.mask = scene.receiverMask(receive);
        batch.push_back(r);
    }
    std::vector<Vec3> out(batch.size());
    scene.traceBatch(batch, out);
    EXPECT_EQ(out, (std::vector<Vec3>{{1, 1, 1}, {0, 0, 0}, {1, 1, 1}, {0, 0, 0}}));
    // Sun rays obey the same groups.
    LightingShader sky;
    sky.sky = true;
    SceneSurface ceiling = quad({-1000, -1000, 500}, {2000, 0, 0}, {0, 2000, 0}, &sky, 0);
    SceneSurface roof = quad({-64, -64, 300}, {128, 0, 0}, {0, 128, 0});
    roof.castShadows = 4;
    TraceScene sunScene({ceiling, roof}, {});
    EXPECT_EQ(sunScene.skyTransmission({0, 0, 0}, {0, 0, 1}, 0, 0, sunScene.receiverMask(1)), (Vec3{1, 1, 1}));
    EXPECT_EQ(sunScene.skyTransmission({0, 0, 0}, {0, 0, 1}, 0, 0, sunScene.receiverMask(4)), (Vec3{0, 0, 0}));
}

TEST(TraceScene, SunOnlyThroughItsOwnSky) {
    LightingShader sky;
    sky.sky = true;
    // A sky ceiling at z = 500 (index 0) and a sky wall at x = 500 (index 1).
    std::vector<SceneSurface> s{quad({-1000, -1000, 500}, {2000, 0, 0}, {0, 2000, 0}, &sky, 0),
                                quad({500, -1000, -1000}, {0, 2000, 0}, {0, 0, 1400}, &sky, 1)};
    TraceScene scene(s, {});
    const Vec3 up{0, 0, 1}, side{1, 0, 0};
    EXPECT_EQ(scene.skyTransmission({0, 0, 0}, up, 0), (Vec3{1, 1, 1}));
    EXPECT_EQ(scene.skyTransmission({0, 0, 0}, up, 1), (Vec3{0, 0, 0}));   // wrong sky
    EXPECT_EQ(scene.skyTransmission({0, 0, 0}, up, -1), (Vec3{1, 1, 1}));  // any sky
    EXPECT_EQ(scene.skyTransmission({0, 0, 0}, side, 1), (Vec3{1, 1, 1}));
    EXPECT_EQ(scene.skyTransmission({0, 0, 0}, side, 0), (Vec3{0, 0, 0}));
    EXPECT_EQ(scene.skyTransmission({0, 0, 0}, Vec3{0, 0, -1}, -1), (Vec3{0, 0, 0}));  // no sky below
    // Sky surfaces block point-light rays like walls.
    EXPECT_EQ(scene.transmission({0, 0, 0}, {0, 0, 600}), (Vec3{0, 0, 0}));
}

// Sky surfaces stop point-light segments of the receivers their shadow group shadows, batched or
// one by one, while sun rays still end at them: with every sky in one group they are also in the
// casters' scene under a bit of their own, with skies in two groups they are asked apart.
TEST(TraceScene, SkyStopsSegmentsOfItsGroupAndLetsSunRaysReachIt) {
    LightingShader sky;
    sky.sky = true;
    for (const int wallGroup : {4, 1}) {
        SceneSurface ceiling = quad({-1000, -1000, 500}, {2000, 0, 0}, {0, 2000, 0}, &sky, 0);
        ceiling.castShadows = 4;
        SceneSurface wall = quad({500, -1000, -1000}, {0, 2000, 0}, {0, 0, 1400}, &sky, 0);
        wall.castShadows = wallGroup;
        SceneSurface other = quad({-1000, 700, -1000}, {2000, 0, 0}, {0, 0, 2000});
        other.castShadows = 2;
        TraceScene scene({ceiling, wall, other}, {});
        const Vec3 from{0, 0, 0}, above{0, 0, 600}, beside{600, 0, 0};
        for (const int receive : {1, 4, 2}) {
            const uint32_t mask = scene.receiverMask(receive);
            const Vec3 upExpected = receive == 4 ? Vec3{} : Vec3{1, 1, 1};
            const Vec3 sideExpected = receive == 4 || wallGroup == 1 ? Vec3{} : Vec3{1, 1, 1};
            EXPECT_EQ(scene.transmission(from, above, 0, mask), upExpected) << receive << " " << wallGroup;
            EXPECT_EQ(scene.transmission(from, beside, 0, mask), sideExpected) << receive << " " << wallGroup;
            std::vector<ShadowRay> rays{*TraceScene::segmentRay(from, above), *TraceScene::segmentRay(from, beside),
                                        TraceScene::skyRay(from, {0, 0, 1}, 0), TraceScene::skyRay(from, {1, 0, 0}, 0)};
            for (ShadowRay& r : rays) r.mask = mask;
            std::vector<Vec3> out(rays.size());
            scene.traceBatch(rays, out);
            EXPECT_EQ(out[0], upExpected) << receive << " " << wallGroup;
            EXPECT_EQ(out[1], sideExpected) << receive << " " << wallGroup;
            // Sun rays see the skies of the receiver's groups as one by one; a receiver of every
            // group reaches both skies.
            EXPECT_EQ(out[2], scene.skyTransmission(from, {0, 0, 1}, 0, 0, mask)) << receive << " " << wallGroup;
            EXPECT_EQ(out[3], scene.skyTransmission(from, {1, 0, 0}, 0, 0, mask)) << receive << " " << wallGroup;
            if (receive == 4) {
                EXPECT_EQ(out[2], (Vec3{1, 1, 1})) << wallGroup;
                EXPECT_EQ(out[3], (Vec3{1, 1, 1})) << wallGroup;
            }
        }
    }
}

TEST(TraceScene, OpaqueRoofBlocksSun) {
    LightingShader sky;
    sky.sky = true;
    std::vector<SceneSurface> s{quad({-1000, -1000, 500}, {2000, 0, 0}, {0, 2000, 0}, &sky, 0),
                                quad({-100, -100, 200}, {200, 0, 0}, {0, 200, 0})};
    TraceScene scene(s, {});
    EXPECT_EQ(scene.skyTransmission({0, 0, 0}, {0, 0, 1}, 0), (Vec3{0, 0, 0}));
    EXPECT_EQ(scene.skyTransmission({300, 0, 0}, {0, 0, 1}, 0), (Vec3{1, 1, 1}));
}

TEST(TraceScene, HitAtExactlyIgnoreNearIsPassed) {
    // q3map2 skips hits at a depth up to and including the inhibit radius: a sky face exactly
    // ignoreNear above the point is not seen (the sun ray escapes and the point stays dark, as a
    // grid point half a cell below a skybox roof does); a hair further away it is.
    LightingShader sky;
    sky.sky = true;
    std::vector<SceneSurface> s{quad({-1000, -1000, 64}, {2000, 0, 0}, {0, 2000, 0}, &sky, 0),
                                quad({-1000, 50, -1000}, {2000, 0, 0}, {0, 0, 2000})};  // wall y = 50
    TraceScene scene(s, {});
    const Vec3 up{0, 0, 1};
    EXPECT_EQ(scene.skyTransmission({0, 0, 0}, up, 0, 64), (Vec3{0, 0, 0}));
    EXPECT_EQ(scene.skyTransmission({0, 0, -0.5f}, up, 0, 64), (Vec3{1, 1, 1}));
    EXPECT_EQ(scene.skyTransmission({0, 0, 0}, up, 0, 63.5f), (Vec3{1, 1, 1}));
    // Segments alike: a wall exactly ignoreNear away does not block, single or batched.
    EXPECT_EQ(scene.transmission({0, 0, 0}, {0, 60, 0}, 50), (Vec3{1, 1, 1}));
    EXPECT_EQ(scene.transmission({0, -1, 0}, {0, 60, 0}, 50), (Vec3{0, 0, 0}));
    std::vector<ShadowRay> rays{*TraceScene::segmentRay({0, 0, 0}, {0, 60, 0}, 50),
                                TraceScene::skyRay({0, 0, 0}, up, 0, 64)};
    std::vector<Vec3> out(rays.size());
    scene.traceBatch(rays, out);
    EXPECT_EQ(out[0], (Vec3{1, 1, 1}));
    EXPECT_EQ(out[1], (Vec3{0, 0, 0}));
}

TEST(TraceScene, FirstTestedDepthIsTheNextFloatAboveTheInhibitRadius) {
    // Its definition: 0 without a radius, else the next float up (std::nextafter towards infinity).
    const float inf = std::numeric_limits<float>::infinity();
    const float cases[] = {0.0f, -0.0f, -1.0f, std::numeric_limits<float>::denorm_min(), 1e-30f, 0.5f, 1.0f,
                           50.0f, 64.0f, 1e30f, std::numeric_limits<float>::max(), inf, -inf,
                           std::numeric_limits<float>::quiet_NaN()};
    for (const float radius : cases) {
        const float expected = radius > 0 ? std::nextafter(radius, inf) : 0.0f;
        EXPECT_EQ(std::bit_cast<uint32_t>(TraceScene::firstTestedDepth(radius)), std::bit_cast<uint32_t>(expected))
            << radius;
    }
    for (uint32_t bits = 0x3f800000u; bits < 0x3f800000u + 4096u; ++bits) {
        const float radius = std::bit_cast<float>(bits);
        EXPECT_EQ(TraceScene::firstTestedDepth(radius), std::nextafter(radius, inf)) << radius;
    }
}

TEST(TraceScene, SunRayIntoStructuralSolidIsBlocked) {
    // A sky ceiling and no caster below it; the solid test calls x > 100 solid. A sun ray that
    // stays out of it reaches the sky; one that starts in it or crosses into it before the sky does
    // not, singly and in a batch; segments to point lights likewise, however short.
    LightingShader sky;
    sky.sky = true;
    std::vector<SceneSurface> s{quad({-1000, -1000, 500}, {2000, 0, 0}, {0, 2000, 0}, &sky, 0)};
    TraceSceneOptions options;
    options.solidBetween = [](Vec3 from, Vec3 to) { return std::max(from.x, to.x) > 100; };
    TraceScene scene(s, options);
    const Vec3 up{0, 0, 1}, slanted = normalize(Vec3{1, 0, 1});
    EXPECT_EQ(scene.skyTransmission({0, 0, 0}, up, 0), (Vec3{1, 1, 1}));
    EXPECT_EQ(scene.skyTransmission({150, 0, 0}, up, 0), (Vec3{0, 0, 0}));
    EXPECT_EQ(scene.skyTransmission({0, 0, 0}, slanted, 0), (Vec3{0, 0, 0}));  // reaches x = 500 first
    EXPECT_EQ(scene.transmission({150, 0, 0}, {150, 0, 400}), (Vec3{0, 0, 0}));
    EXPECT_EQ(scene.transmission({0, 0, 0}, {0, 0, 400}), (Vec3{1, 1, 1}));
    EXPECT_EQ(scene.transmission({99, 0, 0}, {101, 0, 0}, 8), (Vec3{0, 0, 0}));  // within ignoreNear
    std::vector<ShadowRay> rays;
    for (int i = 0; i < 90; ++i) {
        const Vec3 from{float(i % 3) * 75.0f, float(i), 0};
        if (i % 5 == 0)
            rays.push_back(*TraceScene::segmentRay(from, from + Vec3{float(i % 4) * 20.0f, 0, 300}));
        else
            rays.push_back(TraceScene::skyRay(from, i % 2 ? up : slanted, 0));
    }
    std::vector<Vec3> out(rays.size());
    scene.traceBatch(rays, out);
    int blocked = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        const ShadowRay& r = rays[i];
        const Vec3 single = r.toSky ? scene.skyTransmission(r.from, r.direction, 0)
                                    : scene.transmission(r.from, r.from + r.direction * (r.tfar + 0.01f));
        EXPECT_EQ(out[i], single) << "ray " << i;
        blocked += out[i] == Vec3{};
    }
    EXPECT_GT(blocked, 0);
    EXPECT_LT(blocked, int(rays.size()));
}

TEST(TraceScene, ClearHullsAndClearRaysSkipTheSolidWalk) {
    // The solid test calls x > 100 solid and counts its calls. A batch whose hull the scene's hull
    // test calls clear asks it nothing; one it does not call clear asks once per open segment; a
    // ray the caller marks clear of solid is never asked about, singly or in a batch.
    std::vector<SceneSurface> s{quad({-1000, -1000, 500}, {2000, 0, 0}, {0, 2000, 0})};
    int walks = 0, hulls = 0;
    bool hullAnswer = true;
    TraceSceneOptions options;
    options.solidBetween = [&](Vec3 from, Vec3 to) {
        ++walks;
        return std::max(from.x, to.x) > 100;
    };
    options.hullClearOfSolid = [&](std::span<const Vec3> points) {
        ++hulls;
        EXPECT_EQ(points.size() % 2, 0u);
        return HullVerdict{hullAnswer, std::nullopt};
    };
    TraceScene scene(s, options);
    std::vector<ShadowRay> rays;
    for (int i = 0; i < 20; ++i) rays.push_back(*TraceScene::segmentRay({float(i) * 10, 0, 0}, {0, 0, 300}));
    std::vector<Vec3> out(rays.size());
    scene.traceBatch(rays, out);
    EXPECT_EQ(hulls, 1);
    EXPECT_EQ(walks, 0);
    for (const Vec3& t : out) EXPECT_EQ(t, (Vec3{1, 1, 1}));

    hullAnswer = false;
    scene.traceBatch(rays, out);
    EXPECT_EQ(hulls, 2);
    EXPECT_EQ(walks, 20);
    for (size_t i = 0; i < rays.size(); ++i) EXPECT_EQ(out[i], (i > 10 ? Vec3{} : Vec3{1, 1, 1})) << i;

    for (ShadowRay& r : rays) r.clearOfSolid = true;
    scene.traceBatch(rays, out);
    EXPECT_EQ(walks, 20);
    EXPECT_EQ(scene.transmission({150, 0, 0}, {150, 0, 400}, 0, kAllShadowGroups, true), (Vec3{1, 1, 1}));
    EXPECT_EQ(scene.transmission({150, 0, 0}, {150, 0, 400}), (Vec3{0, 0, 0}));
    EXPECT_EQ(walks, 21);
}

TEST(TraceScene, AlphaShadowAndLightFilterAttenuate) {
    LightImage grey = solidImage(255, 128, 0, 64);
    LightingShader alpha, filter, both;
    alpha.alphaShadow = true;
    alpha.lightImage = &grey;
    filter.lightFilter = true;
    filter.lightImage = &grey;
    both.alphaShadow = true;
    both.lightFilter = true;
    both.lightImage = &grey;

    {
        std::vector<SceneSurface> s{quad({-64, 50, -64}, {128, 0, 0}, {0, 0, 128}, &alpha)};
        TraceScene scene(s, {});
        Vec3 t = scene.transmission({0, 0, 0}, {0, 100, 0});
        EXPECT_FLOAT_EQ(t.x, (255.0f - 64.0f) / 255.0f);
        EXPECT_FLOAT_EQ(t.y, t.x);
    }
    {
        std::vector<SceneSurface> s{quad({-64, 50, -64}, {128, 0, 0}, {0, 0, 128}, &filter)};
        TraceScene scene(s, {});
        Vec3 t = scene.transmission({0, 0, 0}, {0, 100, 0});
        EXPECT_FLOAT_EQ(t.x, 1.0f);
        EXPECT_FLOAT_EQ(t.y, 128.0f / 255.0f);
        EXPECT_FLOAT_EQ(t.z, 0.0f);
    }
    {
        // Two filtering grates in a row multiply; order of discovery does not matter.
        std::vector<SceneSurface> s{quad({-64, 50, -64}, {128, 0, 0}, {0, 0, 128}, &both),
                                    quad({-64, 70, -64}, {128, 0, 0}, {0, 0, 128}, &alpha)};
        TraceScene scene(s, {});
        const float a = (255.0f - 64.0f) / 255.0f;
        Vec3 t = scene.transmission({0, 0, 0}, {0, 100, 0});
        EXPECT_NEAR(t.x, a * a, 1e-6);
        EXPECT_NEAR(t.y, 128.0f / 255.0f * a * a, 1e-6);
        Vec3 back = scene.transmission({0, 100, 0}, {0, 0, 0});
        EXPECT_EQ(t, back);
        // An opaque wall behind the grates still blocks.
        std::vector<SceneSurface> s2 = s;
        s2.push_back(quad({-64, 90, -64}, {128, 0, 0}, {0, 0, 128}));
        TraceScene scene2(s2, {});
        EXPECT_EQ(scene2.transmission({0, 0, 0}, {0, 100, 0}), (Vec3{0, 0, 0}));
        EXPECT_NEAR(scene2.transmission({0, 0, 0}, {0, 80, 0}).x, a * a, 1e-6);
    }
}

TEST(TraceScene, AlphaShadowReadsTheTexelAtTheHit) {
    LightImage half = halfImage();
    LightingShader grate;
    grate.alphaShadow = true;
    grate.lightImage = &half;
    // s runs along x from -64 (s=0) to 64 (s=1); nearest texel with q3map2's rounding:
    // int(2s + 0.5) is texel 0 (transparent) for s < 0.25 and texel 1 (opaque) up to s = 0.75.
    std::vector<SceneSurface> s{quad({-64, 50, -64}, {128, 0, 0}, {0, 0, 128}, &grate)};
    TraceScene scene(s, {});
    EXPECT_EQ(scene.transmission({-56, 0, 0}, {-56, 100, 0}), (Vec3{1, 1, 1}));
    EXPECT_EQ(scene.transmission({8, 0, 0}, {8, 100, 0}), (Vec3{0, 0, 0}));
}

TEST(TraceScene, AlphaShadowWithoutImageIsOpaque) {
    LightingShader grate;
    grate.alphaShadow = true;
    std::vector<SceneSurface> s{quad({-64, 50, -64}, {128, 0, 0}, {0, 0, 128}, &grate)};
    TraceScene scene(s, {});
    EXPECT_EQ(scene.transmission({0, 0, 0}, {0, 100, 0}), (Vec3{0, 0, 0}));
}

TEST(TraceScene, BatchMatchesSingleRays) {
    // Sky ceiling (index 0) with an opaque beam and a tinted grate below it: a batch of sun and
    // point-light rays, longer than one internal chunk, gives exactly what single rays give.
    LightingShader sky, grate;
    sky.sky = true;
    LightImage tint = solidImage(255, 128, 0, 64);
    grate.alphaShadow = true;
    grate.lightFilter = true;
    grate.lightImage = &tint;
    std::vector<SceneSurface> s{quad({-1000, -1000, 500}, {2000, 0, 0}, {0, 2000, 0}, &sky, 0),
                                quad({-40, -1000, 300}, {80, 0, 0}, {0, 2000, 0}),
                                quad({100, -1000, 200}, {200, 0, 0}, {0, 2000, 0}, &grate)};
    TraceScene scene(s, {});
    std::vector<ShadowRay> rays;
    for (int i = 0; i < 700; ++i) {
        const Vec3 from{static_cast<float>(i % 70) * 6.0f - 200.0f, static_cast<float>(i / 70) * 10.0f, 0};
        if (i % 3 == 0) {
            // Every other point-light segment reaches past the sky ceiling (some through the grate).
            const float top = (i / 3) % 2 ? 600.0f : 400.0f;
            if (auto r = TraceScene::segmentRay(from, from + Vec3{10, 0, top}, 0)) rays.push_back(*r);
        } else {
            rays.push_back(TraceScene::skyRay(from, Vec3{0.1f * static_cast<float>(i % 5), 0, 1}, i % 7 == 0 ? 1 : 0));
        }
    }
    std::vector<Vec3> batch(rays.size()), incoherent(rays.size());
    scene.traceBatch(rays, batch);
    scene.traceBatch(rays, incoherent, false);  // the stream hint changes the speed only
    int lit = 0, tinted = 0, blocked = 0, pastSky = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        const ShadowRay& r = rays[i];
        if (!r.toSky && r.tfar > 500) {
            // Sky surfaces block point-light rays like walls, translucent crossings or not.
            EXPECT_EQ(batch[i], Vec3{}) << "ray " << i;
            EXPECT_EQ(incoherent[i], Vec3{}) << "ray " << i;
            ++pastSky;
        }
        const Vec3 single = r.toSky ? scene.skyTransmission(r.from, r.direction, r.skyIndex)
                                    : scene.transmission(r.from, r.from + r.direction * (r.tfar + 0.01f));
        EXPECT_NEAR(batch[i].x, single.x, 1e-6f) << "ray " << i;
        EXPECT_NEAR(batch[i].y, single.y, 1e-6f) << "ray " << i;
        EXPECT_NEAR(incoherent[i].x, single.x, 1e-6f) << "ray " << i;
        EXPECT_NEAR(incoherent[i].y, single.y, 1e-6f) << "ray " << i;
        lit += batch[i] == Vec3{1, 1, 1};
        tinted += batch[i].x > 0 && batch[i].x < 1;
        blocked += batch[i] == Vec3{};
    }
    // Every kind of outcome occurs.
    EXPECT_GT(lit, 0);
    EXPECT_GT(tinted, 0);
    EXPECT_GT(blocked, 0);
    EXPECT_GT(pastSky, 0);
}

}  // namespace
}  // namespace q3::light
