// Independent writers of test images, so that decoders are checked against files built here rather
// than only against the library's own encoders.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "image.h"

namespace q3::test {

// A deterministic picture with varied colours and alpha.
Image patternImage(int width, int height, bool opaque = false);

struct TgaLayout {
    int type = 2;        // 1, 2, 3, 9, 10, 11
    int bits = 24;       // stored bits per pixel
    bool topOrigin = false;
    bool rightOrigin = false;
    int idLength = 0;    // bytes of image id to insert
    int alphaBits = -1;  // descriptor alpha bits; -1 = 8 for 32-bit, else 0
};
// Writes `image` in the given layout. Colour-mapped layouts use a palette of the image's distinct
// colours (the image must have at most 256). 16-bit true colour stores 5 bits per channel and the
// alpha bit; 8-bit grey stores the red channel.
std::vector<uint8_t> buildTga(const Image& image, const TgaLayout& layout);

// A PNG from raw (unfiltered) scanlines. Chunks are assembled by hand with zlib.
struct PngChunk {
    std::string type;
    std::vector<uint8_t> data;
};
std::vector<uint8_t> buildPng(int width, int height, int bitDepth, int colorType,
                              const std::vector<std::vector<uint8_t>>& rows, const std::vector<PngChunk>& extra = {});

// A baseline JPEG (libjpeg) of greyscale (1 component), RGB (3) or CMYK (4, stored as given,
// Adobe style: 255 means no ink) pixels.
std::vector<uint8_t> buildJpeg(int width, int height, int components, const std::vector<uint8_t>& pixels,
                               int quality = 95);

}  // namespace q3::test
