// Light contributions against the analytic formulas of q3map2 and of the controlled model.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "angle.h"
#include "bsp_tree.h"
#include "grid_encode.h"
#include "light_contribution.h"
#include "light_test_util.h"
#include "trace_scene.h"

namespace q3::light {
namespace {

using test::quad;
using test::squareEmitterLights;

Light pointLight(Vec3 origin, float intensity) {
    Light l;
    l.type = LightType::Point;
    l.origin = origin;
    l.photons = intensity * 7500.0f;
    return l;
}

SamplePoint floorSample(Vec3 p) { return SamplePoint{p, {0, 0, 1}, -1, false}; }

TEST(PointLight, InverseSquareWithAngle) {
    Light l = pointLight({0, 0, 100}, 300);
    LightingEnv env;
    auto c = lightToSample(l, floorSample({0, 0, 0}), env);
    ASSERT_TRUE(c);
    EXPECT_FLOAT_EQ(c->color.x, 2250000.0f / 10000.0f);
    EXPECT_EQ(c->direction, (Vec3{0, 0, 1}));

    auto off = lightToSample(l, floorSample({60, 0, 0}), env);
    ASSERT_TRUE(off);
    const float d2 = 60 * 60 + 100 * 100;
    const float cosine = 100 / std::sqrt(d2);
    EXPECT_NEAR(off->color.y, 2250000.0f / d2 * cosine, 1e-3);

    // Closer than 16 units: clamped distance.
    Light near = pointLight({0, 0, 4}, 1);
    auto n = lightToSample(near, floorSample({0, 0, 0}), env);
    ASSERT_TRUE(n);
    EXPECT_FLOAT_EQ(n->color.x, 7500.0f / 256.0f);

    // Behind the surface: nothing.
    EXPECT_FALSE(lightToSample(pointLight({0, 0, -100}, 300), floorSample({0, 0, 0}), env));
}

TEST(PointLight, ExtraDistAndAngleScaleAndColor) {
    Light l = pointLight({0, 0, 100}, 300);
    l.extraDist = 50;
    l.color = {1, 0.5f, 0};
    l.style = 3;
    LightingEnv env;
    auto c = lightToSample(l, floorSample({0, 0, 0}), env);
    ASSERT_TRUE(c);
    EXPECT_FLOAT_EQ(c->color.x, 2250000.0f / (100 * 100 + 50 * 50));
    EXPECT_FLOAT_EQ(c->color.y, c->color.x * 0.5f);
    EXPECT_EQ(c->color.z, 0);
    EXPECT_EQ(c->style, 3);

    Light a = pointLight({100, 0, 100}, 300);
    a.angleScale = 0.5f;  // angle = min(1, cos/0.5) = 1 at 45 degrees
    auto s = lightToSample(a, floorSample({0, 0, 0}), env);
    ASSERT_TRUE(s);
    EXPECT_NEAR(s->color.x, 2250000.0f / 20000.0f, 1e-3);
}

TEST(PointLight, LinearFalloff) {
    Light l = pointLight({0, 0, 100}, 300);
    l.linear = true;
    l.angleAttenuation = false;
    l.fade = 1;
    LightingEnv env;
    auto c = lightToSample(l, floorSample({0, 0, 0}), env);
    ASSERT_TRUE(c);
    EXPECT_FLOAT_EQ(c->color.x, 2250000.0f / 8000.0f - 100.0f);
    l.fade = 2;
    c = lightToSample(l, floorSample({0, 0, 0}), env);
    ASSERT_TRUE(c);
    EXPECT_FLOAT_EQ(c->color.x, 2250000.0f / 8000.0f - 200.0f);
    // Beyond the point where the line reaches zero: nothing.
    EXPECT_FALSE(lightToSample(l, floorSample({0, 0, -100}), env));
}

TEST(PointLight, FastEnvelopeCutsBelowTolerance) {
    Light l = pointLight({0, 0, 0}, 1);  // photons 7500, envelope sqrt(7500) ~ 86.6
    l.fast = true;
    LightingEnv env;
    EXPECT_TRUE(lightToSample(l, SamplePoint{{0, 0, -80}, {0, 0, 1}}, env));
    EXPECT_FALSE(lightToSample(l, SamplePoint{{0, 0, -90}, {0, 0, 1}}, env));
    l.fast = false;
    EXPECT_TRUE(lightToSample(l, SamplePoint{{0, 0, -90}, {0, 0, 1}}, env));
}

TEST(SpotLight, ConeAndEdgeFade) {
    Light l = pointLight({0, 0, 100}, 300);
    l.type = LightType::Spot;
    l.normal = {0, 0, -1};
    l.radiusByDist = (64.0f + 16.0f) / 100.0f;  // radius 80 at the floor
    LightingEnv env;
    auto centre = lightToSample(l, floorSample({0, 0, 0}), env);
    ASSERT_TRUE(centre);
    EXPECT_FLOAT_EQ(centre->color.x, 225.0f);
    auto edge = lightToSample(l, floorSample({70, 0, 0}), env);
    ASSERT_TRUE(edge);
    const float d2 = 70 * 70 + 100 * 100;
    EXPECT_NEAR(edge->color.x, 2250000.0f / d2 * (100 / std::sqrt(d2)) * (80.0f - 70.0f) / 32.0f, 1e-3);
    EXPECT_FALSE(lightToSample(l, floorSample({90, 0, 0}), env));
}

TEST(Occlusion, WallBetweenLightAndFloor) {
    std::vector<SceneSurface> s{quad({-64, -64, 50}, {128, 0, 0}, {0, 128, 0})};
    TraceScene scene(s, {});
    LightingEnv env;
    env.scene = &scene;
    Light l = pointLight({0, 0, 100}, 300);
    EXPECT_FALSE(lightToSample(l, floorSample({0, 0, 0}), env));
    auto open = lightToSample(l, floorSample({200, 0, 0}), env);
    ASSERT_TRUE(open);
    const float d2 = 200 * 200 + 100 * 100;
    EXPECT_NEAR(open->color.x, 2250000.0f / d2 * (100 / std::sqrt(d2)), 1e-3);
}

TEST(Occlusion, AlphaGrateTintsPointLight) {
    LightImage img;
    img.width = img.height = 1;
    img.rgba = {255, 255, 255, 192};
    LightingShader grate;
    grate.alphaShadow = true;
    grate.translucent = true;
    grate.lightImage = &img;
    std::vector<SceneSurface> s{quad({-64, -64, 50}, {128, 0, 0}, {0, 128, 0}, &grate)};
    TraceScene scene(s, {});
    LightingEnv env;
    env.scene = &scene;
    auto c = lightToSample(pointLight({0, 0, 100}, 300), floorSample({0, 0, 0}), env);
    ASSERT_TRUE(c);
    EXPECT_NEAR(c->color.x, 225.0f * (255.0f - 192.0f) / 255.0f, 1e-3);
}

struct SkyBox {
    LightingShader skyShader;
    std::vector<SceneSurface> surfaces;
    SkyBox() {
        skyShader.sky = true;
        surfaces.push_back(quad({-4096, -4096, 1000}, {8192, 0, 0}, {0, 8192, 0}, &skyShader, 0));
    }
};

TEST(SunLight, ThroughSkyWithLambert) {
    SkyBox box;
    TraceScene scene(box.surfaces, {});
    LightingEnv env;
    env.scene = &scene;
    Light sun;
    sun.type = LightType::Sun;
    sun.normal = normalize(Vec3{1, 0, 1});
    sun.photons = 200;
    sun.color = {1, 0.8f, 0.6f};
    sun.skyIndex = 0;
    auto c = lightToSample(sun, floorSample({0, 0, 0}), env);
    ASSERT_TRUE(c);
    EXPECT_NEAR(c->color.x, 200.0f * std::sqrt(0.5f), 1e-3);
    EXPECT_NEAR(c->color.z, 200.0f * std::sqrt(0.5f) * 0.6f, 1e-3);
    EXPECT_EQ(c->direction, sun.normal);

    // Grid: no angle term.
    auto g = lightToGridPoint(sun, {0, 0, 0}, -1, env);
    ASSERT_TRUE(g);
    EXPECT_FLOAT_EQ(g->color.x, 200.0f);

    // Masked by the wrong sky.
    sun.skyIndex = 1;
    EXPECT_FALSE(lightToSample(sun, floorSample({0, 0, 0}), env));
    EXPECT_FALSE(lightToGridPoint(sun, {0, 0, 0}, -1, env));
    sun.skyIndex = -1;
    EXPECT_TRUE(lightToSample(sun, floorSample({0, 0, 0}), env));
}

TEST(SunLight, TwoSidedSurfacesAreLitFromBelow) {
    Light sun;
    sun.type = LightType::Sun;
    sun.normal = {0, 0, 1};
    sun.photons = 100;
    LightingEnv env;
    SamplePoint down{{0, 0, 0}, {0, 0, -1}, -1, false};
    EXPECT_FALSE(lightToSample(sun, down, env));
    down.twoSided = true;
    auto c = lightToSample(sun, down, env);
    ASSERT_TRUE(c);
    EXPECT_FLOAT_EQ(c->color.x, 100);
}

// Form factor of a differential area parallel to a rectangle, with the rectangle's corner above it.
double cornerFormFactor(double a, double b, double h) {
    const double x = a / h, y = b / h;
    return (x / std::sqrt(1 + x * x) * std::atan(y / std::sqrt(1 + x * x)) +
            y / std::sqrt(1 + y * y) * std::atan(x / std::sqrt(1 + y * y))) /
           (2 * kPiD);
}

TEST(AreaLight, EdgeAnglesMatchAtan2OverTheHalfCircle) {
    double worst = 0;
    for (int i = 0; i <= 20000; ++i) {
        const double theta = kPiD * i / 20000.0;
        const float y = float(std::sin(theta)), x = float(std::cos(theta));
        const double exact = std::atan2(double(y), double(x));
        const double got = atan2NonNegative(y, x);
        worst = std::max(worst, std::fabs(got - exact) / std::max(exact, 1e-3));
    }
    EXPECT_LT(worst, 1e-6);
    EXPECT_EQ(atan2NonNegative(0, 0), 0.0f);
    EXPECT_FLOAT_EQ(atan2NonNegative(0, -2), float(kPiD));
    EXPECT_FLOAT_EQ(atan2NonNegative(3, 0), float(kPiD / 2));
    EXPECT_NEAR(atan2NonNegative(1e-6f, 1), 1e-6, 1e-12);  // small angles keep their precision
}

// A small emitter far away subtends edges of a few thousandths of a radian, where an acos of the
// cosine loses most digits: the form factor must still match the analytic value.
TEST(AreaLight, FarSmallEmitterFormFactorKeepsItsPrecision) {
    const float h = 4000;
    std::vector<Vec3> square{{-8, -8, h}, {-8, 8, h}, {8, 8, h}, {8, -8, h}};
    const double expected = 4 * cornerFormFactor(8, 8, h);
    const float ff = std::fabs(pointToPolygonFormFactor({0, 0, 0}, {0, 0, 1}, square));
    EXPECT_NEAR(ff / expected, 1.0, 2e-3) << ff << " vs " << expected;
}

// The -fast pre-test must never reject a pair the exact factor would keep: over random flat and
// bent polygons, points and normals the bound stays above |F|, and it is tight enough to matter
// far from the emitter.
TEST(AreaLight, FormFactorUpperBoundHoldsAndIsUseful) {
    std::mt19937 rng(12345);
    std::uniform_real_distribution<float> unit(-1, 1);
    auto randomUnit = [&] {
        for (;;) {
            const Vec3 v{unit(rng), unit(rng), unit(rng)};
            if (length(v) > 0.1f && length(v) <= 1) return normalize(v);
        }
    };
    int finite = 0;
    for (int trial = 0; trial < 20000; ++trial) {
        const int corners = 3 + trial % 4;
        const float size = 4 + 60 * (unit(rng) + 1);
        const bool bent = trial % 5 == 0;  // (triangles stay flat)
        std::vector<Vec3> winding;
        for (int i = 0; i < corners; ++i) {
            const float a = 2 * float(kPiD) * float(i) / float(corners);
            winding.push_back({size * std::cos(a), size * std::sin(a), bent ? size * 0.3f * unit(rng) : 0.0f});
        }
        const Vec3 point = Vec3{unit(rng), unit(rng), unit(rng)} * (size * 12);
        const Vec3 normal = randomUnit();
        const EmitterBounds bounds = emitterBounds(winding);
        if (!bent) {
            ASSERT_TRUE(bounds.flat);
        }
        const float exact = std::fabs(pointToPolygonFormFactor(point, normal, winding));
        const float bound = formFactorUpperBound(bounds, point, normal);
        ASSERT_GE(bound, exact) << "trial " << trial;
        finite += std::isfinite(bound);
    }
    EXPECT_GT(finite, 15000);

    // A 32-unit square seen edge-on from 1000 units: the bound is far below the head-on value.
    const std::vector<Vec3> square{{-16, -16, 0}, {16, -16, 0}, {16, 16, 0}, {-16, 16, 0}};
    const float edgeOn = formFactorUpperBound(emitterBounds(square), {1000, 0, 0}, {-1, 0, 0});
    const float headOn = formFactorUpperBound(emitterBounds(square), {0, 0, 1000}, {0, 0, -1});
    EXPECT_LT(edgeOn, headOn * 0.1f);
    EXPECT_GE(headOn, std::fabs(pointToPolygonFormFactor({0, 0, 1000}, {0, 0, -1}, square)));
    EXPECT_FALSE(std::isfinite(formFactorUpperBound(EmitterBounds{}, {0, 0, 1000}, {0, 0, -1})));
}

// The four-lane form factor must give the one-edge form's bits: random polygons of 3 to 70 corners
// (past 64 both take the one-edge path), near, far, in front and behind, plus edges seen end-on.
TEST(AreaLight, VectorFormFactorGivesTheScalarBits) {
    std::mt19937 rng(2718);
    std::uniform_real_distribution<float> unit(-1, 1);
    int nonZero = 0;
    for (int trial = 0; trial < 30000; ++trial) {
        const int corners = 3 + trial % 68;
        const float size = 1 + 200 * (unit(rng) + 1);
        std::vector<Vec3> winding;
        for (int i = 0; i < corners; ++i) {
            const float a = 2 * float(kPiD) * float(i) / float(corners);
            winding.push_back({size * std::cos(a), size * std::sin(a), trial % 3 == 0 ? size * 0.2f * unit(rng) : 0.0f});
        }
        Vec3 point = Vec3{unit(rng), unit(rng), unit(rng)} * (size * (trial % 7 == 0 ? 40.0f : 3.0f));
        if (trial % 11 == 0) point = winding[0] + (winding[1] - winding[0]) * 2.0f;  // on an edge's line
        const Vec3 normal = normalize(Vec3{unit(rng), unit(rng), unit(rng)} + Vec3{0, 0, 0.01f});
        const float vector = pointToPolygonFormFactor(point, normal, winding);
        const float scalar = pointToPolygonFormFactorScalar(point, normal, winding);
        uint32_t vb, sb;
        std::memcpy(&vb, &vector, 4);
        std::memcpy(&sb, &scalar, 4);
        ASSERT_EQ(vb, sb) << "trial " << trial << ": " << vector << " vs " << scalar;
        nonZero += scalar != 0;
    }
    EXPECT_GT(nonZero, 25000);
}

// The four-point form factor must give each point's one-point bits: random polygons of 3 to 70
// corners, four points each (near, far, on an edge's line, at a corner) with their own normals, and
// polygons wound twice round, whose totals pass 2 pi close under them (q3map2 then gives 0).
TEST(AreaLight, FourPointFormFactorGivesEachPointsBits) {
    std::mt19937 rng(1414);
    std::uniform_real_distribution<float> unit(-1, 1);
    int nonZero = 0, brokenNear = 0;
    for (int trial = 0; trial < 12000; ++trial) {
        const int corners = 3 + trial % 68;
        const bool twice = trial % 5 == 4;
        const float size = 1 + 200 * (unit(rng) + 1);
        std::vector<Vec3> winding;
        for (int i = 0; i < corners; ++i) {
            const float a = (twice ? 4 : 2) * float(kPiD) * float(i) / float(corners);
            const float z = trial % 3 == 0 ? size * 0.2f * unit(rng) : 0.0f;
            winding.push_back({size * std::cos(a), size * std::sin(a), z});
        }
        FormFactorPoints points;
        Vec3 at[4], normal[4];
        for (int l = 0; l < 4; ++l) {
            at[l] = Vec3{unit(rng), unit(rng), unit(rng)} * (size * ((trial + l) % 7 == 0 ? 40.0f : 3.0f));
            if (twice && l == 0) at[l] = Vec3{0, 0, size * 0.01f};
            if ((trial + l) % 11 == 0) at[l] = winding[0] + (winding[1] - winding[0]) * 2.0f;
            if ((trial + l) % 13 == 0) at[l] = winding[l % corners];
            normal[l] = normalize(Vec3{unit(rng), unit(rng), unit(rng)} + Vec3{0, 0, 0.01f});
            if (twice && l == 0) normal[l] = {0, 0, 1};
            points.x[l] = at[l].x, points.y[l] = at[l].y, points.z[l] = at[l].z;
            points.nx[l] = normal[l].x, points.ny[l] = normal[l].y, points.nz[l] = normal[l].z;
        }
        float four[4];
        pointToPolygonFormFactor4(points, winding, four);
        for (int l = 0; l < 4; ++l) {
            const float one = pointToPolygonFormFactorScalar(at[l], normal[l], winding);
            uint32_t fb, ob;
            std::memcpy(&fb, &four[l], 4);
            std::memcpy(&ob, &one, 4);
            ASSERT_EQ(fb, ob) << "trial " << trial << " lane " << l << ": " << four[l] << " vs " << one;
            nonZero += one != 0;
            brokenNear += twice && l == 0 && one == 0;
        }
    }
    EXPECT_GT(nonZero, 40000);
    EXPECT_GT(brokenNear, 1000);
}

TEST(AreaLight, FormFactorMatchesAnalyticSquare) {
    const float h = 100;
    std::vector<Vec3> square{{-50, -50, h}, {-50, 50, h}, {50, 50, h}, {50, -50, h}};
    const double expected = 4 * cornerFormFactor(50, 50, h);
    float ff = pointToPolygonFormFactor({0, 0, 0}, {0, 0, 1}, square);
    EXPECT_NEAR(std::fabs(ff), expected, 1e-4);

    // Off-centre: point under a corner of a 100 x 60 rectangle.
    std::vector<Vec3> rect{{0, 0, h}, {0, 60, h}, {100, 60, h}, {100, 0, h}};
    EXPECT_NEAR(std::fabs(pointToPolygonFormFactor({0, 0, 0}, {0, 0, 1}, rect)), cornerFormFactor(100, 60, h), 1e-4);
}

// The area lights of a square emitter of `surfaceLight` (no backsplash), `half` units from its
// centre to each side at height `h`, facing along z by `facing`.
TEST(AreaLight, ContributionFromSurfaceLight) {
    const float h = 100;
    const std::vector<Light> lights = squareEmitterLights(1000, 50, h, -1);
    ASSERT_EQ(lights.size(), 2u);  // one per triangle, no chopping at the default 999
    LightingEnv env;
    std::vector<LightContribution> out;
    gatherSampleLight(lights, floorSample({0, 0, 0}), env, out);
    ASSERT_EQ(out.size(), 2u);
    const double expected = 4 * cornerFormFactor(50, 50, h) * 1000 * 3 * 0.25;
    EXPECT_NEAR(out[0].color.x + out[1].color.x, expected, expected * 1e-4);

    // Grid point: the normal is the direction to each emitter's origin.
    out.clear();
    gatherGridLight(lights, {0, 0, 0}, -1, env, out);
    ASSERT_EQ(out.size(), 2u);
    for (const LightContribution& c : out) {
        const Light& l = lights[&c - out.data()];
        float ff = pointToPolygonFormFactor({0, 0, 0}, normalize(l.origin), l.winding);
        EXPECT_NEAR(c.color.x, std::fabs(ff) * 750.0f, 1e-3);
    }

    // -faster: inverse square with both cosines.
    env.settings.faster = true;
    auto f = lightToSample(lights[0], floorSample({0, 0, 0}), env);
    ASSERT_TRUE(f);
    const Vec3 to = lights[0].origin;
    const float d = length(to);
    const float cosines = (to.z / d) * (to.z / d);
    EXPECT_NEAR(f->color.x, lights[0].photons / (d * d) * cosines, 1e-2);

    // Behind the emitter: nothing.
    env.settings.faster = false;
    EXPECT_FALSE(lightToSample(lights[0], SamplePoint{{0, 0, 200}, {0, 0, -1}}, env));
}

// Random trials of the whole-box test against a small -fast emitter.
struct DarkBoxTrials {
    std::vector<Light> lights = squareEmitterLights(5000, 8, 0, 1);
    LightingEnv env;
    std::mt19937 rng;
    std::uniform_real_distribution<float> unit{-1, 1};
    explicit DarkBoxTrials(unsigned seed) : rng(seed) { env.settings.forceFast = true; }
    Vec3 randomVec3() { return {unit(rng), unit(rng), unit(rng)}; }
    // Probe k of a box: its 8 corners first, then points inside.
    Vec3 probe(const Bounds& box, int k) {
        if (k < 8)
            return {(k & 1) ? box.maxs.x : box.mins.x, (k & 2) ? box.maxs.y : box.mins.y, (k & 4) ? box.maxs.z : box.mins.z};
        return box.mins + (box.maxs - box.mins) * (randomVec3() * 0.5f + Vec3{0.5f, 0.5f, 0.5f});
    }
};

// A box the whole-box test calls dark holds no luxel or grid point that the light reaches: random
// boxes around a small -fast emitter, probed at their corners and inside, facing every way.
TEST(AreaLight, DarkBoxesHoldNoLitPoint) {
    DarkBoxTrials t(77);
    const std::vector<Light>& lights = t.lights;
    ASSERT_FALSE(lights.empty());
    LightingEnv& env = t.env;
    int dark = 0, lit = 0;
    for (int trial = 0; trial < 4000; ++trial) {
        const Light& light = lights[size_t(trial) % lights.size()];
        const Vec3 centre = t.randomVec3() * 400.0f;
        const Vec3 half = (t.randomVec3() + Vec3{1, 1, 1}) * 40.0f;
        const Bounds box{centre - half, centre + half};
        if (!areaLightSurelyDarkIn(light, box, env.settings)) {
            ++lit;
            continue;
        }
        ++dark;
        for (int k = 0; k < 24; ++k) {
            const Vec3 p = t.probe(box, k);
            const Vec3 normal = normalize(light.origin - p + t.randomVec3() * 100.0f);
            ASSERT_FALSE(lightToSample(light, SamplePoint{p, normal, -1, true}, env)) << trial << " " << k;
            ASSERT_FALSE(lightToGridPoint(light, p, -1, env)) << trial << " " << k;
        }
    }
    // Both answers occur, including boxes behind the emitter (one-sided).
    EXPECT_GT(dark, 500);
    EXPECT_GT(lit, 500);
    // The emitter's plane lies 1 unit out along its normal (+z); points more than 1 behind it are dark.
    EXPECT_TRUE(areaLightSurelyDarkIn(lights[0], Bounds{{-50, -50, -90}, {50, 50, -0.2f}}, env.settings));
    EXPECT_FALSE(areaLightSurelyDarkIn(lights[0], Bounds{{-50, -50, -90}, {50, 50, 0.5f}}, env.settings));
    // Just under 1 unit behind that plane, a point facing sideways is still lit.
    const Bounds thin{{20, -2, 0.1f}, {24, 2, 0.3f}};
    const Vec3 edge{22, 0, 0.2f};
    EXPECT_TRUE(lightToSample(lights[0], SamplePoint{edge, normalize(lights[0].origin - edge), -1, true}, env));
    EXPECT_FALSE(areaLightSurelyDarkIn(lights[0], thin, env.settings));
    env.settings.faster = true;  // -faster lights grid points behind emitters: no box is skipped
    EXPECT_FALSE(areaLightSurelyDarkIn(lights[0], Bounds{{-50, -50, -90}, {50, 50, -0.2f}}, env.settings));
}

// With the normal that every sample of the box shares, the whole-box test also bounds the
// receiver's cosine: it calls more boxes dark, and still none that holds a lit sample of that normal.
TEST(AreaLight, DarkBoxesWithOneNormalHoldNoLitSample) {
    DarkBoxTrials t(78);
    const std::vector<Light>& lights = t.lights;
    ASSERT_FALSE(lights.empty());
    const LightingEnv& env = t.env;
    int darkWithNormal = 0, darkWithout = 0;
    for (int trial = 0; trial < 4000; ++trial) {
        const Light& light = lights[size_t(trial) % lights.size()];
        const Vec3 centre = t.randomVec3() * 300.0f;
        // Flat boxes, as a tile of one planar lightmap is, and some thick ones.
        Vec3 half = (t.randomVec3() + Vec3{1, 1, 1}) * 30.0f;
        half[size_t(trial % 3)] *= trial % 2 ? 0.01f : 1.0f;
        const Bounds box{centre - half, centre + half};
        const Vec3 normal = normalize(t.randomVec3() + Vec3{0, 0, 0.01f});
        if (areaLightSurelyDarkIn(light, box, env.settings)) ++darkWithout;
        if (!areaLightSurelyDarkIn(light, box, env.settings, &normal)) continue;
        ++darkWithNormal;
        for (int k = 0; k < 24; ++k) {
            const Vec3 p = t.probe(box, k);
            ASSERT_FALSE(lightToSample(light, SamplePoint{p, normal, -1, true}, env)) << trial << " " << k;
        }
    }
    EXPECT_GT(darkWithNormal, darkWithout + 100);
    // A strip of wall off to the side of the emitter, facing along it: its samples see the
    // emitter nearly edge-on, which only the receiver's cosine tells.
    const Bounds wall{{90, -2, 10}, {90.5f, 2, 20}};
    const Vec3 along{0, 1, 0};
    EXPECT_FALSE(areaLightSurelyDarkIn(lights[0], wall, env.settings));
    EXPECT_TRUE(areaLightSurelyDarkIn(lights[0], wall, env.settings, &along));
}

TEST(GridPoint, PointLightHasNoAngleTerm) {
    Light l = pointLight({100, 0, 0}, 300);
    LightingEnv env;
    auto g = lightToGridPoint(l, {0, 0, 0}, -1, env);
    ASSERT_TRUE(g);
    EXPECT_FLOAT_EQ(g->color.x, 225.0f);
    EXPECT_EQ(g->direction, (Vec3{1, 0, 0}));
    l.affectsGrid = false;
    EXPECT_FALSE(lightToGridPoint(l, {0, 0, 0}, -1, env));
    l.affectsGrid = true;
    l.affectsSurfaces = false;
    EXPECT_FALSE(lightToSample(l, floorSample({0, 0, 0}), env));
    EXPECT_TRUE(lightToGridPoint(l, {0, 0, 0}, -1, env));
}

TEST(GridPoint, LightOnThePointGoesToTheAmbient) {
    // q3map2 normalises the zero vector to zero: a light on the grid point (oacmpdm3 has a row of
    // them) adds nothing to the main direction and a quarter of its light to the ambient.
    LightingEnv env;
    auto on = lightToGridPoint(pointLight({0, 0, 0}, 300), {0, 0, 0}, -1, env);
    ASSERT_TRUE(on);
    EXPECT_EQ(on->direction, (Vec3{}));
    EXPECT_FLOAT_EQ(on->color.x, 300 * 7500.0f / (16 * 16));  // distance clamped to 16
    auto beside = lightToGridPoint(pointLight({100, 0, 0}, 300), {0, 0, 0}, -1, env);
    ASSERT_TRUE(beside);
    const std::vector<LightContribution> both{*on, *beside};
    const GridSample sample = accumulateGridSample(both, {}, GridOptions{});
    EXPECT_EQ(sample.direction, (Vec3{1, 0, 0}));
    EXPECT_FLOAT_EQ(sample.directed.x, 225.0f);
    EXPECT_FLOAT_EQ(sample.ambient.x, 0.25f * on->color.x);
}

TEST(GridPoint, NearOccludersAreNotIgnored) {
    std::vector<SceneSurface> s{quad({-64, -64, 2}, {128, 0, 0}, {0, 128, 0})};
    TraceScene scene(s, {});
    LightingEnv env;
    env.scene = &scene;
    EXPECT_FALSE(lightToGridPoint(pointLight({0, 0, 100}, 300), {0, 0, 0}, -1, env));
}

TEST(GridPoint, InhibitRadiusIgnoresNearOccludersOnly) {
    // q3map2's grid ignores surfaces closer to the point than its inhibit radius (half the largest
    // cell side, 64 units for the default 64 x 64 x 128 grid) and stops at those farther away.
    std::vector<SceneSurface> s{quad({-64, -64, 30}, {128, 0, 0}, {0, 128, 0})};
    TraceScene scene(s, {});
    LightingEnv env;
    env.scene = &scene;
    env.settings.ignoreNear = 64;
    EXPECT_TRUE(lightToGridPoint(pointLight({0, 0, 100}, 300), {0, 0, 0}, -1, env));
    EXPECT_FALSE(lightToGridPoint(pointLight({0, 0, 100}, 300), {0, 0, -40}, -1, env));  // 70 units away
    env.settings.ignoreNear = 0;
    EXPECT_FALSE(lightToGridPoint(pointLight({0, 0, 100}, 300), {0, 0, 0}, -1, env));
}

TEST(GridPoint, StructuralSolidBlocksWithinTheInhibitRadius) {
    // A structural slab (z 40..60, a leaf outside every cluster) with no surface in the scene, as a
    // caulked brush has none: it blocks only when solid leaves are tested, whatever the radius.
    bsp::Bsp b;
    b.planes = {{{0, 0, 1}, 40}, {{0, 0, 1}, 60}};
    b.nodes = {{0, {1, -1}, {-1000, -1000, -1000}, {1000, 1000, 1000}},
               {1, {-3, -2}, {-1000, -1000, 40}, {1000, 1000, 1000}}};
    b.leafs = {{0, 0, {-1000, -1000, -1000}, {1000, 1000, 40}, 0, 0, 0, 0},
               {-1, 0, {-1000, -1000, 40}, {1000, 1000, 60}, 0, 0, 0, 0},
               {1, 0, {-1000, -1000, 60}, {1000, 1000, 1000}, 0, 0, 0, 0}};
    const BspTree tree(b);
    std::vector<SceneSurface> none;
    TraceScene plain(none, {});
    LightingEnv env;
    env.scene = &plain;
    env.tree = &tree;
    env.settings.ignoreNear = 64;
    EXPECT_TRUE(lightToGridPoint(pointLight({0, 0, 100}, 300), {0, 0, 0}, -1, env));
    TraceSceneOptions options;
    options.solidBetween = [&tree](Vec3 from, Vec3 to) { return tree.segmentCrossesSolid(from, to); };
    TraceScene withTree(none, options);
    env.scene = &withTree;
    EXPECT_FALSE(lightToGridPoint(pointLight({0, 0, 100}, 300), {0, 0, 0}, -1, env));
    EXPECT_FALSE(lightToGridPoint(pointLight({0, 0, 62}, 300), {0, 0, 58}, -1, env));  // shorter than the radius
    EXPECT_TRUE(lightToGridPoint(pointLight({100, 0, 20}, 300), {0, 0, 0}, -1, env));  // beside the slab
    std::vector<ShadowRay> deferred;
    env.deferredRays = &deferred;  // batched: the scene applies the same test
    ASSERT_TRUE(lightToGridPoint(pointLight({0, 0, 100}, 300), {0, 0, 0}, -1, env));
    ASSERT_EQ(deferred.size(), 1u);
    std::vector<Vec3> out(1);
    withTree.traceBatch(deferred, out);
    EXPECT_EQ(out[0], Vec3{});
    env.deferredRays = nullptr;
    env.scene = nullptr;  // -notrace: nothing blocks
    EXPECT_TRUE(lightToGridPoint(pointLight({0, 0, 100}, 300), {0, 0, 0}, -1, env));
}

TEST(SunOnly, SkipsEverythingButSuns) {
    LightingEnv env;
    env.settings.sunOnly = true;
    EXPECT_FALSE(lightToSample(pointLight({0, 0, 100}, 300), floorSample({0, 0, 0}), env));
    Light sun;
    sun.type = LightType::Sun;
    sun.normal = {0, 0, 1};
    sun.photons = 10;
    EXPECT_TRUE(lightToSample(sun, floorSample({0, 0, 0}), env));
}

// Controlled model ----------------------------------------------------------------------------

Light controlledLight(Vec3 origin, ControlledParams p) {
    Light l;
    l.type = LightType::Point;
    l.origin = origin;
    l.controlled = p;
    return l;
}

TEST(ControlledModel, FalloffCurve) {
    ControlledParams p;
    p.falloffStart = 50;
    p.falloffEnd = 250;
    p.falloffCurvature = 0;
    EXPECT_FLOAT_EQ(controlledFalloff(p, 40), 1);
    EXPECT_FLOAT_EQ(controlledFalloff(p, 150), 0.5f);
    EXPECT_FLOAT_EQ(controlledFalloff(p, 250), 0);
    p.falloffCurvature = 1;
    const float s2 = 50 * 50, e2 = 250 * 250;
    EXPECT_NEAR(controlledFalloff(p, 100), (s2 / (100 * 100) - s2 / e2) / (1 - s2 / e2), 1e-6);
    p.falloffCurvature = 0.25f;
    p.falloffStart = 0;  // inverse-square part uses s = 16
    const float lin = 1 - 100.0f / 250.0f;
    const float isq = (256.0f / 10000.0f - 256.0f / e2) / (1 - 256.0f / e2);
    EXPECT_NEAR(controlledFalloff(p, 100), 0.75f * lin + 0.25f * isq, 1e-6);
}

TEST(ControlledModel, IncidenceAndValue) {
    ControlledParams p;
    p.brightness = 0.5f;
    p.falloffStart = 1000;
    p.falloffEnd = 2000;
    p.dotProductWeight = 0.4f;
    Light l = controlledLight({100, 0, 100}, p);
    l.color = {1, 0.5f, 0};
    LightingEnv env;
    auto c = lightToSample(l, floorSample({0, 0, 0}), env);
    ASSERT_TRUE(c);
    const float incidence = 0.6f + 0.4f * std::sqrt(0.5f);
    EXPECT_NEAR(c->color.x, 255.0f * 0.5f * incidence, 1e-3);
    EXPECT_NEAR(c->color.y, 255.0f * 0.5f * 0.5f * incidence, 1e-3);
    // Never lit from behind, whatever the weight.
    p.dotProductWeight = 0;
    Light behind = controlledLight({0, 0, -50}, p);
    EXPECT_FALSE(lightToSample(behind, floorSample({0, 0, 0}), env));
    // Beyond falloff_end_dist: culled.
    p.falloffEnd = 1200;
    EXPECT_FALSE(lightToSample(controlledLight({0, 0, 1300}, p), floorSample({0, 0, 0}), env));
    // Negative brightness subtracts light.
    p.brightness = -1;
    auto neg = lightToSample(controlledLight({0, 0, 100}, p), floorSample({0, 0, 0}), env);
    ASSERT_TRUE(neg);
    EXPECT_FLOAT_EQ(neg->color.x, -255.0f);
}

TEST(ControlledModel, SpotCone) {
    ControlledParams p;
    p.falloffStart = 1000;
    p.falloffEnd = 2000;
    p.angleHotspot = 40;
    p.anglePenumbra = 80;
    p.dotProductWeight = 0;
    const Vec3 axis{0, 0, -1};
    auto at = [](float deg) { return Vec3{-std::sin(degToRad(deg)), 0, std::cos(degToRad(deg))}; };
    EXPECT_FLOAT_EQ(controlledCone(p, axis, at(10)), 1);
    EXPECT_NEAR(controlledCone(p, axis, at(30)), 0.5f, 1e-4);
    EXPECT_FLOAT_EQ(controlledCone(p, axis, at(50)), 0);
    p.sphericalAmbient = 0.2f;
    EXPECT_NEAR(controlledCone(p, axis, at(30)), 0.2f + 0.8f * 0.5f, 1e-4);
    EXPECT_NEAR(controlledCone(p, axis, at(90)), 0.2f, 1e-6);

    Light spot = controlledLight({0, 0, 100}, p);
    spot.type = LightType::Spot;
    spot.normal = axis;
    LightingEnv env;
    const float x = 100 * std::tan(degToRad(30));
    auto c = lightToSample(spot, floorSample({x, 0, 0}), env);
    ASSERT_TRUE(c);
    EXPECT_NEAR(c->color.x, 255.0f * (0.2f + 0.8f * 0.5f), 0.05f);
    // Grid: K without incidence.
    auto g = lightToGridPoint(spot, {x, 0, 0}, -1, env);
    ASSERT_TRUE(g);
    EXPECT_NEAR(g->color.x, 255.0f * (0.2f + 0.8f * 0.5f), 0.05f);
}

TEST(ControlledModel, SunOnlyThroughSkyWithFullDotWeight) {
    SkyBox box;
    TraceScene scene(box.surfaces, {});
    LightingEnv env;
    env.scene = &scene;
    ControlledParams p;
    p.brightness = 0.8f;
    p.dotProductWeight = 0.1f;  // ignored: suns force 1
    Light sun = controlledLight({}, p);
    sun.type = LightType::Sun;
    sun.normal = normalize(Vec3{0, 1, 1});
    auto c = lightToSample(sun, floorSample({0, 0, 0}), env);
    ASSERT_TRUE(c);
    EXPECT_NEAR(c->color.x, 255.0f * 0.8f * std::sqrt(0.5f), 1e-3);
    // A roof in the way: no sun.
    box.surfaces.push_back(quad({-100, -100, 50}, {200, 0, 0}, {0, 400, 0}));
    TraceScene roofed(box.surfaces, {});
    env.scene = &roofed;
    EXPECT_FALSE(lightToSample(sun, floorSample({0, 0, 0}), env));
}

}  // namespace
}  // namespace q3::light
