// The screenshot measures on pictures built here.
#include <gtest/gtest.h>

#include "engine_picture.h"

namespace q3::enginetest {
namespace {

Image filled(int w, int h, uint8_t r, uint8_t g, uint8_t b) {
    Image image;
    image.width = w;
    image.height = h;
    image.rgba.resize(size_t(w) * h * 4);
    for (size_t i = 0; i < image.rgba.size(); i += 4) {
        image.rgba[i] = r;
        image.rgba[i + 1] = g;
        image.rgba[i + 2] = b;
        image.rgba[i + 3] = 255;
    }
    return image;
}

TEST(EnginePicture, LumaAndLitShare) {
    const uint8_t white[3] = {255, 255, 255}, green[3] = {0, 255, 0};
    EXPECT_NEAR(luminance(white), 255.0, 1e-9);
    EXPECT_NEAR(luminance(green), 0.7152 * 255, 1e-9);

    const PictureStats black = pictureStats(filled(8, 4, 0, 0, 0));
    EXPECT_EQ(black.pixels, 32u);
    EXPECT_EQ(black.meanLuminance, 0);
    EXPECT_EQ(black.litFraction, 0);

    // Left half white, right half at the black level (still counted black).
    Image half = filled(8, 4, 8, 8, 8);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x)
            for (int c = 0; c < 3; ++c) half.texel(x, y)[c] = 255;
    const PictureStats stats = pictureStats(half);
    EXPECT_NEAR(stats.meanLuminance, (255.0 + 8.0) / 2, 1e-9);
    EXPECT_DOUBLE_EQ(stats.litFraction, 0.5);
    EXPECT_EQ(pictureStats(Image{}).pixels, 0u);
}

TEST(EnginePicture, DifferenceFindsTheModel) {
    const Image scene = filled(10, 10, 40, 40, 40);
    Image withModel = scene;
    for (int y = 2; y < 5; ++y)
        for (int x = 3; x < 5; ++x)
            for (int c = 0; c < 3; ++c) withModel.texel(x, y)[c] = 200;
    withModel.texel(0, 0)[0] = 50;  // rasteriser noise below the tolerance
    const std::vector<uint8_t> mask = differenceMask(scene, withModel, 16);
    const MaskedStats inModel = maskedStats(withModel, mask);
    EXPECT_EQ(inModel.pixels, 6u);
    EXPECT_NEAR(inModel.meanLuminance, 200.0, 1e-9);
    for (double channel : inModel.meanRgb) EXPECT_NEAR(channel, 200.0, 1e-9);
    EXPECT_NEAR(maskedStats(scene, mask).meanLuminance, 40.0, 1e-9);  // the same pixels without it
    EXPECT_EQ(maskedStats(scene, differenceMask(scene, scene, 0)).pixels, 0u);
    EXPECT_EQ(maskedStats(scene, differenceMask(scene, scene, 0)).meanLuminance, 0);
    EXPECT_THROW(differenceMask(scene, filled(10, 9, 0, 0, 0), 16), std::invalid_argument);
    EXPECT_THROW(maskedStats(filled(10, 9, 0, 0, 0), mask), std::invalid_argument);
}

TEST(EnginePicture, LumaShiftCountsBrighterAndDarkerPixels) {
    const Image before = filled(10, 10, 40, 40, 40);
    Image after = before;
    for (int x = 0; x < 10; ++x)
        for (int c = 0; c < 3; ++c) after.texel(x, 0)[c] = 60;  // a row 20 brighter
    for (int c = 0; c < 3; ++c) after.texel(0, 9)[c] = 30;       // one pixel 10 darker
    after.texel(5, 5)[1] = 41;                                   // noise within the tolerance
    const LumaShift shift = lumaShift(before, after, 2.0);
    EXPECT_EQ(shift.brighter, 10u);
    EXPECT_EQ(shift.darker, 1u);
    EXPECT_NEAR(shift.meanChange, (10 * 20.0 - 10.0 + 0.7152) / 100.0, 1e-9);
    const LumaShift reverse = lumaShift(after, before, 2.0);
    EXPECT_EQ(reverse.brighter, 1u);
    EXPECT_EQ(reverse.darker, 10u);
    EXPECT_EQ(lumaShift(before, before, 0.0).brighter, 0u);
    EXPECT_THROW(lumaShift(before, filled(9, 10, 0, 0, 0), 2.0), std::invalid_argument);
}

}  // namespace
}  // namespace q3::enginetest
