// Damaged files of every format: each decode either succeeds with a consistent image or throws
// ImageError. Deterministic mutations (fixed seeds) so that a failure always reproduces.
#include <gtest/gtest.h>

#include <cstdint>

#include "image.h"
#include "image_builders.h"

namespace q3 {
namespace {

struct Lcg {
    uint32_t state;
    uint32_t next() {
        state = state * 1664525u + 1013904223u;
        return state >> 8;
    }
};

void mutateAndDecode(const std::vector<uint8_t>& original, const char* name, uint32_t seed) {
    Lcg random{seed};
    for (int round = 0; round < 1500; ++round) {
        std::vector<uint8_t> bytes = original;
        const int edits = 1 + int(random.next() % 6);
        for (int e = 0; e < edits; ++e) {
            const size_t at = random.next() % bytes.size();
            switch (random.next() % 4) {
                case 0: bytes[at] = uint8_t(random.next()); break;
                case 1: bytes[at] ^= uint8_t(1u << (random.next() % 8)); break;
                case 2: bytes[at] = (random.next() & 1) ? 0xFF : 0x00; break;
                default: bytes.resize(std::max<size_t>(1, at)); break;
            }
            if (bytes.empty()) break;
        }
        try {
            const Image image = decodeImage(bytes, name);
            ASSERT_GT(image.width, 0);
            ASSERT_GT(image.height, 0);
            ASSERT_LE(image.width, kMaxImageDimension);
            ASSERT_LE(image.height, kMaxImageDimension);
            ASSERT_EQ(image.rgba.size(), size_t(image.width) * image.height * 4);
        } catch (const ImageError& error) {
            ASSERT_NE(std::string(error.what()).find(name), std::string::npos);
        }
    }
}

TEST(DamagedImages, TgaNeverCrashes) {
    const Image source = test::patternImage(12, 9);
    mutateAndDecode(encodeTga(source, true), "raw32.tga", 1);
    mutateAndDecode(test::buildTga(source, {10, 24}), "rle24.tga", 2);
    mutateAndDecode(test::buildTga(test::patternImage(16, 1), {9, 8}), "rlemapped.tga", 3);
}

TEST(DamagedImages, PngNeverCrashes) {
    mutateAndDecode(encodePng(test::patternImage(12, 9), true), "rgba.png", 4);
    const test::PngChunk palette{"PLTE", {255, 0, 0, 0, 255, 0, 0, 0, 255}};
    mutateAndDecode(test::buildPng(3, 2, 8, 3, {{0, 1, 2}, {2, 1, 0}}, {palette}), "palette.png", 5);
}

TEST(DamagedImages, JpegNeverCrashes) {
    std::vector<uint8_t> rgb;
    for (int i = 0; i < 24 * 16; ++i) rgb.insert(rgb.end(), {uint8_t(i), uint8_t(i * 3), uint8_t(i * 7)});
    mutateAndDecode(test::buildJpeg(24, 16, 3, rgb), "photo.jpg", 6);
}

}  // namespace
}  // namespace q3
