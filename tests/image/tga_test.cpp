#include <gtest/gtest.h>

#include "image.h"
#include "image_builders.h"

namespace q3 {
namespace {

using test::buildTga;
using test::patternImage;
using test::TgaLayout;

// What a lossless decode of `image` stored with `bits` bits should give back.
Image expectedAfter(const Image& image, int type, int bits, int alphaBits) {
    Image out = image;
    const int baseType = type > 8 ? type - 8 : type;
    for (size_t i = 0; i < out.rgba.size(); i += 4) {
        uint8_t* p = &out.rgba[i];
        if (baseType == 3) {
            p[1] = p[2] = p[0];
            if (bits == 8) p[3] = 255;
        } else if (baseType == 2 && (bits == 15 || bits == 16)) {
            for (int c = 0; c < 3; ++c) {
                unsigned five = p[c] >> 3;
                p[c] = uint8_t((five << 3) | (five >> 2));
            }
            p[3] = (bits == 16 && alphaBits > 0) ? (p[3] >= 128 ? 255 : 0) : 255;
        } else if (baseType == 2 && bits == 24) {
            p[3] = 255;
        }
    }
    return out;
}

// A small image with few colours (for colour maps) and runs (for RLE).
Image blockyImage(int width, int height) {
    Image image = patternImage(width, height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            uint8_t* p = &image.rgba[(size_t(y) * width + x) * 4];
            const int block = (x / 3 + y / 2) % 7;
            p[0] = uint8_t(block * 36);
            p[1] = uint8_t(255 - block * 30);
            p[2] = uint8_t(block * 17 + 5);
            p[3] = uint8_t(block * 40);
        }
    return image;
}

struct TgaCase {
    int type;
    int bits;
    bool topOrigin;
    bool rightOrigin;
    int alphaBits;
};

class TgaDecodeLayouts : public ::testing::TestWithParam<TgaCase> {};

TEST_P(TgaDecodeLayouts, DecodesWhatWasStored) {
    const TgaCase c = GetParam();
    const Image source = blockyImage(19, 11);  // odd sizes catch row-stride mistakes
    TgaLayout layout;
    layout.type = c.type;
    layout.bits = c.bits;
    layout.topOrigin = c.topOrigin;
    layout.rightOrigin = c.rightOrigin;
    layout.alphaBits = c.alphaBits;
    layout.idLength = 5;
    const std::vector<uint8_t> file = buildTga(source, layout);
    const Image decoded = decodeTga(file, "case.tga");
    const Image expected = expectedAfter(source, c.type, c.bits, c.alphaBits < 0 ? (c.bits == 32 ? 8 : 0) : c.alphaBits);
    ASSERT_EQ(decoded.width, 19);
    ASSERT_EQ(decoded.height, 11);
    EXPECT_EQ(decoded.rgba, expected.rgba);
}

INSTANTIATE_TEST_SUITE_P(AllTypes, TgaDecodeLayouts,
                         ::testing::Values(TgaCase{2, 24, false, false, -1}, TgaCase{2, 24, true, false, -1},
                                           TgaCase{2, 32, false, false, -1}, TgaCase{2, 32, true, true, -1},
                                           TgaCase{2, 16, false, false, 1}, TgaCase{2, 16, false, false, 0},
                                           TgaCase{2, 15, true, false, 0}, TgaCase{3, 8, false, false, -1},
                                           TgaCase{3, 16, true, false, 8}, TgaCase{1, 8, false, false, -1},
                                           TgaCase{1, 8, true, false, -1}, TgaCase{10, 24, false, false, -1},
                                           TgaCase{10, 32, true, false, -1}, TgaCase{10, 16, false, false, 1},
                                           TgaCase{11, 8, false, false, -1}, TgaCase{9, 8, true, false, -1},
                                           TgaCase{9, 8, false, true, -1}));

TEST(TgaDecode, RleRunsCrossingRowsAreAccepted) {
    Image flat;
    flat.width = 7;
    flat.height = 5;
    flat.rgba.assign(7 * 5 * 4, 0);
    for (size_t i = 0; i < flat.rgba.size(); i += 4) flat.rgba[i] = 200, flat.rgba[i + 3] = 255;
    TgaLayout layout{10, 24};
    const auto file = buildTga(flat, layout);
    // 35 equal pixels make one run packet of 1 header + 3 bytes after the 18-byte header.
    ASSERT_EQ(file.size(), 18u + 4u);
    EXPECT_EQ(decodeTga(file, "flat.tga").rgba, flat.rgba);
}

TEST(TgaEncode, RoundTrip24And32Bit) {
    const Image source = patternImage(33, 17);
    const Image back32 = decodeTga(encodeTga(source, true), "rt32.tga");
    EXPECT_EQ(back32.width, 33);
    EXPECT_EQ(back32.height, 17);
    EXPECT_EQ(back32.rgba, source.rgba);

    const Image back24 = decodeTga(encodeTga(source, false), "rt24.tga");
    Image opaque = source;
    for (size_t i = 3; i < opaque.rgba.size(); i += 4) opaque.rgba[i] = 255;
    EXPECT_EQ(back24.rgba, opaque.rgba);
}

TEST(TgaEncode, LayoutMatchesQ3map2ExternalLightmaps) {
    const Image source = patternImage(4, 3, true);
    const auto file = encodeTga(source, false);
    ASSERT_EQ(file.size(), 18u + 4 * 3 * 3);
    EXPECT_EQ(file[0], 0);   // no image id
    EXPECT_EQ(file[1], 0);   // no colour map
    EXPECT_EQ(file[2], 2);   // uncompressed true colour
    EXPECT_EQ(file[12], 4);
    EXPECT_EQ(file[14], 3);
    EXPECT_EQ(file[16], 24);
    EXPECT_EQ(file[17], 0);  // bottom-left origin
    // The first stored pixel is the bottom-left one, in BGR order.
    const uint8_t* bottomLeft = source.texel(0, 2);
    EXPECT_EQ(file[18], bottomLeft[2]);
    EXPECT_EQ(file[19], bottomLeft[1]);
    EXPECT_EQ(file[20], bottomLeft[0]);
    EXPECT_EQ(encodeTga(source, true)[17], 8);  // 32-bit declares its alpha bits
}

TEST(TgaEncode, RejectsEmptyImage) {
    EXPECT_THROW(encodeTga(Image{}, false), ImageError);
}

void expectTgaError(const std::vector<uint8_t>& bytes, const std::string& fragment) {
    try {
        decodeTga(bytes, "textures/bad/broken.tga");
        FAIL() << "no error for " << fragment;
    } catch (const ImageError& error) {
        const std::string message = error.what();
        EXPECT_NE(message.find("textures/bad/broken.tga"), std::string::npos) << message;
        EXPECT_NE(message.find(fragment), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos);
    }
}

TEST(TgaMalformed, EveryDefectIsAnError) {
    const Image source = blockyImage(16, 8);
    const auto raw = buildTga(source, {2, 32});
    const auto rle = buildTga(source, {10, 24});
    const auto mapped = buildTga(source, {1, 8});

    expectTgaError({}, "header");
    expectTgaError(std::vector<uint8_t>(raw.begin(), raw.begin() + 17), "header");
    expectTgaError(std::vector<uint8_t>(raw.begin(), raw.end() - 1), "truncated");
    expectTgaError(std::vector<uint8_t>(rle.begin(), rle.end() - 2), "truncated");
    expectTgaError(std::vector<uint8_t>(mapped.begin(), mapped.begin() + 40), "colour map");

    auto absurd = raw;
    absurd[12] = absurd[13] = absurd[14] = absurd[15] = 0xFF;  // 65535 x 65535
    expectTgaError(absurd, "exceeds");
    auto zero = raw;
    zero[12] = zero[13] = 0;
    expectTgaError(zero, "zero");
    auto badType = raw;
    badType[2] = 32;
    expectTgaError(badType, "type");
    auto badBits = raw;
    badBits[16] = 12;
    expectTgaError(badBits, "bits");
    // An RLE stream whose packet runs past the last pixel.
    auto overrun = buildTga(blockyImage(10, 5), {10, 24});
    overrun[18] = 0xFF;  // a run of 128 pixels in a 50-pixel image
    expectTgaError(overrun, "past the end");
    // A colour index outside the map.
    auto badIndex = mapped;
    ASSERT_FALSE(badIndex.empty());
    badIndex.at(badIndex.size() - 1) = 250;
    expectTgaError(badIndex, "colour index");
    // An RLE header claiming a huge picture backed by a few bytes fails before allocating.
    auto hugeRle = rle;
    hugeRle[12] = 0x00;
    hugeRle[13] = 0x40;
    hugeRle[14] = 0x00;
    hugeRle[15] = 0x40;  // 16384 x 16384
    expectTgaError(hugeRle, "truncated");
}

TEST(ImageFormat, DetectsByNameAndSignature) {
    EXPECT_EQ(imageFormatFromName("textures/a/B.TGA"), ImageFormat::Tga);
    EXPECT_EQ(imageFormatFromName("x.jpeg"), ImageFormat::Jpeg);
    EXPECT_EQ(imageFormatFromName("x.JPG"), ImageFormat::Jpeg);
    EXPECT_EQ(imageFormatFromName("x.png"), ImageFormat::Png);
    EXPECT_EQ(imageFormatFromName("dir.tga/x"), ImageFormat::Unknown);
    EXPECT_EQ(sniffImageFormat(encodePng(patternImage(2, 2), true)), ImageFormat::Png);
    EXPECT_EQ(sniffImageFormat(encodeTga(patternImage(2, 2), true)), ImageFormat::Unknown);
    // Content wins over a misleading extension.
    const Image source = patternImage(5, 4);
    EXPECT_EQ(decodeImage(encodePng(source, true), "really_png.tga").rgba, source.rgba);
    EXPECT_EQ(decodeImage(encodeTga(source, true), "plain.tga").rgba, source.rgba);
    EXPECT_THROW(decodeImage(std::vector<uint8_t>(40, 7), "mystery.bin"), ImageError);
}

}  // namespace
}  // namespace q3
