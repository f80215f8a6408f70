// Colour look-ups on decoded images: the average colour q3map2 gives a shader, and texels at a
// texture coordinate for surface lights, alpha shadows and light filters.
#include "image.h"

#include <algorithm>
#include <cmath>

namespace q3 {

namespace {

// Fractional part in [0, 1); non-finite coordinates map to 0 so that callers never index wildly.
double wrapUnit(float v) {
    if (!std::isfinite(v)) return 0.0;
    double f = double(v) - std::floor(double(v));
    return f >= 1.0 ? 0.0 : f;
}

int wrapIndex(long long i, int size) {
    long long m = i % size;
    return int(m < 0 ? m + size : m);
}

}  // namespace

ImageAverage averageColor(const Image& image) {
    ImageAverage result;
    const size_t count = image.empty() ? 0 : size_t(image.width) * image.height;
    if (count == 0 || image.rgba.size() < count * 4) {
        result.mean = {255, 255, 255, 255};
        result.normalized = {1, 1, 1};
        return result;
    }
    // Integer sums are exact and order-independent.
    uint64_t sum[4] = {0, 0, 0, 0};
    for (size_t i = 0; i < count; ++i)
        for (int c = 0; c < 4; ++c) sum[c] += image.rgba[i * 4 + c];
    for (int c = 0; c < 4; ++c) result.mean[c] = float(double(sum[c]) / double(count));
    const uint64_t largest = std::max({sum[0], sum[1], sum[2]});
    for (int c = 0; c < 3; ++c) result.normalized[c] = largest == 0 ? 1.0f : float(double(sum[c]) / double(largest));
    return result;
}

std::array<uint8_t, 4> sampleNearest(const Image& image, float s, float t) {
    if (image.empty()) return {255, 255, 255, 255};
    const int x = int(image.width * wrapUnit(s) + 0.5) % image.width;
    const int y = int(image.height * wrapUnit(t) + 0.5) % image.height;
    const uint8_t* p = image.texel(x, y);
    return {p[0], p[1], p[2], p[3]};
}

std::array<float, 4> sampleBilinear(const Image& image, float s, float t) {
    if (image.empty()) return {255, 255, 255, 255};
    // Texel centres sit at (i + 0.5) / size.
    const double u = wrapUnit(s) * image.width - 0.5;
    const double v = wrapUnit(t) * image.height - 0.5;
    const double u0 = std::floor(u), v0 = std::floor(v);
    const float fu = float(u - u0), fv = float(v - v0);
    const int x0 = wrapIndex((long long)u0, image.width), x1 = wrapIndex((long long)u0 + 1, image.width);
    const int y0 = wrapIndex((long long)v0, image.height), y1 = wrapIndex((long long)v0 + 1, image.height);
    const uint8_t* a = image.texel(x0, y0);
    const uint8_t* b = image.texel(x1, y0);
    const uint8_t* c = image.texel(x0, y1);
    const uint8_t* d = image.texel(x1, y1);
    std::array<float, 4> out{};
    for (int k = 0; k < 4; ++k) {
        const float top = a[k] + (b[k] - a[k]) * fu;
        const float bottom = c[k] + (d[k] - c[k]) * fu;
        out[k] = top + (bottom - top) * fv;
    }
    return out;
}

}  // namespace q3
