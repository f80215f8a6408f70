// Measures on engine screenshots: how bright a picture is, how much of it is lit, and where two
// shots of the same view differ (a model drawn into one of them).
#pragma once

#include <cstddef>
#include <filesystem>
#include <vector>

#include "image.h"

namespace q3::enginetest {

// Rec. 709 luma of an 8-bit RGB pixel, 0..255.
double luminance(const uint8_t* rgb);

struct PictureStats {
    double meanLuminance = 0;  // over every pixel, 0..255
    double litFraction = 0;    // share of pixels brighter than the black level
    size_t pixels = 0;
};

// A pixel at or below this luma counts as black: it leaves room for dithering and the dark grey
// a software rasteriser can leave in unlit corners.
inline constexpr double kBlackLevel = 8.0;

PictureStats pictureStats(const Image& image);

// The pixels where two same-sized shots of one view differ by more than `tolerance` in some
// channel (1) - where a model was drawn into one of them. Throws std::invalid_argument for
// pictures of different sizes.
std::vector<uint8_t> differenceMask(const Image& a, const Image& b, int tolerance);

// How many pixels a mask selects, their mean luma and mean R, G, B in `image` (0 when none).
struct MaskedStats {
    size_t pixels = 0;
    double meanLuminance = 0;
    double meanRgb[3] = {0, 0, 0};
};
MaskedStats maskedStats(const Image& image, const std::vector<uint8_t>& mask);

// How two same-sized shots of one view compare pixel by pixel in luma: how many pixels of `after`
// are brighter than in `before` by more than `tolerance`, how many darker, and the mean change.
// Throws std::invalid_argument for pictures of different sizes.
struct LumaShift {
    size_t brighter = 0;
    size_t darker = 0;
    double meanChange = 0;  // mean of after - before over every pixel
};
LumaShift lumaShift(const Image& before, const Image& after, double tolerance);

// Reads and decodes a PNG (an engine screenshot). Throws FileError / ImageError.
Image readPng(const std::filesystem::path& path);

}  // namespace q3::enginetest
