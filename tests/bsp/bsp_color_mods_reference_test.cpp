// Vertex colour modifiers against q3map2 2.5.17n on the color_mods sample (-meta): shader colorGen /
// colorMod / rgbGen / rgbMod / alphaGen / alphaMod steps and colorMod volume brushes give the same
// bytes in every lump but the entities, and the same .srf and .prt.
#include <gtest/gtest.h>

#include <set>

#include "bsp_reference.h"
#include "bspfile.h"
#include "reference_fixture.h"
#include "test_data.h"

namespace q3::bspstage {
namespace {

namespace fs = std::filesystem;
using namespace q3::bspstage::test;

class ColorModsReference : public conformance::ReferenceTest<int> {};

TEST_P(ColorModsReference, EveryLumpButTheEntitiesEqualsQ3map2s) {
    const SampleCompiles compiles = compileSampleBothWays(reference(), "color_mods");
    expectSampleOutputsEqual(compiles, "color_mods");
    const bsp::Bsp a = bsp::readBsp(compiles.ours / "color_mods.bsp");
    // The sample must exercise what it claims: vertexes of many colours and alphas, not all white.
    std::set<uint32_t> colours;
    size_t notWhite = 0;
    for (const bsp::DrawVert& v : a.drawVerts) {
        colours.insert(uint32_t(v.color[0]) | uint32_t(v.color[1]) << 8 | uint32_t(v.color[2]) << 16 |
                       uint32_t(v.color[3]) << 24);
        notWhite += v.color[0] != 255 || v.color[1] != 255 || v.color[2] != 255 || v.color[3] != 255;
    }
    EXPECT_GT(colours.size(), 12u);
    EXPECT_GT(notWhite, 40u);
    fs::remove_all(compiles.work);
}

INSTANTIATE_TEST_SUITE_P(Samples, ColorModsReference, ::testing::Values(0));

}  // namespace
}  // namespace q3::bspstage
