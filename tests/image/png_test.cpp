#include <gtest/gtest.h>

#include "image.h"
#include "image_builders.h"

namespace q3 {
namespace {

using test::buildPng;
using test::patternImage;
using test::PngChunk;

TEST(PngEncode, RoundTripRgbaAndRgb) {
    const Image source = patternImage(31, 9);
    const Image back = decodePng(encodePng(source, true), "rt.png");
    EXPECT_EQ(back.width, 31);
    EXPECT_EQ(back.height, 9);
    EXPECT_EQ(back.rgba, source.rgba);

    Image opaque = source;
    for (size_t i = 3; i < opaque.rgba.size(); i += 4) opaque.rgba[i] = 255;
    EXPECT_EQ(decodePng(encodePng(source, false), "rgb.png").rgba, opaque.rgba);
}

TEST(PngDecode, GreyscaleDepths) {
    // 2x2 grey at 1, 2, 4, 8 bits: values scale to the full 0..255 range.
    const std::vector<std::vector<uint8_t>> oneBit = {{0b10000000}, {0b01000000}};
    Image image = decodePng(buildPng(2, 2, 1, 0, oneBit), "g1.png");
    EXPECT_EQ(image.rgba, (std::vector<uint8_t>{255, 255, 255, 255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255, 255}));

    image = decodePng(buildPng(2, 1, 2, 0, {{0b01110000}}), "g2.png");
    EXPECT_EQ(image.rgba, (std::vector<uint8_t>{85, 85, 85, 255, 255, 255, 255, 255}));

    image = decodePng(buildPng(2, 1, 4, 0, {{0x3F}}), "g4.png");
    EXPECT_EQ(image.rgba, (std::vector<uint8_t>{51, 51, 51, 255, 255, 255, 255, 255}));

    image = decodePng(buildPng(1, 1, 8, 0, {{77}}), "g8.png");
    EXPECT_EQ(image.rgba, (std::vector<uint8_t>{77, 77, 77, 255}));
}

TEST(PngDecode, SixteenBitKeepsTheHighByte) {
    // RGBA 16-bit: each channel big-endian.
    Image image = decodePng(buildPng(1, 1, 16, 6, {{0x12, 0x34, 0xAB, 0xCD, 0xFF, 0x00, 0x80, 0x01}}), "c16.png");
    EXPECT_EQ(image.rgba, (std::vector<uint8_t>{0x12, 0xAB, 0xFF, 0x80}));
    image = decodePng(buildPng(1, 1, 16, 4, {{0x40, 0x00, 0x20, 0x00}}), "ga16.png");
    EXPECT_EQ(image.rgba, (std::vector<uint8_t>{0x40, 0x40, 0x40, 0x20}));
    image = decodePng(buildPng(1, 1, 16, 2, {{0x01, 0x00, 0x02, 0x00, 0x03, 0x00}}), "rgb16.png");
    EXPECT_EQ(image.rgba, (std::vector<uint8_t>{1, 2, 3, 255}));
}

TEST(PngDecode, GreyAlphaAndRgb) {
    Image image = decodePng(buildPng(2, 1, 8, 4, {{10, 20, 30, 40}}), "ga.png");
    EXPECT_EQ(image.rgba, (std::vector<uint8_t>{10, 10, 10, 20, 30, 30, 30, 40}));
    image = decodePng(buildPng(1, 2, 8, 2, {{1, 2, 3}, {4, 5, 6}}), "rgb.png");
    EXPECT_EQ(image.rgba, (std::vector<uint8_t>{1, 2, 3, 255, 4, 5, 6, 255}));
}

TEST(PngDecode, PaletteWithTransparency) {
    const PngChunk palette{"PLTE", {255, 0, 0, 0, 255, 0, 0, 0, 255}};
    const PngChunk alpha{"tRNS", {128}};  // only the first entry is translucent
    Image image = decodePng(buildPng(3, 1, 8, 3, {{0, 1, 2}}, {palette, alpha}), "pal.png");
    EXPECT_EQ(image.rgba, (std::vector<uint8_t>{255, 0, 0, 128, 0, 255, 0, 255, 0, 0, 255, 255}));
    // 4-bit indices.
    image = decodePng(buildPng(2, 1, 4, 3, {{0x21}}, {palette}), "pal4.png");
    EXPECT_EQ(image.rgba, (std::vector<uint8_t>{0, 0, 255, 255, 0, 255, 0, 255}));
}

TEST(PngDecode, GreyTransparentColourKey) {
    const PngChunk key{"tRNS", {0, 50}};
    Image image = decodePng(buildPng(2, 1, 8, 0, {{50, 60}}, {key}), "key.png");
    EXPECT_EQ(image.rgba, (std::vector<uint8_t>{50, 50, 50, 0, 60, 60, 60, 255}));
}

void expectPngError(const std::vector<uint8_t>& bytes) {
    try {
        decodePng(bytes, "textures/bad/broken.png");
        FAIL() << "no error";
    } catch (const ImageError& error) {
        const std::string message = error.what();
        EXPECT_NE(message.find("textures/bad/broken.png: bad PNG"), std::string::npos) << message;
    }
}

TEST(PngMalformed, EveryDefectIsAnError) {
    const auto good = encodePng(patternImage(40, 30), true);
    expectPngError({});
    expectPngError(std::vector<uint8_t>(good.begin(), good.begin() + 8));
    expectPngError(std::vector<uint8_t>(good.begin(), good.begin() + long(good.size() / 2)));
    expectPngError(std::vector<uint8_t>(good.begin(), good.end() - 20));
    auto badCrc = good;
    badCrc[29] ^= 0xFF;  // inside the IHDR CRC
    expectPngError(badCrc);
    // Absurd and hostile sizes.
    expectPngError(buildPng(100000, 1, 8, 0, {{0}}));
    expectPngError(buildPng(16000, 16000, 8, 6, {{0, 0, 0, 0}}));
    // Not enough rows for the header's height.
    expectPngError(buildPng(4, 4, 8, 0, {{1, 2, 3, 4}}));
    // Invalid colour type / depth combination.
    expectPngError(buildPng(1, 1, 3, 2, {{0}}));
}

}  // namespace
}  // namespace q3
