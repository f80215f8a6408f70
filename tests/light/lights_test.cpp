// The light list: entity lights (q3map2 and controlled models), suns, sky domes, surface lights.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "light_test_util.h"
#include "light_reach.h"
#include "lights.h"

namespace q3::light {
namespace {

using test::entity;

std::vector<Light> lightsOf(const std::vector<bsp::Entity>& ents, const LightScales& scales = {}) {
    test::CapturingLog cap;
    CLibraryRandom random;
    return createEntityLights(ents, ents, scales, cap.log, "test.bsp", random);
}

TEST(EntityLights, DefaultPointLightUsesPointScaleAndWhite) {
    auto lights = lightsOf({entity({{"classname", "worldspawn"}}),
                            entity({{"classname", "light"}, {"origin", "1 2 3"}})});
    ASSERT_EQ(lights.size(), 1u);
    const Light& l = lights[0];
    EXPECT_EQ(l.type, LightType::Point);
    EXPECT_FLOAT_EQ(l.photons, 300.0f * 7500.0f);
    EXPECT_EQ(l.origin, (Vec3{1, 2, 3}));
    EXPECT_EQ(l.color, (Vec3{1, 1, 1}));
    EXPECT_TRUE(l.angleAttenuation);
    EXPECT_FALSE(l.linear);
    EXPECT_TRUE(l.affectsGrid);
    EXPECT_TRUE(l.affectsSurfaces);
    EXPECT_EQ(l.entityNum, 1);
}

TEST(EntityLights, IntensityKeysScaleAndColorNormalisation) {
    auto lights = lightsOf({entity({{"classname", "light"}, {"light", "200"}, {"scale", "2"}, {"_color", "0.5 0.25 0"}}),
                            entity({{"classname", "light_fluoro"}, {"_light", "0"}, {"_color", "0.5 0.25 0"},
                                    {"spawnflags", "32"}})});
    ASSERT_EQ(lights.size(), 2u);
    EXPECT_FLOAT_EQ(lights[0].photons, 400.0f * 7500.0f);
    EXPECT_EQ(lights[0].color, (Vec3{1, 0.5f, 0}));
    EXPECT_FLOAT_EQ(lights[1].photons, 300.0f * 7500.0f);  // 0 means the default 300
    EXPECT_EQ(lights[1].color, (Vec3{0.5f, 0.25f, 0}));     // spawnflags 32: unnormalised
}

TEST(EntityLights, SpawnflagsAndJunior) {
    auto lights = lightsOf({entity({{"classname", "light"}, {"spawnflags", "1"}, {"fade", "2"}}),
                            entity({{"classname", "light"}, {"spawnflags", "2"}}),
                            entity({{"classname", "light"}, {"spawnflags", "16"}}),
                            entity({{"classname", "lightJunior"}, {"spawnflags", "16"}}),
                            entity({{"classname", "light"}, {"_anglescale", "0.5"}, {"spawnflags", "2"}}),
                            entity({{"classname", "info_null"}})});
    ASSERT_EQ(lights.size(), 5u);
    EXPECT_TRUE(lights[0].linear);
    EXPECT_FALSE(lights[0].angleAttenuation);
    EXPECT_FLOAT_EQ(lights[0].fade, 2);
    EXPECT_FALSE(lights[1].linear);
    EXPECT_FALSE(lights[1].angleAttenuation);
    EXPECT_FLOAT_EQ(lights[1].fade, 1);
    EXPECT_FALSE(lights[2].affectsGrid);
    EXPECT_TRUE(lights[3].affectsGrid);  // lightJunior forces the grid and leaves surfaces alone
    EXPECT_FALSE(lights[3].affectsSurfaces);
    EXPECT_TRUE(lights[4].angleAttenuation);  // _anglescale forces angle attenuation back on
    EXPECT_FLOAT_EQ(lights[4].angleScale, 0.5f);
}

TEST(EntityLights, WolfModeDefaultsToLinear) {
    LightScales wolf;
    wolf.wolfLight = true;
    auto lights = lightsOf({entity({{"classname", "light"}}), entity({{"classname", "light"}, {"spawnflags", "1"}})},
                           wolf);
    EXPECT_TRUE(lights[0].linear);
    EXPECT_FALSE(lights[0].angleAttenuation);
    EXPECT_FALSE(lights[1].linear);
    EXPECT_TRUE(lights[1].angleAttenuation);
}

TEST(EntityLights, SpotlightFromTarget) {
    auto lights = lightsOf({entity({{"classname", "light"}, {"origin", "0 0 100"}, {"target", "t1"}, {"radius", "48"},
                                    {"spawnflags", "1"}}),
                            entity({{"classname", "info_null"}, {"targetname", "t1"}, {"origin", "0 0 -100"}})});
    ASSERT_EQ(lights.size(), 1u);
    const Light& l = lights[0];
    EXPECT_EQ(l.type, LightType::Spot);
    EXPECT_EQ(l.normal, (Vec3{0, 0, -1}));
    EXPECT_FLOAT_EQ(l.radiusByDist, (48.0f + 16.0f) / 200.0f);
    EXPECT_FALSE(l.linear);  // spotlights are always inverse square
    EXPECT_TRUE(l.angleAttenuation);
    EXPECT_FLOAT_EQ(l.photons, 300.0f * 7500.0f);
}

TEST(EntityLights, MissingTargetWarnsAndStaysPoint) {
    test::CapturingLog cap;
    std::vector<bsp::Entity> ents{entity({{"classname", "light"}, {"target", "nowhere"}})};
    CLibraryRandom random;
    auto lights = createEntityLights(ents, ents, {}, cap.log, "test.bsp", random);
    ASSERT_EQ(lights.size(), 1u);
    EXPECT_EQ(lights[0].type, LightType::Point);
    ASSERT_EQ(cap.warnings.size(), 1u);
    EXPECT_NE(cap.warnings[0].find("missing target"), std::string::npos);
}

TEST(EntityLights, SamplesJitterDeterministicallyAndSplitIntensity) {
    std::vector<bsp::Entity> ents{
        entity({{"classname", "light"}, {"origin", "0 0 0"}, {"_samples", "4"}, {"_deviance", "8"}})};
    auto a = lightsOf(ents);
    auto b = lightsOf(ents);
    ASSERT_EQ(a.size(), 4u);
    EXPECT_EQ(a[0].origin, (Vec3{0, 0, 0}));
    for (size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i].origin, b[i].origin);
        EXPECT_FLOAT_EQ(a[i].photons, 75.0f * 7500.0f);
        EXPECT_FLOAT_EQ(a[i].falloffTolerance, 0.25f);
        EXPECT_LE(std::fabs(a[i].origin.x), 8.0f);
        EXPECT_LE(std::fabs(a[i].origin.z), 8.0f);
    }
    EXPECT_NE(a[1].origin, a[2].origin);
}

TEST(EntityLights, InvalidStyleIsAnError) {
    std::vector<bsp::Entity> ents{entity({{"classname", "light"}, {"style", "300"}})};
    test::CapturingLog cap;
    CLibraryRandom random;
    EXPECT_THROW(createEntityLights(ents, ents, {}, cap.log, "test.bsp", random), CompileError);
    auto ok = lightsOf({entity({{"classname", "light"}, {"_style", "5"}})});
    EXPECT_EQ(ok[0].style, 5);
}

TEST(EntityLights, ExtraDistAndFilterRadius) {
    LightScales scales;
    scales.extraDist = 12;
    auto lights = lightsOf({entity({{"classname", "light"}}),
                            entity({{"classname", "light"}, {"_extradist", "3"}, {"_filterradius", "9"}})},
                           scales);
    EXPECT_FLOAT_EQ(lights[0].extraDist, 12);
    EXPECT_FLOAT_EQ(lights[1].extraDist, 3);
    EXPECT_FLOAT_EQ(lights[1].filterRadius, 9);
}

TEST(EntityLights, EntitySunSplitsIntensityTwiceAsQ3map2) {
    auto lights = lightsOf({entity({{"classname", "light"}, {"origin", "0 0 0"}, {"target", "s"}, {"_sun", "1"},
                                    {"light", "100"}, {"_samples", "2"}, {"_deviance", "1"}}),
                            entity({{"classname", "target_position"}, {"targetname", "s"}, {"origin", "0 0 -10"}})});
    ASSERT_EQ(lights.size(), 2u);
    for (const Light& l : lights) {
        EXPECT_EQ(l.type, LightType::Sun);
        EXPECT_FLOAT_EQ(l.photons, 100.0f / 4.0f);
        EXPECT_EQ(l.skyIndex, -1);
        EXPECT_GT(l.normal.z, 0.99f);  // towards the sun: up
    }
    EXPECT_EQ(lights[0].normal, (Vec3{0, 0, 1}));
}

TEST(ControlledLights, DefaultsAndLegacyKeysIgnored) {
    auto lights = lightsOf({entity({{"classname", "light"}, {"brightness", "0.5"}, {"light", "9999"}})});
    ASSERT_EQ(lights.size(), 1u);
    ASSERT_TRUE(lights[0].controlled.has_value());
    const ControlledParams& p = *lights[0].controlled;
    EXPECT_FLOAT_EQ(p.brightness, 0.5f);
    EXPECT_FLOAT_EQ(p.dotProductWeight, 0.5f);
    EXPECT_FLOAT_EQ(p.falloffStart, 0);
    EXPECT_FLOAT_EQ(p.falloffEnd, 300);
    EXPECT_FLOAT_EQ(p.falloffCurvature, 0.5f);
    EXPECT_FLOAT_EQ(p.angleHotspot, 45);
    EXPECT_FLOAT_EQ(p.anglePenumbra, 60);
    EXPECT_FLOAT_EQ(p.sphericalAmbient, 0);
}

TEST(ControlledLights, ClampsWithWarningsNamingEntityAndKey) {
    test::CapturingLog cap;
    std::vector<bsp::Entity> ents{entity({{"classname", "worldspawn"}}),
                                  entity({{"classname", "light"},
                                          {"brightness", "3"},
                                          {"dot_product_weight", "-1"},
                                          {"falloff_start_dist", "200"},
                                          {"falloff_end_dist", "100"},
                                          {"falloff_curvature", "2"},
                                          {"angle_hotspot", "90"},
                                          {"angle_penumbra", "30"},
                                          {"spherical_ambient", "1.5"},
                                          {"_color", "2 1 0"}})};
    CLibraryRandom random;
    auto lights = createEntityLights(ents, ents, {}, cap.log, "test.bsp", random);
    ASSERT_EQ(lights.size(), 1u);
    const ControlledParams& p = *lights[0].controlled;
    EXPECT_FLOAT_EQ(p.brightness, 1);
    EXPECT_FLOAT_EQ(p.dotProductWeight, 0);
    EXPECT_FLOAT_EQ(p.falloffStart, 200);
    EXPECT_FLOAT_EQ(p.falloffEnd, 200);  // raised to start
    EXPECT_FLOAT_EQ(p.falloffCurvature, 1);
    EXPECT_FLOAT_EQ(p.angleHotspot, 90);
    EXPECT_FLOAT_EQ(p.anglePenumbra, 90);  // raised to hotspot
    EXPECT_FLOAT_EQ(p.sphericalAmbient, 1);
    EXPECT_EQ(lights[0].color, (Vec3{1, 0.5f, 0}));
    ASSERT_EQ(cap.warnings.size(), 7u);
    for (const char* key : {"brightness", "dot_product_weight", "falloff_end_dist", "falloff_curvature",
                            "angle_penumbra", "spherical_ambient", "_color"}) {
        bool found = false;
        for (const std::string& w : cap.warnings)
            if (w.find(std::string("\"") + key + "\"") != std::string::npos && w.find("entity 1") != std::string::npos)
                found = true;
        EXPECT_TRUE(found) << key;
    }
}

TEST(ControlledLights, SpotAndSun) {
    auto lights = lightsOf({entity({{"classname", "light"}, {"origin", "0 0 100"}, {"target", "t"}, {"angle_hotspot", "30"}}),
                            entity({{"classname", "light"}, {"origin", "0 0 100"}, {"target", "t"}, {"_sun", "1"},
                                    {"brightness", "1"}}),
                            entity({{"classname", "info_null"}, {"targetname", "t"}, {"origin", "100 0 0"}})});
    ASSERT_EQ(lights.size(), 2u);
    EXPECT_EQ(lights[0].type, LightType::Spot);
    EXPECT_NEAR(lights[0].normal.x, std::sqrt(0.5f), 1e-6);
    EXPECT_NEAR(lights[0].normal.z, -std::sqrt(0.5f), 1e-6);
    EXPECT_EQ(lights[1].type, LightType::Sun);
    EXPECT_NEAR(lights[1].normal.z, std::sqrt(0.5f), 1e-6);  // towards the sun
}

TEST(WorldLighting, Keys) {
    WorldLighting w = readWorldLighting(entity({{"classname", "worldspawn"}, {"_ambient", "10"}, {"_color", "1 0.5 0"},
                                                {"_minlight", "4"}, {"_mingridlight", "8"}, {"_noshadersun", "1"}}));
    EXPECT_EQ(w.ambient, (Vec3{10, 5, 0}));
    EXPECT_EQ(w.minLight, (Vec3{4, 2, 0}));
    EXPECT_EQ(w.minVertexLight, (Vec3{4, 2, 0}));
    EXPECT_EQ(w.minGridLight, (Vec3{8, 4, 0}));
    EXPECT_TRUE(w.noShaderSun);
    EXPECT_FALSE(w.keepLights);
}

// The worldspawn colour scales the ambient and minimum lights as written, not normalised to a
// brightest channel of 1 (oacmpdm10's worldspawn).
TEST(WorldLighting, ColorIsNotNormalised) {
    WorldLighting w =
        readWorldLighting(entity({{"classname", "worldspawn"}, {"ambient", "2"}, {"_color", "0.87 0.87 0.5"}}));
    EXPECT_NEAR(w.ambient.x, 1.74f, 1e-5);
    EXPECT_NEAR(w.ambient.y, 1.74f, 1e-5);
    EXPECT_NEAR(w.ambient.z, 1.0f, 1e-5);
    // A colour of zero length means white.
    w = readWorldLighting(entity({{"classname", "worldspawn"}, {"_minlight", "3"}, {"_color", "0 0 0"}}));
    EXPECT_EQ(w.minLight, (Vec3{3, 3, 3}));
}

TEST(SunLights, ShaderSunSamplesAndScale) {
    LightScales scales;
    scales.skyScale = 2;
    SunDirective sun;
    sun.intensity = 100;
    sun.direction = normalize(Vec3{1, 0, 1});
    sun.samples = 4;
    sun.devianceDeg = 2;
    sun.filterRadius = 8;
    std::vector<Light> a, b;
    CLibraryRandom first, second;
    appendSunLights(a, sun, 3, scales, first);
    appendSunLights(b, sun, 3, scales, second);
    ASSERT_EQ(a.size(), 4u);
    EXPECT_NEAR(a[0].normal.x, sun.direction.x, 1e-6);
    EXPECT_NEAR(a[0].normal.z, sun.direction.z, 1e-6);
    for (size_t i = 0; i < a.size(); ++i) {
        EXPECT_FLOAT_EQ(a[i].photons, 25.0f * 2.0f);
        EXPECT_EQ(a[i].skyIndex, 3);
        EXPECT_FLOAT_EQ(a[i].filterRadius, 2);
        EXPECT_EQ(a[i].normal, b[i].normal);
        // Within the deviance cone (2 degrees in azimuth/elevation space).
        EXPECT_GT(dot(a[i].normal, sun.direction), std::cos(degToRad(3.0f)));
    }
    scales.oneSky = true;
    std::vector<Light> c;
    appendSunLights(c, sun, 3, scales, first);
    EXPECT_EQ(c[0].skyIndex, -1);
    EXPECT_FALSE(c[0].skyDome);
}

TEST(SunLights, SkyDomeLayout) {
    SkyLightDirective sky;
    sky.value = 100;
    sky.iterations = 3;
    std::vector<Light> suns;
    appendSkyLights(suns, sky, {1, 1, 1}, 0, 0, 0, {});
    // angleSteps = 8; eleStep = 30; with the straight-up sun the rings stop at 90 - 1.5 * 30:
    // elevations 15 and 45 -> 2 rings of 8, plus the straight-up sun.
    ASSERT_EQ(suns.size(), 8u * 2u + 1u);
    float sum = 0;
    for (const Light& l : suns) sum += l.photons;
    EXPECT_NEAR(sum, 100.0f, 1e-3);
    for (const Light& l : suns) EXPECT_TRUE(l.skyDome);  // sky ambient, as opposed to a sun
    EXPECT_NEAR(suns[0].normal.z, std::sin(degToRad(15.0f)), 1e-5);
    EXPECT_NEAR(suns[8].normal.z, std::sin(degToRad(45.0f)), 1e-5);
    // The second ring is staggered by half an azimuth step (45 / 2 degrees).
    EXPECT_NEAR(std::atan2(suns[8].normal.y, suns[8].normal.x), degToRad(22.5f), 1e-5);
    // Sky domes of a horizon range below 90 degrees: photons scaled by max(0.25, range / 90).
    SkyLightDirective low;
    low.value = 100;
    low.iterations = 3;
    low.horizonMin = 0;
    low.horizonMax = 45;
    std::vector<Light> lowSuns;
    appendSkyLights(lowSuns, low, {1, 1, 1}, 0, 0, 0, {});
    float lowSum = 0;
    for (const Light& l : lowSuns) lowSum += l.photons;
    EXPECT_NEAR(lowSum, 50.0f, 1e-3);
    EXPECT_EQ(suns.back().normal, (Vec3{0, 0, 1}));
}

TEST(SunLights, SkyDomeColoursFromSkyBox) {
    auto solid = [](uint8_t r, uint8_t g, uint8_t b) {
        LightImage img;
        img.width = img.height = 4;
        for (int i = 0; i < 16; ++i) img.rgba.insert(img.rgba.end(), {r, g, b, 255});
        return img;
    };
    const LightImage side = solid(0, 0, 200), up = solid(255, 0, 0), down = solid(0, 255, 0);
    const SkyBoxImages box{&side, &side, &side, &side, &up, &down};
    SkyLightDirective sky;
    sky.value = 100;
    sky.iterations = 3;
    sky.sampleColor = true;
    std::vector<Light> suns;
    appendSkyLights(suns, sky, {1, 1, 1}, 0, 0, 0, {}, &box);
    ASSERT_EQ(suns.size(), 17u);
    float brightest = 0;
    for (const Light& l : suns) {
        brightest = std::max(brightest, maxComponent(l.color));
        EXPECT_EQ(l.color.y, 0.0f);  // the ground image is below the dome's horizon
    }
    EXPECT_FLOAT_EQ(brightest, 1.0f);
    const Light& top = suns.back();
    EXPECT_GT(top.color.x, top.color.z);      // straight up sees the red top
    EXPECT_GT(suns[0].color.z, suns[0].color.x);  // 15 degrees up sees mostly the blue sides
    // Without the images the shader colour stays.
    std::vector<Light> plain;
    appendSkyLights(plain, sky, {1, 0.5f, 0.5f}, 0, 0, 0, {}, nullptr);
    EXPECT_EQ(plain[0].color, (Vec3{1, 0.5f, 0.5f}));
}

TEST(SurfaceLights, PatchMeshEmitsOneWindingPerQuadEvenWithACollapsedEdge) {
    // A 2 x 3 lighting mesh whose first column collapses to one point (a fan-shaped patch): q3map2
    // emits every quad whole, the collapsed ones as three-sided quads, never as split triangles.
    LightingShader sh;
    sh.surfaceLight = 100;
    sh.backsplashSet = true;  // q3map_backsplash 0 0: no backsplash copies
    sh.backsplashFraction = 0;
    sh.backsplashDistance = 0;
    EmitterGeometry g;
    g.meshWidth = 2;
    g.meshHeight = 3;
    g.xyz = {{0, 0, 0}, {64, 0, 0}, {0, 0, 0}, {64, 64, 0}, {0, 0, 0}, {0, 64, 0}};
    g.normals.assign(6, Vec3{0, 0, 1});
    std::vector<Light> out;
    appendAreaLights(out, g, sh, {});
    ASSERT_EQ(out.size(), 2u);
    float area = 0;
    for (const Light& l : out) {
        EXPECT_EQ(l.winding.size(), 4u);
        EXPECT_EQ(l.normal, (Vec3{0, 0, 1}));
        area += l.photons / (100.0f * 0.25f);
    }
    EXPECT_NEAR(area, 64 * 64 / 2.0f + 64 * 64 / 2.0f, 0.5f);
    // The second row starts at its other corner ((x + y) & 1): its winding begins at row 2.
    EXPECT_EQ(out[1].winding[0], (Vec3{0, 0, 0}));
    EXPECT_EQ(out[1].winding[1], (Vec3{0, 64, 0}));
}

TEST(SurfaceLights, AreaLightsChoppedWithBacksplash) {
    LightingShader sh;
    sh.surfaceLight = 100;
    sh.lightSubdivide = 64;
    sh.color = {1, 0.5f, 0.5f};
    EmitterGeometry g;
    g.xyz = {{0, 0, 0}, {128, 0, 0}, {128, 128, 0}, {0, 128, 0}};
    g.normals = {{0, 0, -1}, {0, 0, -1}, {0, 0, -1}, {0, 0, -1}};
    g.triangles = {0, 1, 2, 0, 2, 3};
    std::vector<Light> out;
    appendAreaLights(out, g, sh, {});
    ASSERT_FALSE(out.empty());
    ASSERT_EQ(out.size() % 2, 0u);  // every piece is followed by its backsplash
    float emitted = 0, splashed = 0;
    for (size_t i = 0; i < out.size(); i += 2) {
        const Light& l = out[i];
        ASSERT_EQ(l.type, LightType::Area);
        emitted += l.photons;
        EXPECT_FLOAT_EQ(l.add, 100.0f * 3.0f * 0.25f);
        EXPECT_EQ(l.color, sh.color);
        Bounds b;
        for (const Vec3& p : l.winding) b.add(p);
        EXPECT_LE(b.size().x, 64.001f);
        EXPECT_LE(b.size().y, 64.001f);
        // q3map2 2.5.17n's backsplash: the piece's polygon, reversed and 23 units out along the
        // normal, facing back at the emitter's wall, one-sided, with 7 x 5 % of its strength.
        const Light& splash = out[i + 1];
        ASSERT_EQ(splash.type, LightType::Area);
        splashed += splash.photons;
        EXPECT_FLOAT_EQ(splash.add, l.add * 0.35f);
        EXPECT_EQ(splash.normal, (Vec3{0, 0, 1}));
        EXPECT_FALSE(splash.twoSided);
        EXPECT_FLOAT_EQ(splash.origin.z, -1.0f - 23.0f);
        ASSERT_EQ(splash.winding.size(), l.winding.size());
        for (size_t k = 0; k < l.winding.size(); ++k) {
            const Vec3 expected = l.winding[l.winding.size() - 1 - k] + Vec3{0, 0, -23};
            EXPECT_EQ(splash.winding[k], expected);
        }
        EXPECT_FLOAT_EQ(splash.planeDist, dot(splash.origin, splash.normal));
    }
    EXPECT_NEAR(emitted, 100.0f * 128 * 128 * 0.25f, 1.0f);
    EXPECT_NEAR(splashed, emitted * 0.35f, 1.0f);
}

TEST(SurfaceLights, BacksplashOptionAndShaderOverride) {
    LightingShader sh;
    sh.surfaceLight = 100;
    EmitterGeometry g;
    g.xyz = {{0, 0, 0}, {16, 0, 0}, {16, 16, 0}};
    g.normals.assign(3, Vec3{0, 0, 1});
    g.triangles = {0, 1, 2};
    LightScales scales;
    scales.backsplashFractionScale = 2;
    scales.backsplashDistance = 40;
    std::vector<Light> out;
    appendAreaLights(out, g, sh, scales);
    ASSERT_EQ(out.size(), 2u);
    EXPECT_EQ(out[1].type, LightType::Area);
    EXPECT_FLOAT_EQ(out[1].photons, out[0].photons * 7.0f * 0.1f);
    EXPECT_FLOAT_EQ(out[1].origin.z, out[0].origin.z + 40.0f);
    // q3map_backsplash in the shader wins over the command line.
    sh.backsplashSet = true;
    sh.backsplashFraction = 0.5f;
    sh.backsplashDistance = 8;
    out.clear();
    appendAreaLights(out, g, sh, scales);
    ASSERT_EQ(out.size(), 2u);
    EXPECT_FLOAT_EQ(out[1].photons, out[0].photons * 7.0f * 0.5f);
    EXPECT_FLOAT_EQ(out[1].origin.z, out[0].origin.z + 8.0f);
    // Sky shaders have no backsplash.
    sh.sky = true;
    out.clear();
    appendAreaLights(out, g, sh, scales);
    EXPECT_EQ(out.size(), 1u);
}

TEST(SurfaceLights, LightEnvelopes) {
    Light point;
    point.photons = 10000;
    point.fast = true;
    point.falloffTolerance = 1;
    EXPECT_FLOAT_EQ(lightEnvelope(point), 100);
    point.fast = false;
    EXPECT_TRUE(std::isinf(lightEnvelope(point)));
    Light controlled;
    controlled.controlled = ControlledParams{};
    controlled.controlled->falloffEnd = 420;
    EXPECT_FLOAT_EQ(lightEnvelope(controlled), 420);
}


// The envelope index answers exactly what testing every light with lightReachesBounds answers, in
// light order: random point, spot, area and sun lights of random envelopes against random boxes,
// including boxes touching an envelope's edge and lights more than one index block apart.
TEST(LightReachIndex, MatchesEveryLightTested) {
    std::mt19937 rng(4242);
    std::uniform_real_distribution<float> coord(-4000, 4000), size(0, 600), unit(0, 1);
    std::vector<Light> lights(700);
    std::vector<float> envelopes(lights.size());
    for (size_t i = 0; i < lights.size(); ++i) {
        Light& l = lights[i];
        const float kind = unit(rng);
        l.type = kind < 0.5f ? LightType::Point : kind < 0.8f ? LightType::Area : kind < 0.95f ? LightType::Spot : LightType::Sun;
        l.origin = {coord(rng), coord(rng), coord(rng)};
        envelopes[i] = unit(rng) < 0.02f ? std::numeric_limits<float>::infinity() : size(rng) * 3;
    }
    const LightReach reach(lights, envelopes);
    std::vector<uint32_t> got;
    size_t reached = 0;
    for (int trial = 0; trial < 3000; ++trial) {
        Bounds box;
        const Vec3 corner{coord(rng), coord(rng), coord(rng)};
        box.add(corner);
        box.add(corner + Vec3{size(rng), size(rng), size(rng)});
        if (trial % 10 == 0) {  // a box whose nearest point is just inside or outside some envelope
            const Light& l = lights[size_t(trial) % lights.size()];
            const float e = envelopes[size_t(trial) % lights.size()];
            box = Bounds{};
            box.add(l.origin + Vec3{e * (trial % 20 == 0 ? 0.9999f : 1.0001f), 0, 0});
            box.add(l.origin + Vec3{e + 50, 10, 10});
        }
        reach.reaching(box, got);
        std::vector<uint32_t> expected;
        for (size_t i = 0; i < lights.size(); ++i)
            if (lightReachesBounds(lights[i], box, envelopes[i])) expected.push_back(uint32_t(i));
        ASSERT_EQ(got, expected) << "trial " << trial;
        reached += got.size();
    }
    EXPECT_GT(reached, 3000u);
}

}  // namespace
}  // namespace q3::light
