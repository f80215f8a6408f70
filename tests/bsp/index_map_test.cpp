// The index map's pixel look-up, layer blending and layer shader names (q3map2
// GetShaderIndexForPoint, GetIndexedShader) on a hand-made 4x2 map, and the 8-bit PCX and BMP
// readers (q3map2 LoadPCX, LoadBMP) on hand-made files.
#include <gtest/gtest.h>

#include <vector>

#include "image.h"
#include "index_map.h"
#include "index_map_formats.h"

namespace q3::bspstage {
namespace {

// Layers 0..3 along x on the top row, 4..7 on the bottom one, over x 0..400 and y 0..100.
IndexMap stripes() {
    IndexMap im;
    im.baseShader = "t/ground";
    im.layers = 8;
    im.width = 4;
    im.height = 2;
    im.pixels = {0, 1, 2, 3, 4, 5, 6, 7};
    for (int i = 0; i < 8; ++i) im.offsets[size_t(i)] = float(i) * 2;
    im.bounds.add({0, 0, 0});
    im.bounds.add({400, 100, 64});
    return im;
}

TEST(IndexMap, PixelsSpanTheBoundsWithTheTopRowAtTheLargestY) {
    const IndexMap im = stripes();
    EXPECT_EQ(im.layerAt({0, 100, 0}), 0);
    EXPECT_EQ(im.layerAt({99.9f, 51, 0}), 0);
    EXPECT_EQ(im.layerAt({100, 51, 0}), 1);   // s = 0.25 starts the second column
    EXPECT_EQ(im.layerAt({399, 99, 0}), 3);
    EXPECT_EQ(im.layerAt({0, 50, 0}), 4);     // t = 0.5 starts the second row
    EXPECT_EQ(im.layerAt({400, 0, 0}), 7);    // the far edges clamp to the last pixel
    EXPECT_EQ(im.layerAt({-50, 300, 0}), 0);  // outside the bounds: the nearest edge pixel
    EXPECT_EQ(im.layerAt({900, -300, 0}), 7);
}

TEST(IndexMap, AZeroSizedAxisReadsTheFirstPixelColumn) {
    IndexMap im = stripes();
    im.bounds.maxs.x = im.bounds.mins.x;
    EXPECT_EQ(im.layerAt({0, 0, 0}), 4);  // 0 / 0 is not a number
    EXPECT_EQ(im.layerAt({5, 99, 0}), 0); // x / 0 is infinite
}

TEST(IndexMap, TheHighestLayerIsOpaqueAndNamesTheShader) {
    const IndexMap im = stripes();
    const std::vector<Vec3> mixed = {{0, 100, 0}, {150, 100, 0}, {150, 20, 0}};
    const LayeredVertices v = im.layer(mixed);
    EXPECT_EQ(v.lowest, 0);
    EXPECT_EQ(v.highest, 5);
    EXPECT_EQ(v.alpha, (std::vector<uint8_t>{0, 0, 255}));
    EXPECT_EQ(v.zOffset, (std::vector<float>{0, 2, 10}));
    EXPECT_EQ(im.layerShaderName(v), "textures/t/ground_0to5");

    const std::vector<Vec3> one = {{250, 80, 0}, {260, 90, 0}, {290, 60, 0}};
    const LayeredVertices same = im.layer(one);
    EXPECT_EQ(same.alpha, (std::vector<uint8_t>{255, 255, 255}));
    EXPECT_EQ(im.layerShaderName(same), "textures/t/ground_2");
}

// A 3x2 PCX (xmax 2, ymax 1) with `lineBytes` bytes per scan line and the given RLE data.
std::vector<uint8_t> pcx(int lineBytes, std::vector<uint8_t> data) {
    std::vector<uint8_t> out(128, 0);
    out[0] = 0x0a;
    out[1] = 5;
    out[2] = 1;
    out[3] = 8;
    out[8] = 2;   // xmax
    out[10] = 1;  // ymax
    out[65] = 1;  // one plane
    out[66] = uint8_t(lineBytes);
    out.insert(out.end(), data.begin(), data.end());
    return out;
}

TEST(IndexMapFormats, PcxRunsAndScanLinePadding) {
    // Row 0: a run of two 7s and a literal 1, then one padding run skipped; row 1: a run of three 0xc5.
    const PaletteIndexes p = decodePcxIndexes(pcx(4, {0xc2, 7, 1, 9, 0xc3, 0xc5, 0}), "a.pcx");
    EXPECT_EQ(p.width, 3);
    EXPECT_EQ(p.height, 2);
    EXPECT_EQ(p.pixels, (std::vector<uint8_t>{7, 7, 1, 0xc5, 0xc5, 0xc5}));
    // A run past the end of a row spills into the next one, which overwrites it.
    EXPECT_EQ(decodePcxIndexes(pcx(3, {0xc4, 2, 3, 4, 5}), "b.pcx").pixels,
              (std::vector<uint8_t>{2, 2, 2, 3, 4, 5}));
    EXPECT_THROW(decodePcxIndexes(pcx(3, {0xc4}), "short.pcx"), ImageError);
    std::vector<uint8_t> wrongVersion = pcx(3, {1, 2, 3, 4, 5, 6});
    wrongVersion[1] = 3;
    EXPECT_THROW(decodePcxIndexes(wrongVersion, "v3.pcx"), ImageError);
}

// A 2x2 8-bit BMP (40-byte header, no palette) of `height` (negative: top-down) and pixel rows.
std::vector<uint8_t> bmp(int32_t height, std::vector<uint8_t> rows, uint16_t bits = 8) {
    std::vector<uint8_t> out(54, 0);
    auto put32 = [&](size_t at, uint32_t v) {
        for (int i = 0; i < 4; ++i) out[at + size_t(i)] = uint8_t(v >> (8 * i));
    };
    out[0] = 'B';
    out[1] = 'M';
    put32(10, 54);  // pixel data offset
    put32(14, 40);
    put32(18, 2);
    put32(22, uint32_t(height));
    out[26] = 1;
    out[28] = uint8_t(bits);
    out.insert(out.end(), rows.begin(), rows.end());
    return out;
}

TEST(IndexMapFormats, BmpRowsInFileOrderUnlessTopDown) {
    EXPECT_EQ(decodeBmpIndexes(bmp(2, {1, 2, 3, 4}), "up.bmp").pixels, (std::vector<uint8_t>{1, 2, 3, 4}));
    EXPECT_EQ(decodeBmpIndexes(bmp(-2, {1, 2, 3, 4}), "down.bmp").pixels, (std::vector<uint8_t>{3, 4, 1, 2}));
    EXPECT_THROW(decodeBmpIndexes(bmp(2, {1, 2, 3}), "short.bmp"), ImageError);
    EXPECT_THROW(decodeBmpIndexes(bmp(2, {1, 2, 3, 4}, 24), "rgb.bmp"), ImageError);
}

}  // namespace
}  // namespace q3::bspstage
