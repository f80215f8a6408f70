// q3map_foliage against q3map2 2.5.17n on the foliage sample (-meta): the same Foliage surfaces
// (the model's vertices and one vertex per copy, in the same places, drawn by the same rand()
// sequence) on the floor's meta surface and on a curved patch, so every lump but the entities is
// q3map2's, and so are the .srf and .prt. Vertex normals may differ in the last bit: the curved
// patch's own (a difference of patch normals), and so the copies' on it, which average them.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "bsp_reference.h"
#include "bspfile.h"
#include "file_io.h"
#include "reference_fixture.h"
#include "test_data.h"

namespace q3::bspstage {
namespace {

namespace fs = std::filesystem;
using namespace q3::bspstage::test;

class FoliageReference : public conformance::ReferenceTest<int> {};

TEST_P(FoliageReference, FoliageSurfaceEqualsQ3map2s) {
    const auto [work, ours, theirs] = compileSampleBothWays(reference(), "foliage");
    const bsp::Bsp a = bsp::readBsp(ours / "foliage.bsp"), b = bsp::readBsp(theirs / "foliage.bsp");
    for (int lump = 0; lump < bsp::kMaxLumps; ++lump)
        if (lump != bsp::LUMP_ENTITIES && lump != bsp::LUMP_DRAWVERTS)
            EXPECT_TRUE(bsp::lumpBytes(a, lump) == bsp::lumpBytes(b, lump)) << bsp::lumpName(lump);
    EXPECT_EQ(readFileText(ours / "foliage.srf"), readFileText(theirs / "foliage.srf"));
    EXPECT_EQ(readFileText(ours / "foliage.prt"), readFileText(theirs / "foliage.prt"));

    ASSERT_EQ(a.drawVerts.size(), b.drawVerts.size());
    for (size_t i = 0; i < a.drawVerts.size(); ++i) {
        const bsp::DrawVert &va = a.drawVerts[i], &vb = b.drawVerts[i];
        EXPECT_TRUE(std::memcmp(va.xyz, vb.xyz, sizeof va.xyz) == 0 && std::memcmp(va.st, vb.st, sizeof va.st) == 0 &&
                    std::memcmp(va.color, vb.color, sizeof va.color) == 0)
            << "vertex " << i;
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(va.normal[c], vb.normal[c], 1e-6) << "vertex " << i;
    }
    // The sample must exercise what it claims: a Foliage surface for the patch (found first) and
    // one for the floor, each copy a vertex after the model's, on the hump or flat on the floor.
    std::vector<int> copies;
    for (const bsp::Surface& s : a.surfaces) {
        if (s.surfaceType != bsp::MST_FOLIAGE) continue;
        copies.push_back(s.patchWidth);
        EXPECT_EQ(s.numVerts, s.patchWidth + s.patchHeight);
        const bool onPatch = copies.size() == 1;
        for (int k = s.patchHeight; k < s.numVerts; ++k) {
            const bsp::DrawVert& v = a.drawVerts[size_t(s.firstVert + k)];
            EXPECT_TRUE(onPatch ? v.xyz[2] > 0 && v.normal[2] >= 0.5f : v.xyz[2] == 0 && v.normal[2] == 1.0f)
                << "copy " << k - s.patchHeight << " of foliage surface " << copies.size();
        }
    }
    ASSERT_EQ(copies.size(), 2u);
    EXPECT_GT(copies[0], 5);
    EXPECT_GT(copies[1], 50);
    fs::remove_all(work);
}

INSTANTIATE_TEST_SUITE_P(Samples, FoliageReference, ::testing::Values(0));

}  // namespace
}  // namespace q3::bspstage
