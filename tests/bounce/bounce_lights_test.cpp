// Radiosity emitters (createBounceLights): q3map2's value/photons/add, chopping at 256 and the
// gradient re-chop down to 64, the colour as texture x luxel with -bouncecolorratio, unlit luxels
// skipped, the excluded shaders, styles, two-sided shaders, input checks, ordering and the -dump
// text. Expected numbers come from q3map2's formulas written out in each test.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include <tbb/task_arena.h>

#include "bounce_lights.h"
#include "bounce_test_util.h"
#include "log.h"

namespace q3::light {
namespace {

using test::lightBounds;
using test::polygonArea;
using test::squareSurface;

constexpr float kWhite = 255;
// q3map2: value = 500 * shaderBounceScale * 0.375; photons = value * area * bounceScale;
// add = value * 3 * bounceScale.
float expectedValue(float shaderBounceScale) { return 500.0f * shaderBounceScale * 0.375f; }

void expectColorNear(Vec3 actual, Vec3 expected, float tolerance) {
    EXPECT_NEAR(actual.x, expected.x, tolerance);
    EXPECT_NEAR(actual.y, expected.y, tolerance);
    EXPECT_NEAR(actual.z, expected.z, tolerance);
}

float maxExtent(const Light& light) { return maxComponent(lightBounds(light).size()); }

float totalArea(const std::vector<Light>& lights) {
    float sum = 0;
    for (const Light& l : lights) sum += polygonArea(l.winding);
    return sum;
}

std::vector<Light> lightsOf(const BounceSurface& s, const BounceSettings& settings = {}) {
    return createBounceLights(std::span<const BounceSurface>(&s, 1), settings);
}

TEST(BounceLights, UniformSquareGivesQ3map2Values) {
    const BounceSurface s = squareSurface(64, 8, Vec3::splat(kWhite));
    const std::vector<Light> lights = lightsOf(s);
    // Each triangle (extent 64 < 256) is one emitter.
    ASSERT_EQ(lights.size(), 2u);
    const float value = expectedValue(1);
    for (const Light& l : lights) {
        EXPECT_EQ(l.type, LightType::Area);
        ASSERT_EQ(l.winding.size(), 3u);
        EXPECT_NEAR(polygonArea(l.winding), 2048.0f, 1e-3f);
        EXPECT_NEAR(l.photons, value * 2048.0f * 0.25f, 0.05f);
        EXPECT_NEAR(l.add, value * 3.0f * 0.25f, 1e-4f);
        expectColorNear(l.color, {1, 1, 1}, 1e-5f);
        EXPECT_EQ(l.normal, Vec3(0, 0, 1));
        EXPECT_NEAR(l.planeDist, 1.0f, 1e-5f);
        EXPECT_EQ(l.style, 0);
        EXPECT_FALSE(l.twoSided);
        EXPECT_FALSE(l.fast);
        EXPECT_EQ(l.falloffTolerance, 1.0f);
        EXPECT_EQ(l.entityNum, -1);
    }
    // Origin: mean of the triangle's corners, one unit off the plane.
    const Vec3 firstCentre = (Vec3{0, 0, 0} + Vec3{64, 0, 0} + Vec3{64, 64, 0}) / 3.0f + Vec3{0, 0, 1};
    EXPECT_NEAR(distance(lights[0].origin, firstCentre), 0.0f, 1e-4f);
    const Vec3 secondCentre = (Vec3{0, 0, 0} + Vec3{64, 64, 0} + Vec3{0, 64, 0}) / 3.0f + Vec3{0, 0, 1};
    EXPECT_NEAR(distance(lights[1].origin, secondCentre), 0.0f, 1e-4f);
}

TEST(BounceLights, ScalesAndSettingsReachTheLight) {
    BounceSurface s = squareSurface(64, 8, Vec3::splat(kWhite));
    s.shaderBounceScale = 2;
    BounceSettings settings;
    settings.bounceScale = 0.5f;
    settings.falloffTolerance = 3;
    settings.fast = true;
    const std::vector<Light> lights = lightsOf(s, settings);
    ASSERT_EQ(lights.size(), 2u);
    const float value = expectedValue(2);
    for (const Light& l : lights) {
        EXPECT_NEAR(l.photons, value * 2048.0f * 0.5f, 0.1f);
        EXPECT_NEAR(l.add, value * 3.0f * 0.5f, 1e-3f);
        EXPECT_TRUE(l.fast);
        EXPECT_EQ(l.falloffTolerance, 3.0f);
    }
}

TEST(BounceLights, WideSquareIsChoppedAt256) {
    const BounceSurface s = squareSurface(512, 32, Vec3::splat(kWhite));
    const std::vector<Light> lights = lightsOf(s);
    // Each triangle (extent 512) is cut at x = 256 into a 256-triangle and a quadrilateral 256 wide
    // and 512 tall; that one is cut at y = 256 into a square and a triangle: 3 pieces each.
    ASSERT_EQ(lights.size(), 6u);
    for (const Light& l : lights) {
        EXPECT_LE(maxExtent(l), 256.0f + 1e-3f);
        EXPECT_GE(maxExtent(l), 256.0f - 1e-3f);
    }
    EXPECT_NEAR(totalArea(lights), 512.0f * 512.0f, 0.5f);
    float photons = 0;
    for (const Light& l : lights) photons += l.photons;
    EXPECT_NEAR(photons, expectedValue(1) * 512.0f * 512.0f * 0.25f, 20.0f);
}

TEST(BounceLights, ShaderLightSubdivideOverridesDefault) {
    LightingShader shader;
    shader.lightSubdivide = 32;
    BounceSurface s = squareSurface(64, 8, Vec3::splat(kWhite));
    s.shader = &shader;
    const std::vector<Light> lights = lightsOf(s);
    EXPECT_GT(lights.size(), 2u);
    for (const Light& l : lights) EXPECT_LE(maxExtent(l), 32.0f + 1e-3f);
    EXPECT_NEAR(totalArea(lights), 64.0f * 64.0f, 0.05f);
}

// A 2x2 image: (0,0) red, (1,0) green, (0,1) blue, (1,1) a brown; row 0 at the top.
LightImage twoByTwo() {
    LightImage image;
    image.width = 2;
    image.height = 2;
    image.rgba = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 200, 100, 50, 255};
    return image;
}

TEST(BounceLights, ColorIsTextureTimesLuxel) {
    const LightImage image = twoByTwo();
    const Vec3 luxel{128, 64, 255};
    // Texel x = int(2 * s + 0.5) mod 2: s = 0 picks column 0, s = 0.5 column 1 (same for t).
    struct Case {
        float s, t;
        Vec3 texel;
    };
    const Case cases[] = {{0.0f, 0.0f, {255, 0, 0}},
                          {0.5f, 0.0f, {0, 255, 0}},
                          {0.0f, 0.5f, {0, 0, 255}},
                          {0.5f, 0.5f, {200, 100, 50}}};
    for (const Case& c : cases) {
        BounceSurface s = squareSurface(64, 8, luxel);
        s.image = &image;
        test::setUniformSt(s, c.s, c.t);
        const std::vector<Light> lights = lightsOf(s);
        const Vec3 expected = c.texel / 255.0f * (luxel / 255.0f);
        if (length(expected) < kBounceMinColor) {
            EXPECT_TRUE(lights.empty());
            continue;
        }
        ASSERT_EQ(lights.size(), 2u) << "texel at st " << c.s << " " << c.t;
        for (const Light& l : lights) expectColorNear(l.color, expected, 1e-5f);
    }
}

TEST(BounceLights, AverageColorStandsInForMissingImage) {
    BounceSurface s = squareSurface(64, 8, Vec3{255, 128, 64});
    s.averageColor = {0.5f, 1.0f, 0.25f};
    const std::vector<Light> lights = lightsOf(s);
    ASSERT_EQ(lights.size(), 2u);
    for (const Light& l : lights)
        expectColorNear(l.color, Vec3{0.5f, 1.0f, 0.25f} * (Vec3{255, 128, 64} / 255.0f), 1e-5f);
}

TEST(BounceLights, ColorRatioMixesTextureTowardsGrey) {
    const LightImage image = twoByTwo();
    BounceSurface s = squareSurface(64, 8, Vec3::splat(kWhite));
    s.image = &image;
    test::setUniformSt(s, 0.5f, 0.5f);  // the (200, 100, 50) texel
    const float grey = (200.0f + 100.0f + 50.0f) / 3.0f;

    BounceSettings settings;
    settings.colorRatio = 0;
    std::vector<Light> lights = lightsOf(s, settings);
    ASSERT_EQ(lights.size(), 2u);
    for (const Light& l : lights) expectColorNear(l.color, Vec3::splat(grey / 255.0f), 1e-5f);

    settings.colorRatio = 0.25f;
    lights = lightsOf(s, settings);
    ASSERT_EQ(lights.size(), 2u);
    const Vec3 mixed = Vec3{200, 100, 50} * 0.25f + Vec3::splat(grey * 0.75f);
    for (const Light& l : lights) expectColorNear(l.color, mixed / 255.0f, 1e-5f);
}

// Point-in-convex-polygon in the z = 0 plane (either winding order).
bool windingContains(const std::vector<Vec3>& w, float x, float y) {
    int sign = 0;
    for (size_t i = 0; i < w.size(); ++i) {
        const Vec3& a = w[i];
        const Vec3& b = w[(i + 1) % w.size()];
        const float c = (b.x - a.x) * (y - a.y) - (b.y - a.y) * (x - a.x);
        if (std::fabs(c) < 1e-6f) continue;
        const int s = c > 0 ? 1 : -1;
        if (sign != 0 && s != sign) return false;
        sign = s;
    }
    return true;
}

TEST(BounceLights, SharpGradientChopsDownTo64ButNotBelow) {
    // One luxel per unit: bright (255) for x < 100, dim (20) elsewhere; the gradient across the
    // edge is (1 - 20/255) * 1 > 0.75.
    const BounceSurface s =
        squareSurface(512, 512, Vec3::splat(kWhite), [](int x, int) { return Vec3::splat(x < 100 ? 255.0f : 20.0f); });
    const std::vector<Light> lights = lightsOf(s);
    ASSERT_FALSE(lights.empty());
    EXPECT_NEAR(totalArea(lights), 512.0f * 512.0f, 1.0f);

    int finePieces = 0;
    for (const Light& l : lights) {
        const Bounds b = lightBounds(l);
        EXPECT_GE(maxExtent(l), 64.0f - 0.5f) << "chopped below the 64-unit minimum";
        if (maxExtent(l) <= 64.0f + 0.5f) ++finePieces;
        // Far from the edge the light is uniform: the pieces keep the 256 chop.
        if (b.mins.x >= 256.0f - 0.5f) {
            EXPECT_GE(maxExtent(l), 256.0f - 0.5f);
        }
    }
    EXPECT_GT(finePieces, 0);
    // The piece that holds a point just across the edge was re-chopped to 64.
    int holders = 0;
    for (const Light& l : lights) {
        if (!windingContains(l.winding, 101.0f, 10.0f)) continue;
        ++holders;
        EXPECT_LE(maxExtent(l), 64.0f + 0.5f);
    }
    EXPECT_EQ(holders, 1);
}

TEST(BounceLights, SamplingStopsAt150LitSamples) {
    // A square piece is sampled as the fan triangles (0,1,2) then (0,2,3), 125 points each, until
    // 150 lit samples: all 125 of the first (lit white, below the diagonal) and 25 of the second
    // (black, above it). Points lie at least 64/7 units off the diagonal.
    const BounceSurface s =
        squareSurface(64, 64, Vec3{}, [](int x, int y) { return x > y ? Vec3::splat(255.0f) : Vec3{}; });
    std::vector<BouncePieceVertex> piece;
    for (const BounceVertex& v : s.verts) piece.push_back({v, Vec3{}});
    const BounceSample sample = sampleBouncePiece(s, piece, 1.0f);
    EXPECT_EQ(sample.samples, kBounceMaxSamples);
    expectColorNear(sample.color, Vec3::splat(125.0f / 150.0f), 1e-5f);
    expectColorNear(sample.gradient, Vec3::splat(1.0f), 1e-6f);

    // A triangle has only its own 125 points.
    piece.pop_back();
    const BounceSample triangle = sampleBouncePiece(s, piece, 1.0f);
    EXPECT_EQ(triangle.samples, 125);
    expectColorNear(triangle.color, Vec3::splat(1.0f), 1e-5f);
    expectColorNear(triangle.gradient, Vec3{}, 1e-6f);
}

TEST(BounceLights, UniformLightIsNotRechopped) {
    // The same square with one dim luxel value everywhere keeps the 6 pieces of the 256 chop.
    const BounceSurface s = squareSurface(512, 512, Vec3::splat(20.0f));
    EXPECT_EQ(lightsOf(s).size(), 6u);
}

TEST(BounceLights, UnlitLuxelsAreSkipped) {
    // Left half lit white, right half black but marked unlit: the colour is that of the lit half.
    BounceSurface s = squareSurface(64, 8, Vec3::splat(kWhite), [](int x, int) {
        return x < 4 ? Vec3::splat(255.0f) : Vec3{};
    });
    s.lit.resize(s.luxels.size());
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) s.lit[static_cast<size_t>(y * 8 + x)] = x < 4 ? 1 : 0;
    std::vector<Light> lights = lightsOf(s);
    ASSERT_EQ(lights.size(), 2u);
    for (const Light& l : lights) expectColorNear(l.color, {1, 1, 1}, 1e-5f);

    // q3map2's own mark, a negative luxel, is skipped the same way.
    BounceSurface negative = squareSurface(64, 8, Vec3::splat(kWhite), [](int x, int) {
        return x < 4 ? Vec3::splat(255.0f) : Vec3::splat(-1.0f);
    });
    lights = lightsOf(negative);
    ASSERT_EQ(lights.size(), 2u);
    for (const Light& l : lights) expectColorNear(l.color, {1, 1, 1}, 1e-5f);

    // Nothing lit: no samples, no emitter.
    std::fill(s.lit.begin(), s.lit.end(), uint8_t{0});
    EXPECT_TRUE(lightsOf(s).empty());
}

TEST(BounceLights, ExcludedShadersEmitNothing) {
    const BounceSurface base = squareSurface(64, 8, Vec3::splat(kWhite));
    ASSERT_EQ(lightsOf(base).size(), 2u);
    const auto excluded = [&](void (*mark)(LightingShader&)) {
        LightingShader shader;
        mark(shader);
        BounceSurface s = base;
        s.shader = &shader;
        return lightsOf(s).empty();
    };
    EXPECT_TRUE(excluded([](LightingShader& sh) { sh.sky = true; }));
    EXPECT_TRUE(excluded([](LightingShader& sh) { sh.nodraw = true; }));
    EXPECT_TRUE(excluded([](LightingShader& sh) { sh.translucent = true; }));
    EXPECT_TRUE(excluded([](LightingShader& sh) { sh.autosprite = true; }));
    EXPECT_FALSE(excluded([](LightingShader&) {}));

    BounceSurface zeroScale = base;
    zeroScale.shaderBounceScale = 0;
    EXPECT_TRUE(lightsOf(zeroScale).empty());
    zeroScale.shaderBounceScale = -1;
    EXPECT_TRUE(lightsOf(zeroScale).empty());
    EXPECT_FALSE(surfaceBounces(nullptr, 0));
    EXPECT_TRUE(surfaceBounces(nullptr, 0.5f));
}

TEST(BounceLights, CullNoneAndFogAreTwoSided) {
    for (int which = 0; which < 2; ++which) {
        LightingShader shader;
        (which == 0 ? shader.twoSided : shader.fog) = true;
        BounceSurface s = squareSurface(64, 8, Vec3::splat(kWhite));
        s.shader = &shader;
        const std::vector<Light> lights = lightsOf(s);
        ASSERT_EQ(lights.size(), 2u);
        for (const Light& l : lights) EXPECT_TRUE(l.twoSided);
    }
}

TEST(BounceLights, StyleIsPassedThrough) {
    BounceSurface s = squareSurface(64, 8, Vec3::splat(kWhite));
    s.style = 5;
    for (const Light& l : lightsOf(s)) EXPECT_EQ(l.style, 5);
    BounceSettings settings;
    settings.noStyles = true;
    for (const Light& l : lightsOf(s, settings)) EXPECT_EQ(l.style, 0);
    s.style = 255;  // LS_NONE is no style to light
    for (const Light& l : lightsOf(s)) EXPECT_EQ(l.style, 0);
    s.style = 254;
    for (const Light& l : lightsOf(s)) EXPECT_EQ(l.style, 254);
}

TEST(BounceLights, DarkSurfaceEmitsNothing) {
    EXPECT_TRUE(lightsOf(squareSurface(64, 8, Vec3{})).empty());
    // Below q3map2's 0.0001 colour floor: 0.001 / 255 * sqrt(3) is about 7e-6.
    EXPECT_TRUE(lightsOf(squareSurface(64, 8, Vec3::splat(0.001f))).empty());
}

TEST(BounceLights, TinyPiecesAreDropped) {
    // A triangle of area 0.5 is under q3map2's minimum emitter area of 1.
    BounceSurface s = squareSurface(1, 1, Vec3::splat(kWhite));
    EXPECT_TRUE(lightsOf(s).empty());
}

TEST(BounceLights, VertexLitSurfaceUsesVertexLight) {
    BounceSurface s = squareSurface(64, 8, Vec3{255, 128, 0});
    s.width = s.height = 0;
    s.luxels.clear();
    const std::vector<Light> lights = lightsOf(s);
    ASSERT_EQ(lights.size(), 2u);
    for (const Light& l : lights) expectColorNear(l.color, Vec3{255, 128, 0} / 255.0f, 1e-5f);

    // Without vertex light there is nothing to re-emit.
    s.vertexLight.clear();
    EXPECT_TRUE(lightsOf(s).empty());
}

TEST(BounceLights, VertexLightIsInterpolatedAtTheCuts) {
    // Vertex light falls linearly from 255 at x = 0 to 0 at x = 512, so a cut point at x carries
    // 255 * (1 - x / 512); a vertex-lit piece's colour is the mean over its points.
    BounceSurface s = squareSurface(512, 1, Vec3{});
    s.width = s.height = 0;
    s.luxels.clear();
    for (size_t i = 0; i < s.verts.size(); ++i) s.vertexLight[i] = Vec3::splat(255.0f * (1 - s.verts[i].xyz.x / 512));
    const std::vector<Light> lights = lightsOf(s);
    // Across a 256-wide piece the light spans at most 1 -> 0.5: gradient (1 - 0.5) * 1 = 0.5 < 0.75,
    // so the plain 256 chop's 6 pieces stay.
    ASSERT_EQ(lights.size(), 6u);
    EXPECT_NEAR(totalArea(lights), 512.0f * 512.0f, 1.0f);
    for (const Light& l : lights) {
        float expected = 0;
        for (const Vec3& p : l.winding) expected += 1 - p.x / 512;
        expected /= static_cast<float>(l.winding.size());
        expectColorNear(l.color, Vec3::splat(expected), 1e-4f);
    }
}

TEST(BounceLights, BrokenGeometryEmitsNothing) {
    BounceSurface nan = squareSurface(64, 8, Vec3::splat(kWhite));
    nan.verts[1].xyz.x = std::nanf("");
    // Only the triangle (0, 2, 3) without the broken vertex emits.
    const std::vector<Light> lights = lightsOf(nan);
    ASSERT_EQ(lights.size(), 1u);
    for (const Vec3& p : lights[0].winding) EXPECT_TRUE(isFinite(p));

    // A triangle far beyond any world is not chopped into billions of pieces.
    BounceSurface huge = squareSurface(1e9f, 8, Vec3::splat(kWhite));
    EXPECT_TRUE(lightsOf(huge).empty());
}

TEST(BounceLights, ZeroNormalsEmitNothing) {
    BounceSurface s = squareSurface(64, 8, Vec3::splat(kWhite));
    for (BounceVertex& v : s.verts) v.normal = {};
    EXPECT_TRUE(lightsOf(s).empty());
}

TEST(BounceLights, BadSurfacesAreRejected) {
    BounceSurface s = squareSurface(64, 8, Vec3::splat(kWhite));
    s.surfaceNum = 12;
    BounceSurface wrongLuxels = s;
    wrongLuxels.luxels.pop_back();
    EXPECT_THROW(lightsOf(wrongLuxels), CompileError);
    BounceSurface wrongIndex = s;
    wrongIndex.triangles[4] = 9;
    EXPECT_THROW(lightsOf(wrongIndex), CompileError);
    BounceSurface wrongVertexLight = s;
    wrongVertexLight.vertexLight.pop_back();
    EXPECT_THROW(lightsOf(wrongVertexLight), CompileError);
    BounceSurface wrongLit = s;
    wrongLit.lit.assign(3, 1);
    EXPECT_THROW(lightsOf(wrongLit), CompileError);
    try {
        lightsOf(wrongIndex);
    } catch (const CompileError& e) {
        EXPECT_NE(std::string(e.what()).find("surface 12"), std::string::npos);
    }
}

// Surfaces of varied size, light and position, stacked in z so their order shows in the output.
std::vector<BounceSurface> manySurfaces() {
    std::vector<BounceSurface> surfaces;
    for (int i = 0; i < 40; ++i) {
        const float size = 64.0f + 48.0f * static_cast<float>(i % 9);
        const int edge = 3 + i % 11;
        BounceSurface s = squareSurface(size, 32, Vec3::splat(kWhite), [edge, i](int x, int y) {
            return x < edge || y == i % 32 ? Vec3{255, 200, 150} : Vec3{10, 12, 14};
        });
        s.surfaceNum = i;
        s.style = i % 3;
        test::translate(s, {static_cast<float>(i) * 3.0f, 0, static_cast<float>(i) * 100.0f});
        surfaces.push_back(std::move(s));
    }
    return surfaces;
}

void expectSameLights(const std::vector<Light>& a, const std::vector<Light>& b) {
    ASSERT_EQ(a.size(), b.size());
    for (size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i].winding, b[i].winding) << i;
        EXPECT_EQ(a[i].origin, b[i].origin) << i;
        EXPECT_EQ(a[i].color, b[i].color) << i;
        EXPECT_EQ(a[i].photons, b[i].photons) << i;
        EXPECT_EQ(a[i].add, b[i].add) << i;
        EXPECT_EQ(a[i].style, b[i].style) << i;
    }
}

TEST(BounceLights, DeterministicAndInSurfaceOrder) {
    const std::vector<BounceSurface> surfaces = manySurfaces();
    const std::vector<Light> first = createBounceLights(surfaces, {});
    const std::vector<Light> second = createBounceLights(surfaces, {});
    ASSERT_GT(first.size(), surfaces.size());
    expectSameLights(first, second);

    // Surface by surface, one at a time, gives the same list in the same order.
    std::vector<Light> oneByOne;
    for (const BounceSurface& s : surfaces) {
        std::vector<Light> part = lightsOf(s);
        oneByOne.insert(oneByOne.end(), part.begin(), part.end());
    }
    expectSameLights(first, oneByOne);
    for (size_t i = 1; i < first.size(); ++i) EXPECT_LE(first[i - 1].origin.z, first[i].origin.z);

    // One worker thread gives the same list as many.
    std::vector<Light> single;
    tbb::task_arena arena(1);
    arena.execute([&] { single = createBounceLights(surfaces, {}); });
    expectSameLights(first, single);
}

TEST(BounceLights, DumpWritesQ3map2LightEntities) {
    Light light;
    light.type = LightType::Area;
    light.add = 140.625f;
    light.origin = {32.4f, -7.6f, 1.0f};
    light.color = {1.0f, 0.5f, 0.0625f};
    Light second = light;
    second.add = 2.9f;
    second.origin = {0, 0, 0};
    const std::vector<Light> lights{light, second};
    EXPECT_EQ(bounceLightsAsMap(lights),
              "{\n\"classname\" \"light\"\n\"light\" \"140\"\n\"origin\" \"32 -8 1\"\n\"_color\" \"1.000 0.500 0.062\"\n}\n"
              "{\n\"classname\" \"light\"\n\"light\" \"2\"\n\"origin\" \"0 0 0\"\n\"_color\" \"1.000 0.500 0.062\"\n}\n");
    EXPECT_EQ(bounceLightsAsMap({}), "");
}

}  // namespace
}  // namespace q3::light
