#include "image_builders.h"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <cstdio>
#include <map>
#include <stdexcept>

#include <jpeglib.h>
#include <zlib.h>

namespace q3::test {

Image patternImage(int width, int height, bool opaque) {
    Image image;
    image.width = width;
    image.height = height;
    image.rgba.resize(size_t(width) * height * 4);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            uint8_t* p = &image.rgba[(size_t(y) * width + x) * 4];
            p[0] = uint8_t(x * 37 + y * 11);
            p[1] = uint8_t(y * 53 + 7);
            p[2] = uint8_t((x ^ y) * 29);
            p[3] = opaque ? 255 : uint8_t(x * 13 + y * 71 + 3);
        }
    return image;
}

namespace {

void put16(std::vector<uint8_t>& out, unsigned v) {
    out.push_back(uint8_t(v & 0xFF));
    out.push_back(uint8_t(v >> 8));
}

void put32be(std::vector<uint8_t>& out, uint32_t v) {
    for (int shift = 24; shift >= 0; shift -= 8) out.push_back(uint8_t(v >> shift));
}

}  // namespace

std::vector<uint8_t> buildTga(const Image& image, const TgaLayout& layout) {
    const int baseType = layout.type > 8 ? layout.type - 8 : layout.type;
    const bool rle = layout.type > 8;
    std::vector<std::array<uint8_t, 4>> palette;
    std::map<std::array<uint8_t, 4>, int> paletteIndex;
    if (baseType == 1) {
        for (size_t i = 0; i < image.rgba.size(); i += 4) {
            std::array<uint8_t, 4> c{image.rgba[i], image.rgba[i + 1], image.rgba[i + 2], image.rgba[i + 3]};
            if (paletteIndex.emplace(c, int(palette.size())).second) palette.push_back(c);
        }
        if (palette.size() > 256) throw std::runtime_error("too many colours for a test palette");
    }
    const int pixelBytes = (layout.bits + 7) / 8;
    auto encodePixel = [&](const uint8_t* p) {
        std::vector<uint8_t> out;
        if (baseType == 1) {
            out.push_back(uint8_t(paletteIndex.at({p[0], p[1], p[2], p[3]})));
        } else if (baseType == 3) {
            out.push_back(p[0]);
            if (layout.bits == 16) out.push_back(p[3]);
        } else if (layout.bits == 16 || layout.bits == 15) {
            unsigned v = unsigned(p[0] >> 3) << 10 | unsigned(p[1] >> 3) << 5 | unsigned(p[2] >> 3);
            if (p[3] >= 128) v |= 0x8000;
            put16(out, v);
        } else {
            out = {p[2], p[1], p[0]};
            if (layout.bits == 32) out.push_back(p[3]);
        }
        return out;
    };

    std::vector<uint8_t> out(18, 0);
    out[0] = uint8_t(layout.idLength);
    out[2] = uint8_t(layout.type);
    if (baseType == 1) {
        out[1] = 1;
        out[5] = uint8_t(palette.size() & 0xFF);
        out[6] = uint8_t(palette.size() >> 8);
        out[7] = 32;
    }
    out[12] = uint8_t(image.width & 0xFF);
    out[13] = uint8_t(image.width >> 8);
    out[14] = uint8_t(image.height & 0xFF);
    out[15] = uint8_t(image.height >> 8);
    out[16] = uint8_t(layout.bits);
    const int alphaBits = layout.alphaBits >= 0 ? layout.alphaBits : (layout.bits == 32 ? 8 : 0);
    out[17] = uint8_t(alphaBits | (layout.topOrigin ? 0x20 : 0) | (layout.rightOrigin ? 0x10 : 0));
    for (int i = 0; i < layout.idLength; ++i) out.push_back(uint8_t('a' + i % 26));
    for (const auto& c : palette) out.insert(out.end(), {c[2], c[1], c[0], c[3]});

    std::vector<std::vector<uint8_t>> stored;  // pixels in file order
    for (int row = 0; row < image.height; ++row) {
        const int y = layout.topOrigin ? row : image.height - 1 - row;
        for (int col = 0; col < image.width; ++col) {
            const int x = layout.rightOrigin ? image.width - 1 - col : col;
            stored.push_back(encodePixel(image.texel(x, y)));
        }
    }
    if (!rle) {
        for (const auto& p : stored) out.insert(out.end(), p.begin(), p.end());
        return out;
    }
    // Runs of equal pixels become run packets, everything else raw packets; packets cross rows.
    size_t i = 0;
    while (i < stored.size()) {
        size_t run = 1;
        while (i + run < stored.size() && run < 128 && stored[i + run] == stored[i]) ++run;
        if (run >= 2) {
            out.push_back(uint8_t(0x80 | (run - 1)));
            out.insert(out.end(), stored[i].begin(), stored[i].end());
            i += run;
            continue;
        }
        size_t raw = 1;
        while (i + raw < stored.size() && raw < 128 &&
               !(i + raw + 1 < stored.size() && stored[i + raw] == stored[i + raw + 1]))
            ++raw;
        out.push_back(uint8_t(raw - 1));
        for (size_t k = 0; k < raw; ++k) out.insert(out.end(), stored[i + k].begin(), stored[i + k].end());
        i += raw;
    }
    (void)pixelBytes;
    return out;
}

std::vector<uint8_t> buildPng(int width, int height, int bitDepth, int colorType,
                              const std::vector<std::vector<uint8_t>>& rows, const std::vector<PngChunk>& extra) {
    std::vector<uint8_t> out = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    auto chunk = [&](const std::string& type, const std::vector<uint8_t>& data) {
        put32be(out, uint32_t(data.size()));
        const size_t start = out.size();
        out.insert(out.end(), type.begin(), type.end());
        out.insert(out.end(), data.begin(), data.end());
        put32be(out, uint32_t(crc32(0, out.data() + start, uInt(out.size() - start))));
    };
    std::vector<uint8_t> ihdr;
    put32be(ihdr, uint32_t(width));
    put32be(ihdr, uint32_t(height));
    ihdr.insert(ihdr.end(), {uint8_t(bitDepth), uint8_t(colorType), 0, 0, 0});
    chunk("IHDR", ihdr);
    for (const PngChunk& c : extra) chunk(c.type, c.data);
    std::vector<uint8_t> raw;
    for (const auto& row : rows) {
        raw.push_back(0);  // filter: none
        raw.insert(raw.end(), row.begin(), row.end());
    }
    uLongf packedSize = compressBound(uLong(raw.size()));
    std::vector<uint8_t> packed(packedSize);
    if (compress(packed.data(), &packedSize, raw.data(), uLong(raw.size())) != Z_OK)
        throw std::runtime_error("zlib compress failed");
    packed.resize(packedSize);
    chunk("IDAT", packed);
    chunk("IEND", {});
    return out;
}

std::vector<uint8_t> buildJpeg(int width, int height, int components, const std::vector<uint8_t>& pixels,
                               int quality) {
    jpeg_compress_struct info{};
    jpeg_error_mgr error{};
    info.err = jpeg_std_error(&error);
    jpeg_create_compress(&info);
    unsigned char* buffer = nullptr;
    unsigned long size = 0;
    jpeg_mem_dest(&info, &buffer, &size);
    info.image_width = unsigned(width);
    info.image_height = unsigned(height);
    info.input_components = components;
    info.in_color_space = components == 1 ? JCS_GRAYSCALE : components == 4 ? JCS_CMYK : JCS_RGB;
    jpeg_set_defaults(&info);
    jpeg_set_quality(&info, quality, TRUE);
    jpeg_start_compress(&info, TRUE);
    while (info.next_scanline < info.image_height) {
        JSAMPROW row = const_cast<uint8_t*>(pixels.data()) + size_t(info.next_scanline) * width * components;
        jpeg_write_scanlines(&info, &row, 1);
    }
    jpeg_finish_compress(&info);
    std::vector<uint8_t> out(buffer, buffer + size);
    jpeg_destroy_compress(&info);
    std::free(buffer);
    return out;
}

}  // namespace q3::test
