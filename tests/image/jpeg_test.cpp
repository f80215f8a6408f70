#include <gtest/gtest.h>

#include <cstdlib>

#include "image.h"
#include "image_builders.h"

namespace q3 {
namespace {

using test::buildJpeg;

// A smooth picture compresses with small errors.
std::vector<uint8_t> smoothRgb(int width, int height) {
    std::vector<uint8_t> pixels;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            pixels.insert(pixels.end(), {uint8_t(x * 255 / width), uint8_t(y * 255 / height), uint8_t(128)});
    return pixels;
}

TEST(JpegDecode, RgbMatchesWithinCompressionError) {
    const int width = 48, height = 40;
    const auto pixels = smoothRgb(width, height);
    const Image image = decodeJpeg(buildJpeg(width, height, 3, pixels, 98), "smooth.jpg");
    ASSERT_EQ(image.width, width);
    ASSERT_EQ(image.height, height);
    int worst = 0;
    for (int i = 0; i < width * height; ++i) {
        for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(int(image.rgba[i * 4 + c]) - pixels[i * 3 + c]));
        ASSERT_EQ(image.rgba[i * 4 + 3], 255);
    }
    EXPECT_LE(worst, 6);
}

// The size from the header alone equals the decoded one; a cut header and a non-JPEG fail, and
// imageDimensions decodes the other formats.
TEST(JpegDecode, DimensionsFromTheHeaderMatchTheDecodedPicture) {
    const std::vector<uint8_t> bytes = buildJpeg(48, 40, 3, smoothRgb(48, 40), 90);
    const ImageDimensions d = jpegDimensions(bytes, "smooth.jpg");
    EXPECT_EQ(d.width, 48);
    EXPECT_EQ(d.height, 40);
    const ImageDimensions any = imageDimensions(bytes, "smooth.tga");  // content wins over the name
    EXPECT_EQ(any.width, 48);
    EXPECT_EQ(any.height, 40);
    EXPECT_THROW(jpegDimensions(std::span(bytes).first(20), "cut.jpg"), ImageError);
    EXPECT_THROW(jpegDimensions(std::vector<uint8_t>(64, 7), "noise.jpg"), ImageError);
}

TEST(JpegDecode, GreyscaleExpandsToRgb) {
    std::vector<uint8_t> grey(16 * 8);
    for (size_t i = 0; i < grey.size(); ++i) grey[i] = uint8_t(100 + i % 16);
    const Image image = decodeJpeg(buildJpeg(16, 8, 1, grey, 100), "grey.jpg");
    ASSERT_EQ(image.rgba.size(), 16u * 8 * 4);
    for (size_t i = 0; i < grey.size(); ++i) {
        EXPECT_EQ(image.rgba[i * 4], image.rgba[i * 4 + 1]);
        EXPECT_EQ(image.rgba[i * 4], image.rgba[i * 4 + 2]);
        EXPECT_NEAR(image.rgba[i * 4], grey[i], 3);
    }
}

TEST(JpegDecode, AdobeCmykConvertsToRgb) {
    // Stored values: 255 = no ink. With K = 255 the stored C, M, Y are the RGB values; K halves them.
    std::vector<uint8_t> cmyk;
    for (int i = 0; i < 16 * 16; ++i) cmyk.insert(cmyk.end(), {200, 100, 50, uint8_t(i < 128 ? 255 : 128)});
    const Image image = decodeJpeg(buildJpeg(16, 16, 4, cmyk, 100), "cmyk.jpg");
    ASSERT_EQ(image.width, 16);
    const uint8_t* top = image.texel(8, 2);
    EXPECT_NEAR(top[0], 200, 3);
    EXPECT_NEAR(top[1], 100, 3);
    EXPECT_NEAR(top[2], 50, 3);
    EXPECT_EQ(top[3], 255);
    const uint8_t* bottom = image.texel(8, 13);
    EXPECT_NEAR(bottom[0], 100, 3);
    EXPECT_NEAR(bottom[1], 50, 3);
    EXPECT_NEAR(bottom[2], 25, 3);
}

void expectJpegError(const std::vector<uint8_t>& bytes, const char* what) {
    try {
        decodeJpeg(bytes, "textures/bad/broken.jpg");
        FAIL() << "no error for " << what;
    } catch (const ImageError& error) {
        const std::string message = error.what();
        EXPECT_NE(message.find("textures/bad/broken.jpg: bad JPEG"), std::string::npos) << message;
    }
}

TEST(JpegMalformed, EveryDefectIsAnError) {
    const auto good = buildJpeg(64, 64, 3, smoothRgb(64, 64));
    expectJpegError({}, "empty");
    expectJpegError({0xFF, 0xD8, 0xFF}, "signature only");
    expectJpegError(std::vector<uint8_t>(good.begin(), good.begin() + long(good.size() / 2)), "half");
    expectJpegError(std::vector<uint8_t>(good.begin(), good.begin() + 300), "header only");
    expectJpegError(std::vector<uint8_t>(200, 0x42), "garbage");
    // A start-of-frame claiming 60000 x 60000.
    auto huge = good;
    for (size_t i = 0; i + 8 < huge.size(); ++i)
        if (huge[i] == 0xFF && huge[i + 1] == 0xC0) {
            huge[i + 5] = 0xEA, huge[i + 6] = 0x60, huge[i + 7] = 0xEA, huge[i + 8] = 0x60;
            break;
        }
    expectJpegError(huge, "60000 square");
    // A plausible header with most of the data gone: must not be padded into a picture.
    auto bigHeader = good;
    for (size_t i = 0; i + 8 < bigHeader.size(); ++i)
        if (bigHeader[i] == 0xFF && bigHeader[i + 1] == 0xC0) {
            bigHeader[i + 5] = 0x3F, bigHeader[i + 6] = 0xFF, bigHeader[i + 7] = 0x3F, bigHeader[i + 8] = 0xFF;
            break;
        }
    expectJpegError(bigHeader, "16383 square");
}

}  // namespace
}  // namespace q3
