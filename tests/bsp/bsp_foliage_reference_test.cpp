// q3map_foliage against q3map2 2.5.17n on the foliage sample (-meta): the same Foliage surface
// (the model's vertices and one vertex per copy, in the same places, drawn by the same rand()
// sequence), so every lump but the entities is q3map2's, and so are the .srf and .prt. The sample's
// curved floor patch is the one exception q3map2 2.5.17n itself allows: its vertex normals may
// differ in the last bit.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstring>

#include "bsp_reference.h"
#include "bsp_samples.h"
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
    const fs::path work = q3::test::tempDir() / ("foliage-" + std::to_string(::getpid()));
    const fs::path ours = compileSample("foliage", work / "ours");
    const fs::path theirs = referenceSampleCompile(reference(), "foliage", work / "ref");
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
    // The sample must exercise what it claims: one Foliage surface with many copies, each copy a
    // vertex after the model's, standing on the floor.
    int foliage = 0;
    for (const bsp::Surface& s : a.surfaces) {
        if (s.surfaceType != bsp::MST_FOLIAGE) continue;
        ++foliage;
        EXPECT_GT(s.patchWidth, 50) << "copies";
        EXPECT_EQ(s.numVerts, s.patchWidth + s.patchHeight);
        for (int k = s.patchHeight; k < s.numVerts; ++k) {
            EXPECT_EQ(a.drawVerts[size_t(s.firstVert + k)].xyz[2], 0.0f) << "copy " << k - s.patchHeight;
            EXPECT_EQ(a.drawVerts[size_t(s.firstVert + k)].normal[2], 1.0f) << "copy " << k - s.patchHeight;
        }
    }
    EXPECT_EQ(foliage, 1);
    fs::remove_all(work);
}

INSTANTIATE_TEST_SUITE_P(Samples, FoliageReference, ::testing::Values(0));

}  // namespace
}  // namespace q3::bspstage
