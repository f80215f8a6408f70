// Images in memory: TGA/JPEG/PNG decoding into 8-bit RGBA, TGA/PNG encoding, and the colour look-ups
// the light stage makes on textures (average colour, texel at a texture coordinate). Pure functions
// over byte buffers; no file system and no compiler state.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "file_io.h"

namespace q3 {

// A malformed or unsupported image. The message names the image and what is wrong.
struct ImageError : FileError {
    using FileError::FileError;
};

// Rows run top to bottom (row 0 is the top of the picture, texture coordinate t = 0), 4 bytes per
// pixel in R, G, B, A order. rgba.size() == width * height * 4.
struct Image {
    int width = 0;
    int height = 0;
    std::vector<uint8_t> rgba;

    bool empty() const { return width <= 0 || height <= 0; }
    const uint8_t* texel(int x, int y) const { return &rgba[(static_cast<size_t>(y) * width + x) * 4]; }
    uint8_t* texel(int x, int y) { return &rgba[(static_cast<size_t>(y) * width + x) * 4]; }
};

// Largest width or height any decoder accepts; larger headers are rejected as hostile.
inline constexpr int kMaxImageDimension = 16384;

enum class ImageFormat { Unknown, Tga, Jpeg, Png };

// From the file name's extension (case-insensitive): .tga, .jpg/.jpeg, .png.
ImageFormat imageFormatFromName(std::string_view name);
// From the leading bytes (JPEG and PNG signatures). TGA has no signature and yields Unknown.
ImageFormat sniffImageFormat(std::span<const uint8_t> bytes);

// Decoders. `name` is used only in error messages. Every failure throws ImageError.
// TGA: types 1, 2, 3 (colour-mapped, true-colour, grey) and their RLE forms 9, 10, 11; 8, 15/16,
// 24 and 32 bits per pixel; bottom-left or top-left origin.
Image decodeTga(std::span<const uint8_t> bytes, std::string_view name);
Image decodeJpeg(std::span<const uint8_t> bytes, std::string_view name);
// PNG: every colour type and bit depth (palette, grey, grey+alpha, RGB, RGBA, 16-bit, tRNS).
Image decodePng(std::span<const uint8_t> bytes, std::string_view name);
// Picks the decoder from the signature, falling back to the name's extension (TGA).
Image decodeImage(std::span<const uint8_t> bytes, std::string_view name);
// Width and height only: a JPEG's come from its header alone (frame header checked, scan data not
// decoded); other formats are decoded. Throws ImageError as the decoders do.
struct ImageDimensions {
    int width = 0;
    int height = 0;
};
ImageDimensions jpegDimensions(std::span<const uint8_t> bytes, std::string_view name);
ImageDimensions imageDimensions(std::span<const uint8_t> bytes, std::string_view name);

// Uncompressed true-colour TGA as q3map2 writes external lightmaps (lm_NNNN.tga): type 2,
// bottom-left origin with the rows stored bottom-up so the picture reads upright, BGR(A) order.
// With alpha == false the file is 24-bit and the alpha channel is dropped.
std::vector<uint8_t> encodeTga(const Image& image, bool alpha);
// 8-bit RGBA (alpha == true) or RGB PNG.
std::vector<uint8_t> encodePng(const Image& image, bool alpha);

// q3map2's shader colour from an image (LoadShaderImages): the channel sums over all pixels.
struct ImageAverage {
    std::array<float, 4> mean{};        // per-channel mean, 0..255 (RGB and alpha)
    std::array<float, 3> normalized{};  // RGB sum scaled so its largest component is 1 (white if black)
};
ImageAverage averageColor(const Image& image);

// Texel at texture coordinate (s, t), repeating outside [0, 1), as q3map2's RadSampleImage:
// x = int(width * s + 0.5) mod width (same for y). An empty image yields opaque white.
std::array<uint8_t, 4> sampleNearest(const Image& image, float s, float t);
// Bilinear filtering between the four nearest texel centres, repeating at the edges. 0..255 scale.
std::array<float, 4> sampleBilinear(const Image& image, float s, float t);

}  // namespace q3
