#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "bspfile.h"
#include "grid_encode.h"
#include "log.h"
#include "test_data.h"

namespace q3::light {
namespace {

TEST(GridEncode, ParseGridSize) {
    EXPECT_EQ(parseGridSize("", "w"), (Vec3{64, 64, 128}));
    EXPECT_EQ(parseGridSize(" 32 48.5 96 ", "w"), (Vec3{32, 48.5f, 96}));
    EXPECT_THROW(parseGridSize("32 32", "test.bsp"), CompileError);
    EXPECT_THROW(parseGridSize("32 x 32", "test.bsp"), CompileError);
    EXPECT_THROW(parseGridSize("1 2 3 4", "test.bsp"), CompileError);
    try {
        parseGridSize("a b c", "maps/x.bsp");
        FAIL();
    } catch (const CompileError& e) {
        EXPECT_NE(std::string(e.what()).find("maps/x.bsp"), std::string::npos);
    }
}

TEST(GridEncode, LayoutFromBounds) {
    // mins: 64*ceil(-100/64) = -64, 64*ceil(-10/64) = 0, 128*ceil(5/128) = 128
    // maxs: 64*floor(300/64) = 256, 64*floor(70/64) = 64, 128*floor(600/128) = 512
    GridLayout g = computeGridLayout({64, 64, 128}, {-100, -10, 5}, {300, 70, 600});
    EXPECT_EQ(g.mins, (Vec3{-64, 0, 128}));
    EXPECT_EQ(g.bounds, (std::array<int, 3>{6, 2, 4}));
    EXPECT_EQ(g.numPoints(), 48);
    EXPECT_FALSE(g.sizeChanged());
    EXPECT_EQ(g.pointCoords(0), (std::array<int, 3>{0, 0, 0}));
    EXPECT_EQ(g.pointCoords(6 * 2 + 6 + 5), (std::array<int, 3>{5, 1, 1}));
    EXPECT_EQ(g.pointOrigin(6 * 2 + 6 + 5), (Vec3{-64 + 5 * 64, 64, 256}));
}

TEST(GridEncode, EmptyWorldHasNoPoints) {
    GridLayout g = computeGridLayout({64, 64, 128}, {10, 10, 10}, {-10, -10, -10});
    EXPECT_EQ(g.numPoints(), 0);
    EXPECT_EQ(computeGridLayout({64, 64, 128}, Bounds{}.mins, Bounds{}.maxs).numPoints(), 0);
}

TEST(GridEncode, SizeIsFlooredAndAtLeastEight) {
    GridLayout g = computeGridLayout({4, 33.7f, 64}, {0, 0, 0}, {64, 64, 64});
    EXPECT_EQ(g.size, (Vec3{8, 33, 64}));
    EXPECT_TRUE(g.sizeChanged());
    EXPECT_EQ(g.sizeKeyValue(), "8 33 64");
    EXPECT_EQ(g.bounds, (std::array<int, 3>{9, 2, 2}));  // 33*ceil(0)=0, 33*floor(64/33)=33
}

TEST(GridEncode, GrowsUntilUnderTheLimit) {
    // 8-unit cells over 1024^3 would be 129^3 = 2146689 points.
    GridLayout g = computeGridLayout({8, 8, 8}, {0, 0, 0}, {1024, 1024, 1024});
    // x grows first: 24 8 8 -> 43*129*129 = 715563 fits.
    EXPECT_EQ(g.size, (Vec3{24, 8, 8}));
    EXPECT_EQ(g.growSteps, 1);
    EXPECT_EQ(g.bounds, (std::array<int, 3>{43, 129, 129}));
    EXPECT_LE(g.numPoints(), kMaxGridPoints);
    EXPECT_EQ(g.sizeKeyValue(), "24 8 8");
    // Several rounds rotate x, y, z.
    GridLayout h = computeGridLayout({8, 8, 8}, {0, 0, 0}, {4096, 4096, 4096});
    EXPECT_LE(h.numPoints(), kMaxGridPoints);
    EXPECT_GE(h.growSteps, 3);
    const int full = h.growSteps / 3, extra = h.growSteps % 3;
    EXPECT_EQ(h.size.x, 8.0f + 16.0f * float(full + (extra > 0)));
    EXPECT_EQ(h.size.y, 8.0f + 16.0f * float(full + (extra > 1)));
    EXPECT_EQ(h.size.z, 8.0f + 16.0f * float(full));
}

TEST(GridEncode, SingleLightIsAllDirected) {
    LightContribution c{{100, 50, 25}, {0, 0, 1}, 0};
    GridSample s = accumulateGridSample(std::span(&c, 1), {0, 0, 0}, GridOptions{});
    EXPECT_EQ(s.directed, (Vec3{100, 50, 25}));
    EXPECT_EQ(s.ambient, (Vec3{0, 0, 0}));
    EXPECT_EQ(s.direction, (Vec3{0, 0, 1}));
    bsp::GridPoint p = encodeGridPoint(s, GridOptions{}, ColorOptions{});
    // Ambient bytes would be 0 while directed is not: forced to 1 1 1.
    EXPECT_EQ(p.ambient[0], 1);
    EXPECT_EQ(p.ambient[1], 1);
    EXPECT_EQ(p.ambient[2], 1);
    EXPECT_EQ(p.directed[0], 100);
    EXPECT_EQ(p.directed[1], 50);
    EXPECT_EQ(p.directed[2], 25);
    EXPECT_EQ(p.latLong[0], 0);
    EXPECT_EQ(p.latLong[1], 0);
}

TEST(GridEncode, TwoOpposedLightsSplitIntoAmbient) {
    // Equal lights from +x and +y: primary direction is the diagonal, cos = 0.7071 each.
    std::vector<LightContribution> cs = {{{100, 100, 100}, {1, 0, 0}, 0}, {{100, 100, 100}, {0, 1, 0}, 0}};
    GridSample s = accumulateGridSample(cs, {10, 10, 10}, GridOptions{});
    const float d = std::sqrt(0.5f);
    EXPECT_NEAR(s.direction.x, d, 1e-6f);
    EXPECT_NEAR(s.direction.y, d, 1e-6f);
    EXPECT_NEAR(s.directed.x, 200 * d, 1e-3f);
    EXPECT_NEAR(s.ambient.x, 10 + 2 * 0.25f * (1 - d) * 100, 1e-3f);

    // Directionality 0.5 and ambient directionality 0.2: d = 0.2 + cos*0.3
    GridOptions o;
    o.directionality = 0.5f;
    o.ambientDirectionality = 0.2f;
    GridSample t = accumulateGridSample(cs, {0, 0, 0}, o);
    const float w = 0.2f + d * 0.3f;
    EXPECT_NEAR(t.directed.y, 200 * w, 1e-3f);
    EXPECT_NEAR(t.ambient.y, 2 * 0.25f * (1 - w) * 100, 1e-3f);

    // A contribution opposite to the primary direction is clamped to d = 0.
    std::vector<LightContribution> opposed = {{{300, 300, 300}, {0, 0, 1}, 0}, {{100, 100, 100}, {0, 0, -1}, 0}};
    GridSample u = accumulateGridSample(opposed, {0, 0, 0}, GridOptions{});
    EXPECT_EQ(u.direction, (Vec3{0, 0, 1}));
    EXPECT_NEAR(u.directed.x, 300, 1e-4f);
    EXPECT_NEAR(u.ambient.x, 0.25f * 100, 1e-4f);
}

TEST(GridEncode, StylesBeyondFourFoldIntoStyleZero) {
    std::vector<LightContribution> cs = {
        {{10, 0, 0}, {0, 0, 1}, 1}, {{20, 0, 0}, {0, 0, 1}, 2}, {{40, 0, 0}, {0, 0, 1}, 3},
        {{80, 0, 0}, {0, 0, 1}, 4},  // fifth distinct style (0 is always slot 0) -> style 0
        {{5, 0, 0}, {0, 0, 1}, 0},
    };
    GridSample s = accumulateGridSample(cs, {0, 0, 0}, GridOptions{});
    EXPECT_NEAR(s.directed.x, 85, 1e-4f);  // 80 folded + 5
}

TEST(GridEncode, MinLightScalesAndNoLight) {
    GridOptions o;
    o.minLight = {20, 30, 40};
    o.scale = 2.0f;
    o.ambientScale = 0.5f;
    GridSample s{{25, 10, 0}, {50, 60, 70}, {1, 0, 0}};
    bsp::GridPoint p = encodeGridPoint(s, o, ColorOptions{});
    EXPECT_EQ(p.ambient[0], 25);  // max(25,20) * 2 * 0.5
    EXPECT_EQ(p.ambient[1], 30);
    EXPECT_EQ(p.ambient[2], 40);
    EXPECT_EQ(p.directed[0], 100);
    EXPECT_EQ(p.directed[1], 120);
    EXPECT_EQ(p.directed[2], 140);
    // Nothing at all: stays zero (the engine skips it), direction bytes of the zero vector.
    bsp::GridPoint dark = encodeGridPoint(accumulateGridSample({}, {0, 0, 0}, GridOptions{}), GridOptions{}, ColorOptions{});
    EXPECT_EQ(dark.ambient[0] + dark.ambient[1] + dark.ambient[2], 0);
    EXPECT_EQ(dark.latLong[0], 128);
    EXPECT_EQ(dark.latLong[1], 0);
}

TEST(GridEncode, LatLongBytes) {
    EXPECT_EQ(normalToLatLong({0, 0, 1}), (std::array<uint8_t, 2>{0, 0}));
    EXPECT_EQ(normalToLatLong({0, 0, -1}), (std::array<uint8_t, 2>{128, 0}));
    // +x: acos(0) = 90 deg -> 63.75 -> 63 ; atan2 = 0
    EXPECT_EQ(normalToLatLong({1, 0, 0}), (std::array<uint8_t, 2>{63, 0}));
    // +y: atan2 = 90 -> 63 ; -y: -90 -> -63 -> 193 ; -x: 180 -> 127
    EXPECT_EQ(normalToLatLong({0, 1, 0}), (std::array<uint8_t, 2>{63, 63}));
    EXPECT_EQ(normalToLatLong({0, -1, 0}), (std::array<uint8_t, 2>{63, 193}));
    EXPECT_EQ(normalToLatLong({-1, 0, 0}), (std::array<uint8_t, 2>{63, 127}));
    // Engine decode of exact bytes.
    Vec3 up = latLongToNormal({0, 0});
    EXPECT_NEAR(up.z, 1.0f, 1e-6f);
    Vec3 east = latLongToNormal({64, 0});  // lng 90 deg, lat 0
    EXPECT_NEAR(east.x, 1.0f, 1e-6f);
    EXPECT_NEAR(east.z, 0.0f, 1e-6f);
    Vec3 north = latLongToNormal({64, 64});
    EXPECT_NEAR(north.y, 1.0f, 1e-6f);
}

TEST(GridEncode, DirectionsRoundTripThroughTheEngineDecode) {
    // 255-vs-256 scale plus truncation: at most ~1.4 deg per angle plus 180/256 deg of scale error.
    const float maxError = std::cos(degToRad(3.0f));
    int tested = 0;
    for (int i = 0; i < 40; ++i) {
        for (int j = 0; j < 80; ++j) {
            const float theta = kPi * (float(i) + 0.5f) / 40.0f;
            const float phi = 2.0f * kPi * float(j) / 80.0f - kPi;
            const Vec3 n{std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
            const Vec3 back = latLongToNormal(normalToLatLong(n));
            EXPECT_GT(dot(n, back), maxError) << n.x << " " << n.y << " " << n.z;
            ++tested;
        }
    }
    EXPECT_EQ(tested, 3200);
}

}  // namespace
}  // namespace q3::light
