#include <gtest/gtest.h>

#include "image.h"
#include "image_builders.h"

namespace q3 {
namespace {

Image solid(int width, int height, std::array<uint8_t, 4> colour) {
    Image image;
    image.width = width;
    image.height = height;
    image.rgba.resize(size_t(width) * height * 4);
    for (size_t i = 0; i < image.rgba.size(); ++i) image.rgba[i] = colour[i % 4];
    return image;
}

// 4x1 with distinct texels: 0, 60, 120, 180 in red.
Image ramp() {
    Image image;
    image.width = 4;
    image.height = 1;
    image.rgba.resize(16);
    for (int x = 0; x < 4; ++x) {
        image.rgba[x * 4 + 0] = uint8_t(x * 60);
        image.rgba[x * 4 + 1] = 10;
        image.rgba[x * 4 + 2] = 20;
        image.rgba[x * 4 + 3] = 255;
    }
    return image;
}

TEST(AverageColor, MeanAndNormalisedLikeQ3map2) {
    Image image = solid(2, 1, {200, 100, 50, 255});
    image.rgba[4] = 100;  // second texel: 100,100,50, alpha 0
    image.rgba[7] = 0;
    const ImageAverage average = averageColor(image);
    EXPECT_FLOAT_EQ(average.mean[0], 150);
    EXPECT_FLOAT_EQ(average.mean[1], 100);
    EXPECT_FLOAT_EQ(average.mean[2], 50);
    EXPECT_FLOAT_EQ(average.mean[3], 127.5f);
    EXPECT_FLOAT_EQ(average.normalized[0], 1);
    EXPECT_FLOAT_EQ(average.normalized[1], 200.0f / 300.0f);
    EXPECT_FLOAT_EQ(average.normalized[2], 100.0f / 300.0f);
}

TEST(AverageColor, BlackNormalisesToWhite) {
    const ImageAverage average = averageColor(solid(3, 3, {0, 0, 0, 255}));
    EXPECT_FLOAT_EQ(average.mean[0], 0);
    EXPECT_FLOAT_EQ(average.mean[3], 255);
    EXPECT_EQ(average.normalized, (std::array<float, 3>{1, 1, 1}));
}

TEST(SampleNearest, FollowsRadSampleImageRounding) {
    const Image image = ramp();
    // x = int(4 * s + 0.5) mod 4
    EXPECT_EQ(sampleNearest(image, 0.0f, 0)[0], 0);
    EXPECT_EQ(sampleNearest(image, 0.1f, 0)[0], 0);     // 0.9 -> 0
    EXPECT_EQ(sampleNearest(image, 0.2f, 0)[0], 60);    // 1.3 -> 1
    EXPECT_EQ(sampleNearest(image, 0.6f, 0)[0], 120);   // 2.9 -> 2
    EXPECT_EQ(sampleNearest(image, 0.99f, 0)[0], 0);    // 4.46 -> 4 mod 4
    EXPECT_EQ(sampleNearest(image, -0.25f, 0)[0], 180); // wraps to 0.75 -> 3.5 -> 3
    EXPECT_EQ(sampleNearest(image, 7.5f, 3.25f)[0], 120);
    const auto texel = sampleNearest(image, 0.5f, 0.5f);
    EXPECT_EQ(texel, (std::array<uint8_t, 4>{120, 10, 20, 255}));
}

TEST(SampleNearest, EmptyImageAndNonFiniteCoordinatesAreSafe) {
    EXPECT_EQ(sampleNearest(Image{}, 0.3f, 0.3f), (std::array<uint8_t, 4>{255, 255, 255, 255}));
    const Image image = ramp();
    EXPECT_EQ(sampleNearest(image, std::numeric_limits<float>::quiet_NaN(), 0)[0], 0);
    EXPECT_EQ(sampleNearest(image, std::numeric_limits<float>::infinity(), 0)[0], 0);
    EXPECT_EQ(sampleNearest(image, 1e30f, -1e30f)[0], 0);
}

TEST(SampleBilinear, CentresEdgesAndWrap) {
    const Image image = ramp();
    EXPECT_FLOAT_EQ(sampleBilinear(image, 0.125f, 0.5f)[0], 0);     // centre of texel 0
    EXPECT_FLOAT_EQ(sampleBilinear(image, 0.375f, 0.5f)[0], 60);    // centre of texel 1
    EXPECT_FLOAT_EQ(sampleBilinear(image, 0.25f, 0.5f)[0], 30);     // halfway 0..1
    EXPECT_FLOAT_EQ(sampleBilinear(image, 0.0f, 0.5f)[0], 90);      // halfway between texel 3 and 0
    EXPECT_FLOAT_EQ(sampleBilinear(image, 1.0f, 0.5f)[0], 90);
    EXPECT_FLOAT_EQ(sampleBilinear(image, -0.875f, 0.5f)[0], 0);    // wraps to 0.125
    const auto all = sampleBilinear(image, 0.3f, 0.7f);
    EXPECT_FLOAT_EQ(all[1], 10);
    EXPECT_FLOAT_EQ(all[2], 20);
    EXPECT_FLOAT_EQ(all[3], 255);
}

TEST(SampleBilinear, TwoDimensionalBlend) {
    Image image = solid(2, 2, {0, 0, 0, 0});
    image.rgba[(1 * 2 + 1) * 4] = 200;  // bottom-right texel red
    EXPECT_FLOAT_EQ(sampleBilinear(image, 0.5f, 0.5f)[0], 50);  // the shared corner of all four
    EXPECT_FLOAT_EQ(sampleBilinear(image, 0.75f, 0.75f)[0], 200);
    EXPECT_FLOAT_EQ(sampleBilinear(image, 0.75f, 0.5f)[0], 100);
}

}  // namespace
}  // namespace q3
