// Truevision TGA: decoding of every type Quake 3 era tools produce, and the uncompressed writer used
// for external lightmaps.
#include "image.h"

#include <array>
#include <string>

namespace q3 {

namespace {

enum TgaType : uint8_t {
    kColorMapped = 1,
    kTrueColor = 2,
    kGrey = 3,
    kRleColorMapped = 9,
    kRleTrueColor = 10,
    kRleGrey = 11,
};

struct TgaHeader {
    uint8_t idLength, colorMapType, imageType;
    uint16_t colorMapFirst, colorMapLength;
    uint8_t colorMapEntryBits;
    uint16_t width, height;
    uint8_t pixelBits, descriptor;
};

constexpr size_t kTgaHeaderSize = 18;

uint16_t readU16(const uint8_t* p) { return uint16_t(p[0] | (p[1] << 8)); }

[[noreturn]] void fail(std::string_view name, const std::string& what) {
    throw ImageError(std::string(name) + ": bad TGA: " + what);
}

// Converts one stored pixel of `bits` bits to RGBA. 16-bit pixels are A1R5G5B5; their alpha bit is
// honoured only when the header declares alpha bits, since many writers leave it zero.
std::array<uint8_t, 4> unpackPixel(const uint8_t* p, int bits, bool grey, bool alpha16) {
    switch (bits) {
        case 8: return {p[0], p[0], p[0], 255};
        case 15:
        case 16: {
            if (grey) return {p[0], p[0], p[0], p[1]};  // 16-bit grey + alpha
            unsigned v = readU16(p);
            auto expand = [](unsigned c) { return uint8_t((c << 3) | (c >> 2)); };
            uint8_t a = (alpha16 && bits == 16) ? ((v & 0x8000) ? 255 : 0) : 255;
            return {expand((v >> 10) & 31), expand((v >> 5) & 31), expand(v & 31), a};
        }
        case 24: return {p[2], p[1], p[0], 255};
        default: return {p[2], p[1], p[0], p[3]};  // 32
    }
}

TgaHeader parseHeader(std::span<const uint8_t> bytes, std::string_view name) {
    if (bytes.size() < kTgaHeaderSize) fail(name, "file is shorter than the 18-byte header");
    const uint8_t* h = bytes.data();
    return TgaHeader{h[0], h[1], h[2], readU16(h + 3), readU16(h + 5), h[7],
                     readU16(h + 12), readU16(h + 14), h[16], h[17]};
}

}  // namespace

Image decodeTga(std::span<const uint8_t> bytes, std::string_view name) {
    const TgaHeader header = parseHeader(bytes, name);
    const uint8_t type = header.imageType;
    const bool rle = type >= 9;
    const uint8_t baseType = rle ? uint8_t(type - 8) : type;
    if (baseType != kColorMapped && baseType != kTrueColor && baseType != kGrey)
        fail(name, "unsupported image type " + std::to_string(type));
    if (header.width == 0 || header.height == 0) fail(name, "zero width or height");
    if (header.width > kMaxImageDimension || header.height > kMaxImageDimension)
        fail(name, "size " + std::to_string(header.width) + "x" + std::to_string(header.height) + " exceeds " +
                       std::to_string(kMaxImageDimension));

    const int bits = header.pixelBits;
    const bool grey = baseType == kGrey;
    bool bitsOk = false;
    if (baseType == kColorMapped) bitsOk = bits == 8 || bits == 16;
    else if (grey) bitsOk = bits == 8 || bits == 16;
    else bitsOk = bits == 15 || bits == 16 || bits == 24 || bits == 32;
    if (!bitsOk) fail(name, std::to_string(bits) + " bits per pixel is not valid for type " + std::to_string(type));
    const size_t pixelBytes = size_t(bits + 7) / 8;

    size_t offset = kTgaHeaderSize + header.idLength;
    if (offset > bytes.size()) fail(name, "truncated in the image id field");

    // The colour map, when present, is skipped for true-colour images and decoded for mapped ones.
    std::vector<std::array<uint8_t, 4>> palette;
    if (header.colorMapType == 1) {
        const int entryBits = header.colorMapEntryBits;
        if (entryBits != 15 && entryBits != 16 && entryBits != 24 && entryBits != 32)
            fail(name, "colour map entries of " + std::to_string(entryBits) + " bits");
        const size_t entryBytes = size_t(entryBits + 7) / 8;
        const size_t mapBytes = entryBytes * header.colorMapLength;
        if (offset + mapBytes > bytes.size()) fail(name, "truncated in the colour map");
        for (size_t i = 0; i < header.colorMapLength; ++i)
            palette.push_back(unpackPixel(bytes.data() + offset + i * entryBytes, entryBits, false, true));
        offset += mapBytes;
    } else if (header.colorMapType != 0) {
        fail(name, "colour map type " + std::to_string(header.colorMapType));
    }
    if (baseType == kColorMapped && palette.empty()) fail(name, "colour-mapped image without a colour map");

    const size_t pixelCount = size_t(header.width) * header.height;
    const size_t available = bytes.size() - offset;
    // Reject before allocating: raw data must be all there; RLE needs at least one packet (a header
    // byte and one pixel) per 128 pixels.
    if (!rle && available < pixelCount * pixelBytes) fail(name, "pixel data truncated");
    if (rle && available < (pixelCount + 127) / 128 * (1 + pixelBytes)) fail(name, "RLE pixel data truncated");

    const bool alpha16 = (header.descriptor & 0x0F) != 0;
    auto toRgba = [&](const uint8_t* p) -> std::array<uint8_t, 4> {
        if (baseType != kColorMapped) return unpackPixel(p, bits, grey, alpha16);
        unsigned index = bits == 8 ? p[0] : readU16(p);
        if (index < header.colorMapFirst || index - header.colorMapFirst >= palette.size())
            fail(name, "colour index " + std::to_string(index) + " outside the colour map");
        return palette[index - header.colorMapFirst];
    };

    // Decode in file order, then place rows according to the origin bits.
    std::vector<uint8_t> stored(pixelCount * 4);
    const uint8_t* src = bytes.data() + offset;
    const uint8_t* end = bytes.data() + bytes.size();
    size_t done = 0;
    if (!rle) {
        for (; done < pixelCount; ++done, src += pixelBytes) {
            auto c = toRgba(src);
            std::copy(c.begin(), c.end(), stored.begin() + done * 4);
        }
    } else {
        while (done < pixelCount) {
            if (src >= end) fail(name, "RLE pixel data truncated");
            const uint8_t packet = *src++;
            const size_t count = size_t(packet & 0x7F) + 1;
            if (done + count > pixelCount) fail(name, "RLE packet runs past the end of the image");
            const bool run = packet & 0x80;
            const size_t need = run ? pixelBytes : pixelBytes * count;
            if (size_t(end - src) < need) fail(name, "RLE pixel data truncated");
            for (size_t i = 0; i < count; ++i) {
                auto c = toRgba(run ? src : src + i * pixelBytes);
                std::copy(c.begin(), c.end(), stored.begin() + (done + i) * 4);
            }
            src += need;
            done += count;
        }
    }

    Image image;
    image.width = header.width;
    image.height = header.height;
    image.rgba.resize(pixelCount * 4);
    const bool topOrigin = header.descriptor & 0x20;
    const bool rightOrigin = header.descriptor & 0x10;
    const size_t rowBytes = size_t(image.width) * 4;
    for (int row = 0; row < image.height; ++row) {
        const int destRow = topOrigin ? row : image.height - 1 - row;
        const uint8_t* from = stored.data() + row * rowBytes;
        uint8_t* to = image.rgba.data() + destRow * rowBytes;
        if (!rightOrigin) {
            std::copy(from, from + rowBytes, to);
        } else {
            for (int x = 0; x < image.width; ++x)
                std::copy(from + x * 4, from + x * 4 + 4, to + (image.width - 1 - x) * 4);
        }
    }
    return image;
}

std::vector<uint8_t> encodeTga(const Image& image, bool alpha) {
    if (image.empty() || image.width > 0xFFFF || image.height > 0xFFFF ||
        image.rgba.size() != size_t(image.width) * image.height * 4)
        throw ImageError("encodeTga: image of " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                         " cannot be written");
    const size_t pixelBytes = alpha ? 4 : 3;
    std::vector<uint8_t> out(kTgaHeaderSize + size_t(image.width) * image.height * pixelBytes);
    out[2] = kTrueColor;
    out[12] = uint8_t(image.width & 0xFF);
    out[13] = uint8_t(image.width >> 8);
    out[14] = uint8_t(image.height & 0xFF);
    out[15] = uint8_t(image.height >> 8);
    out[16] = uint8_t(pixelBytes * 8);
    out[17] = alpha ? 8 : 0;  // bottom-left origin; alpha bits
    uint8_t* dst = out.data() + kTgaHeaderSize;
    for (int row = image.height - 1; row >= 0; --row) {
        for (int x = 0; x < image.width; ++x) {
            const uint8_t* p = image.texel(x, row);
            *dst++ = p[2];
            *dst++ = p[1];
            *dst++ = p[0];
            if (alpha) *dst++ = p[3];
        }
    }
    return out;
}

}  // namespace q3
