// q3map2's ColorToBytes: how a light value in float units (255 = full) becomes the stored bytes of
// lightmaps, vertex colours and grid points. Pure functions of an options struct.
#pragma once

#include <array>
#include <cstdint>

#include "vec3.h"

namespace q3::light {

using Rgb8 = std::array<uint8_t, 3>;

// Global colour controls of the -light command line (q3map2 defaults for the quake3 game).
struct ColorOptions {
    float brightness = 1.0f;  // -brightness: multiplier applied before everything else
    float contrast = 0.0f;    // -contrast, -255..255 (0 = off)
    float gamma = 1.0f;       // -gamma: pow(x/255, 1/gamma)*255
    float exposure = 0.0f;    // -exposure (0 = off): x *= (1-exp(-max/exposure))*255/max
    float saturation = 1.0f;  // -saturation (1 = unchanged)
    float compensate = 1.0f;  // -compensate: final divide emulating engine overbrighting
    float maxLight = 255.0f;  // worldspawn _maxlight, clamped to 0..255
    bool sRGB = false;        // -sRGBlight: encode the result as sRGB before the byte conversion
};

// The contrast factor 259(c+255)/(255(259-c)) that maps x to factor*(x-128)+128.
float contrastFactor(float contrast);

// Saturation through the linear-RGB luminance matrix (0.3086, 0.6094, 0.0820).
Vec3 applySaturation(Vec3 color, float saturation);

// Linear [0,1] -> sRGB [0,1] transfer function.
float linearToSrgb(float linear);

// Every step of ColorToBytes except the final truncation, in q3map2's order:
// x brightness -> contrast -> clamp >= 0 -> gamma -> exposure -> saturation -> x (scale/compensate)
// -> colour-preserving clamp to maxLight -> optional sRGB. `scale` is the per-use factor
// (q3map_lightmapBrightness of a lightmap, -gridscale for the grid, q3map_vertexScale for vertex
// colours); scale <= 0 means 1, as in q3map2.
Vec3 colorToFloatBytes(Vec3 color, float scale, const ColorOptions& options);

// colorToFloatBytes then truncation to bytes (q3map2 stores with a plain float -> byte cast).
Rgb8 colorToBytes(Vec3 color, float scale, const ColorOptions& options);

}  // namespace q3::light
