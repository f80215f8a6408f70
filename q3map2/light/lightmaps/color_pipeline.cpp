#include "color_pipeline.h"

#include <algorithm>
#include <cmath>

namespace q3::light {

float contrastFactor(float contrast) {
    return (259.0f * (contrast + 255.0f)) / (255.0f * (259.0f - contrast));
}

Vec3 applySaturation(Vec3 c, float saturation) {
    // Luminance weights for linear RGB (graficaobscura "matrix" article), not the NTSC ones.
    constexpr float kR = 0.3086f, kG = 0.6094f, kB = 0.0820f;
    const float inv = 1.0f - saturation;
    const float grey = (kR * c.x + kG * c.y + kB * c.z) * inv;
    return {grey + saturation * c.x, grey + saturation * c.y, grey + saturation * c.z};
}

float linearToSrgb(float v) {
    if (v <= 0.0031308f) return v * 12.92f;
    return 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

Vec3 colorToFloatBytes(Vec3 color, float scale, const ColorOptions& o) {
    if (scale <= 0.0f) scale = 1.0f;
    Vec3 s = color * o.brightness;

    if (o.contrast != 0.0f) {
        const float f = contrastFactor(o.contrast);
        for (int i = 0; i < 3; ++i) s[i] = f * (s[i] - 128.0f) + 128.0f;
    }
    for (int i = 0; i < 3; ++i) s[i] = std::max(0.0f, s[i]);

    if (o.gamma != 1.0f) {
        const float invGamma = 1.0f / o.gamma;
        for (int i = 0; i < 3; ++i) s[i] = std::pow(s[i] / 255.0f, invGamma) * 255.0f;
    }

    if (o.exposure != 0.0f) {
        const float max = maxComponent(s);
        // Soft knee: the brightest channel approaches 255 instead of clipping.
        const float factor = max > 0.0f ? (1.0f - std::exp(-max / o.exposure)) * 255.0f / max : 0.0f;
        s *= factor;
    }

    if (o.saturation != 1.0f) s = applySaturation(s, o.saturation);

    // q3map2 2.5.17n divides by -compensate before the clamp: -compensate 2 keeps light up to 510
    // apart (measured against it on oacmpdm5: dividing after the clamp left the legacy grid's
    // directed light at 0.88 of q3map2's, correlation 0.92; before it, 1.006 and 0.997).
    s *= scale / o.compensate;

    // Clamp while keeping the hue: scale all channels by the same amount.
    const float max = maxComponent(s);
    if (max > o.maxLight) s *= o.maxLight / max;
    for (int i = 0; i < 3; ++i) s[i] = std::max(0.0f, s[i]);

    if (o.sRGB) {
        for (int i = 0; i < 3; ++i) s[i] = std::floor(linearToSrgb(s[i] / 255.0f) * 255.0f + 0.5f);
    }
    return s;
}

Rgb8 colorToBytes(Vec3 color, float scale, const ColorOptions& options) {
    const Vec3 s = colorToFloatBytes(color, scale, options);
    Rgb8 out{};
    for (int i = 0; i < 3; ++i) out[i] = uint8_t(std::clamp(s[i], 0.0f, 255.0f));
    return out;
}

}  // namespace q3::light
