// The index map's pixel look-up, layer blending and layer shader names (q3map2
// GetShaderIndexForPoint, GetIndexedShader) on a hand-made 4x2 map.
#include <gtest/gtest.h>

#include <vector>

#include "index_map.h"

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

}  // namespace
}  // namespace q3::bspstage
