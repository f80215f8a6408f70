#include "engine_picture.h"

#include <cstdlib>
#include <stdexcept>

#include "file_io.h"

namespace q3::enginetest {

double luminance(const uint8_t* rgb) { return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]; }

PictureStats pictureStats(const Image& image) {
    PictureStats stats;
    stats.pixels = size_t(image.width) * size_t(image.height);
    if (stats.pixels == 0) return stats;
    double sum = 0;
    size_t lit = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const double l = luminance(image.texel(x, y));
            sum += l;
            if (l > kBlackLevel) ++lit;
        }
    stats.meanLuminance = sum / double(stats.pixels);
    stats.litFraction = double(lit) / double(stats.pixels);
    return stats;
}

std::vector<uint8_t> differenceMask(const Image& a, const Image& b, int tolerance) {
    if (a.width != b.width || a.height != b.height)
        throw std::invalid_argument("screenshots of different sizes cannot be compared");
    std::vector<uint8_t> mask(size_t(a.width) * size_t(a.height), 0);
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            const uint8_t* p = a.texel(x, y);
            const uint8_t* q = b.texel(x, y);
            bool differs = false;
            for (int c = 0; c < 3; ++c) differs = differs || std::abs(int(p[c]) - int(q[c])) > tolerance;
            mask[size_t(y) * a.width + x] = differs ? 1 : 0;
        }
    return mask;
}

MaskedStats maskedStats(const Image& image, const std::vector<uint8_t>& mask) {
    if (mask.size() != size_t(image.width) * size_t(image.height))
        throw std::invalid_argument("mask and screenshot sizes differ");
    MaskedStats stats;
    double sum = 0, rgb[3] = {0, 0, 0};
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            if (!mask[size_t(y) * image.width + x]) continue;
            ++stats.pixels;
            sum += luminance(image.texel(x, y));
            for (int c = 0; c < 3; ++c) rgb[c] += image.texel(x, y)[c];
        }
    if (stats.pixels) {
        stats.meanLuminance = sum / double(stats.pixels);
        for (int c = 0; c < 3; ++c) stats.meanRgb[c] = rgb[c] / double(stats.pixels);
    }
    return stats;
}

LumaShift lumaShift(const Image& before, const Image& after, double tolerance) {
    if (before.width != after.width || before.height != after.height)
        throw std::invalid_argument("screenshots of different sizes cannot be compared");
    LumaShift shift;
    double sum = 0;
    for (int y = 0; y < before.height; ++y)
        for (int x = 0; x < before.width; ++x) {
            const double change = luminance(after.texel(x, y)) - luminance(before.texel(x, y));
            sum += change;
            if (change > tolerance) ++shift.brighter;
            if (change < -tolerance) ++shift.darker;
        }
    const size_t pixels = size_t(before.width) * size_t(before.height);
    if (pixels) shift.meanChange = sum / double(pixels);
    return shift;
}

Image readPng(const std::filesystem::path& path) {
    const std::vector<uint8_t> bytes = readFileBytes(path);
    return decodePng(bytes, path.string());
}

}  // namespace q3::enginetest
