#include "index_map_formats.h"

#include <algorithm>
#include <string>

#include "image.h"

namespace q3::bspstage {
namespace {

int littleShort(std::span<const uint8_t> b, size_t at) { return int(int16_t(uint16_t(b[at] | b[at + 1] << 8))); }
int littleUnsignedShort(std::span<const uint8_t> b, size_t at) { return int(b[at] | b[at + 1] << 8); }
int32_t littleLong(std::span<const uint8_t> b, size_t at) {
    return int32_t(uint32_t(b[at]) | uint32_t(b[at + 1]) << 8 | uint32_t(b[at + 2]) << 16 | uint32_t(b[at + 3]) << 24);
}

[[noreturn]] void malformed(std::string_view name, const std::string& what) {
    throw ImageError(std::string(name) + ": " + what);
}

constexpr size_t kPcxHeader = 128;

}  // namespace

PaletteIndexes decodePcxIndexes(std::span<const uint8_t> bytes, std::string_view name) {
    if (bytes.size() < kPcxHeader) malformed(name, "too short for a PCX header");
    const int xmax = littleUnsignedShort(bytes, 8), ymax = littleUnsignedShort(bytes, 10);
    if (bytes[0] != 0x0a || bytes[1] != 5 || bytes[2] != 1 || bytes[3] != 8 || xmax >= 640 || ymax >= 480)
        malformed(name, "not a version 5, RLE, 8-bit PCX under 640x480");
    const int lineSize = int(bytes[65]) * littleUnsignedShort(bytes, 66);
    PaletteIndexes out;
    out.width = xmax + 1;
    out.height = ymax + 1;
    out.pixels.assign(size_t(out.width) * size_t(out.height), 0);
    size_t at = kPcxHeader;
    int value = 0, run = 0;
    // One run: a count byte (two high bits set) and the value, or a single value.
    auto nextRun = [&] {
        if (at >= bytes.size()) malformed(name, "pixel data ends early");
        value = bytes[at++];
        run = 1;
        if ((value & 0xc0) == 0xc0) {
            run = value & 0x3f;
            if (at >= bytes.size()) malformed(name, "pixel data ends early");
            value = bytes[at++];
        }
    };
    for (int y = 0; y < out.height; ++y) {
        const size_t row = size_t(y) * size_t(out.width);
        int x = 0;
        while (x < out.width) {
            nextRun();
            // A run past the row's end spills into the next row, which overwrites it.
            for (; run > 0; --run, ++x)
                if (row + size_t(x) < out.pixels.size()) out.pixels[row + size_t(x)] = uint8_t(value);
        }
        // q3map2 skips one run (not one byte) per byte the scan line is longer than the picture.
        for (; x < lineSize; ++x) nextRun();
    }
    return out;
}

PaletteIndexes decodeBmpIndexes(std::span<const uint8_t> bytes, std::string_view name) {
    if (bytes.size() < 26 || bytes[0] != 'B' || bytes[1] != 'M') malformed(name, "not a BMP file");
    const size_t dataOffset = size_t(uint32_t(littleLong(bytes, 10)));
    const int32_t headerSize = littleLong(bytes, 14);
    int width = 0, height = 0, planes = 0, bits = 0;
    if (headerSize == 40 && bytes.size() >= 34) {
        width = littleLong(bytes, 18);
        height = littleLong(bytes, 22);
        planes = littleShort(bytes, 26);
        bits = littleShort(bytes, 28);
    } else if (headerSize == 12) {
        width = littleShort(bytes, 18);
        height = littleShort(bytes, 20);
        planes = littleShort(bytes, 22);
        bits = littleShort(bytes, 24);
    } else {
        malformed(name, "unknown BMP header size " + std::to_string(headerSize));
    }
    if (planes != 1 || bits != 8) malformed(name, "not a one-plane 8-bit BMP");
    const bool topDown = height < 0;
    if (topDown) height = -height;
    if (width <= 0 || height <= 0 || width > kMaxImageDimension || height > kMaxImageDimension)
        malformed(name, "bad BMP size " + std::to_string(width) + "x" + std::to_string(height));
    PaletteIndexes out;
    out.width = width;
    out.height = height;
    const size_t rowBytes = size_t(width), total = rowBytes * size_t(height);
    if (dataOffset > bytes.size() || bytes.size() - dataOffset < total) malformed(name, "pixel data ends early");
    out.pixels.resize(total);
    for (size_t r = 0; r < size_t(height); ++r) {
        const size_t to = topDown ? size_t(height) - 1 - r : r;
        std::copy_n(bytes.begin() + std::ptrdiff_t(dataOffset + r * rowBytes), rowBytes,
                    out.pixels.begin() + std::ptrdiff_t(to * rowBytes));
    }
    return out;
}

}  // namespace q3::bspstage
