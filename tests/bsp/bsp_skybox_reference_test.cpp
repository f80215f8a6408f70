// _skybox against q3map2 2.5.17n on the skybox sample: the .srf (with the sky copies' parents) is
// byte-identical, so are the leafs (bounds grown by the copies), leaf surfaces and planes, and every
// surface, sky copies included, has q3map2's vertices (in another order where the known base
// winding difference puts a face's first corner elsewhere).
#include <gtest/gtest.h>

#include <algorithm>

#include "bsp_reference.h"
#include "bspfile.h"
#include "file_io.h"
#include "reference_fixture.h"
#include "test_data.h"

namespace q3::bspstage {
namespace {

namespace fs = std::filesystem;
using namespace q3::bspstage::test;

// Each surface's vertex records as sorted byte strings: the same set whatever the order.
std::vector<std::vector<std::string>> vertexSets(const bsp::Bsp& b) {
    std::vector<std::vector<std::string>> out;
    for (const bsp::Surface& s : b.surfaces) {
        std::vector<std::string> verts;
        for (int v = s.firstVert; v < s.firstVert + s.numVerts; ++v) {
            const auto* bytes = reinterpret_cast<const char*>(&b.drawVerts[size_t(v)]);
            verts.emplace_back(bytes, sizeof(bsp::DrawVert));
        }
        std::sort(verts.begin(), verts.end());
        out.push_back(std::move(verts));
    }
    return out;
}

class SkyboxReference : public conformance::ReferenceTest<int> {};

TEST_P(SkyboxReference, SkyCopiesEqualQ3map2s) {
    const auto [work, ours, theirs] = compileSampleBothWays(reference(), "skybox");
    const std::string srf = readFileText(ours / "skybox.srf");
    EXPECT_EQ(srf, readFileText(theirs / "skybox.srf"));
    EXPECT_NE(srf.find("\tparent "), std::string::npos) << "the sample should make sky copies";
    const bsp::Bsp a = bsp::readBsp(ours / "skybox.bsp"), b = bsp::readBsp(theirs / "skybox.bsp");
    for (int lump : {bsp::LUMP_PLANES, bsp::LUMP_LEAFS, bsp::LUMP_LEAFSURFACES, bsp::LUMP_SHADERS})
        EXPECT_TRUE(bsp::lumpBytes(a, lump) == bsp::lumpBytes(b, lump)) << bsp::lumpName(lump);
    EXPECT_EQ(vertexSets(a), vertexSets(b));
    fs::remove_all(work);
}

INSTANTIATE_TEST_SUITE_P(Samples, SkyboxReference, ::testing::Values(0));

}  // namespace
}  // namespace q3::bspstage
