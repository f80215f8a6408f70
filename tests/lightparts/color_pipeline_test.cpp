#include <gtest/gtest.h>

#include <cmath>

#include "color_pipeline.h"

namespace q3::light {
namespace {

TEST(ColorPipeline, DefaultsTruncateAndClampPreservingHue) {
    ColorOptions o;
    EXPECT_EQ(colorToBytes({100.7f, 50.2f, 0.9f}, 1.0f, o), (Rgb8{100, 50, 0}));
    // 510 300 0 -> scaled by 255/510 = 0.5 -> 255 150 0
    EXPECT_EQ(colorToBytes({510.0f, 300.0f, 0.0f}, 1.0f, o), (Rgb8{255, 150, 0}));
    // Negative light clamps to zero.
    EXPECT_EQ(colorToBytes({-20.0f, 10.0f, 300.0f}, 1.0f, o), (Rgb8{0, 8, 255}));
}

TEST(ColorPipeline, ScaleAndCompensate) {
    ColorOptions o;
    EXPECT_EQ(colorToBytes({40, 80, 120}, 2.0f, o), (Rgb8{80, 160, 240}));
    // scale <= 0 means 1
    EXPECT_EQ(colorToBytes({40, 80, 120}, 0.0f, o), (Rgb8{40, 80, 120}));
    o.compensate = 4.0f;
    EXPECT_EQ(colorToBytes({40, 80, 120}, 1.0f, o), (Rgb8{10, 20, 30}));
    // q3map2 2.5.17n compensates before the hue-keeping clamp: 800 400 0 -> /4 -> 200 100 0, and
    // light up to 255 * compensate stays apart.
    EXPECT_EQ(colorToBytes({800, 400, 0}, 1.0f, o), (Rgb8{200, 100, 0}));
    o.compensate = 2.0f;
    EXPECT_EQ(colorToBytes({400, 200, 100}, 1.0f, o), (Rgb8{200, 100, 50}));
    EXPECT_EQ(colorToBytes({1020, 510, 0}, 1.0f, o), (Rgb8{255, 127, 0}));
}

TEST(ColorPipeline, BrightnessComesFirst) {
    ColorOptions o;
    o.brightness = 2.0f;
    o.gamma = 2.0f;
    // (2*64/255)^(1/2)*255 = sqrt(0.50196)*255 = 180.66
    EXPECT_EQ(colorToBytes({64, 0, 0}, 1.0f, o), (Rgb8{180, 0, 0}));
}

TEST(ColorPipeline, Gamma) {
    ColorOptions o;
    o.gamma = 2.2f;
    const float expected = std::pow(100.0f / 255.0f, 1.0f / 2.2f) * 255.0f;  // 166.63
    EXPECT_NEAR(colorToFloatBytes({100, 100, 100}, 1.0f, o).x, expected, 1e-3f);
    EXPECT_EQ(colorToBytes({100, 0, 255}, 1.0f, o)[0], 166);
    EXPECT_EQ(colorToBytes({100, 0, 255}, 1.0f, o)[2], 255);
}

TEST(ColorPipeline, Contrast) {
    EXPECT_FLOAT_EQ(contrastFactor(0.0f), 259.0f * 255.0f / (255.0f * 259.0f));
    EXPECT_NEAR(contrastFactor(128.0f), 259.0f * 383.0f / (255.0f * 131.0f), 1e-5f);
    ColorOptions o;
    o.contrast = 128.0f;
    const float f = contrastFactor(128.0f);  // 2.9696
    // 100 -> f*(100-128)+128 = 44.85 ; 20 -> negative -> 0 ; 150 -> 193.3
    Vec3 r = colorToFloatBytes({100, 20, 150}, 1.0f, o);
    EXPECT_NEAR(r.x, f * (100 - 128) + 128, 1e-3f);
    EXPECT_EQ(r.y, 0.0f);
    EXPECT_NEAR(r.z, f * (150 - 128) + 128, 1e-3f);
}

TEST(ColorPipeline, Exposure) {
    ColorOptions o;
    o.exposure = 200.0f;
    // max = 400 -> factor = (1-exp(-2))*255/400 = 0.551 ; 400 -> 220.49, 100 -> 55.12
    Vec3 r = colorToFloatBytes({400, 100, 0}, 1.0f, o);
    const float factor = (1.0f - std::exp(-2.0f)) * 255.0f / 400.0f;
    EXPECT_NEAR(r.x, 400 * factor, 1e-3f);
    EXPECT_NEAR(r.y, 100 * factor, 1e-3f);
    EXPECT_EQ(colorToBytes({400, 100, 0}, 1.0f, o), (Rgb8{220, 55, 0}));
    // Black stays black (no division by zero).
    EXPECT_EQ(colorToBytes({0, 0, 0}, 1.0f, o), (Rgb8{0, 0, 0}));
}

TEST(ColorPipeline, Saturation) {
    // Saturation 0 gives the luminance grey.
    Vec3 g = applySaturation({100, 50, 200}, 0.0f);
    const float lum = 0.3086f * 100 + 0.6094f * 50 + 0.0820f * 200;
    EXPECT_NEAR(g.x, lum, 1e-3f);
    EXPECT_NEAR(g.y, lum, 1e-3f);
    EXPECT_NEAR(g.z, lum, 1e-3f);
    // Saturation 1 is the identity, 2 pushes away from grey.
    Vec3 same = applySaturation({100, 50, 200}, 1.0f);
    EXPECT_NEAR(same.x, 100, 1e-4f);
    Vec3 more = applySaturation({100, 50, 200}, 2.0f);
    EXPECT_NEAR(more.x, 2 * 100 - lum, 1e-3f);
    ColorOptions o;
    o.saturation = 0.0f;
    EXPECT_EQ(colorToBytes({100, 50, 200}, 1.0f, o), (Rgb8{77, 77, 77}));  // lum = 77.69
}

TEST(ColorPipeline, OrderSaturationBeforeScaleAndClamp) {
    ColorOptions o;
    o.saturation = 0.0f;
    o.maxLight = 100.0f;
    // grey 77.69 * 2 = 155.4 -> clamped to 100
    EXPECT_EQ(colorToBytes({100, 50, 200}, 2.0f, o), (Rgb8{100, 100, 100}));
}

TEST(ColorPipeline, MaxLightClampKeepsRatio) {
    ColorOptions o;
    o.maxLight = 128.0f;
    EXPECT_EQ(colorToBytes({256, 128, 64}, 1.0f, o), (Rgb8{128, 64, 32}));
    EXPECT_EQ(colorToBytes({100, 20, 10}, 1.0f, o), (Rgb8{100, 20, 10}));
}

TEST(ColorPipeline, Srgb) {
    EXPECT_NEAR(linearToSrgb(0.5f), 0.7353569f, 1e-5f);
    EXPECT_NEAR(linearToSrgb(0.001f), 0.01292f, 1e-6f);
    ColorOptions o;
    o.sRGB = true;
    // 127.5/255 = 0.5 -> 0.73536*255 = 187.5 -> floor(+0.5) = 188
    EXPECT_EQ(colorToBytes({127.5f, 0, 255}, 1.0f, o), (Rgb8{188, 0, 255}));
}

}  // namespace
}  // namespace q3::light
