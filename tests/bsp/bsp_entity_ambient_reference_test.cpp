// Ambient light per entity against q3map2 2.5.17n on the entity_ambient sample: our .srf carries
// the worldspawn's _color x ambient in its default block and the func_door's own on its surfaces,
// as q3map2's does, and both -light stages give each surface the ambient of its block.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>

#include "bsp_reference.h"
#include "bspfile.h"
#include "file_io.h"
#include "reference_fixture.h"
#include "test_data.h"

namespace q3::bspstage {
namespace {

namespace fs = std::filesystem;
using namespace q3::bspstage::test;

// Mean lightmap colour of a model's lightmapped surfaces: the texels whose centres lie inside the box
// of each surface's vertex lightmap coordinates (q3map2 leaves the surface records' rectangles zero).
std::array<double, 3> modelLightmapMean(const bsp::Bsp& map, size_t model) {
    std::array<double, 3> sum{};
    double texels = 0;
    const bsp::Model& m = map.models.at(model);
    for (int i = m.firstSurface; i < m.firstSurface + m.numSurfaces; ++i) {
        const bsp::Surface& s = map.surfaces.at(size_t(i));
        if (s.lightmapNum < 0 || s.numVerts == 0) continue;
        std::array<float, 2> lo{1e9f, 1e9f}, hi{-1e9f, -1e9f};
        for (int v = s.firstVert; v < s.firstVert + s.numVerts; ++v)
            for (size_t a = 0; a < 2; ++a) {
                lo[a] = std::min(lo[a], map.drawVerts.at(size_t(v)).lightmap[a] * 128.0f);
                hi[a] = std::max(hi[a], map.drawVerts.at(size_t(v)).lightmap[a] * 128.0f);
            }
        for (int y = 0; y < 128; ++y)
            for (int x = 0; x < 128; ++x) {
                if (x + 0.5f < lo[0] || x + 0.5f > hi[0] || y + 0.5f < lo[1] || y + 0.5f > hi[1]) continue;
                const size_t at = (size_t(s.lightmapNum) * 128 * 128 + size_t(y) * 128 + size_t(x)) * 3;
                for (size_t ch = 0; ch < 3; ++ch) sum[ch] += map.lightmaps.at(at + ch);
                ++texels;
            }
    }
    for (double& v : sum) v /= std::max(1.0, texels);
    return sum;
}

class EntityAmbientReference : public conformance::ReferenceTest<int> {};

TEST_P(EntityAmbientReference, SrfAndLightmapsFollowEachEntitysAmbient) {
    const SampleCompiles compiles = compileSampleBothWays(reference(), "entity_ambient");
    const std::string srf = readFileText(compiles.ours / "entity_ambient.srf");
    EXPECT_EQ(srf, readFileText(compiles.theirs / "entity_ambient.srf"));
    EXPECT_NE(srf.find("default\n{\n\tcastShadows 1\n\treceiveShadows 1\n\tsampleSize 16\n"
                       "\tambientColor ( 4.000000 2.000000 1.000000 )"),
              std::string::npos);
    EXPECT_NE(srf.find("\tambientColor ( 3.000000 6.000000 0.000000 )"), std::string::npos);

    // Both -light stages on our BSP and .srf (the samples' game folder beside each copy).
    std::array<bsp::Bsp, 2> lit;
    const std::array<std::string, 2> tools = {q3::test::shellQuote(q3::test::q3map2Exe()),
                                              q3::test::shellQuote(reference())};
    for (size_t t = 0; t < 2; ++t) {
        const fs::path root = compiles.work / (t == 0 ? "light-ours" : "light-ref");
        fs::copy(compiles.ours.parent_path().parent_path(), root, fs::copy_options::recursive);
        const fs::path bsp = root / "samples" / "maps" / "entity_ambient.bsp";
        std::string output;
        const std::string command = tools[t] + " -fs_basepath " + q3::test::shellQuote(root) +
                                    " -fs_basegame samples -light -fast " + q3::test::shellQuote(bsp);
        ASSERT_EQ(q3::test::runCommand(command, &output), 0) << output;
        lit[t] = bsp::readBsp(bsp);
        ASSERT_FALSE(lit[t].lightmaps.empty()) << command << "\n" << output;
    }
    // The door (model 1) takes its own ambient (3 6 0), the world its default (4 2 1): the same in both.
    for (size_t model : {0u, 1u}) {
        const std::array<double, 3> ours = modelLightmapMean(lit[0], model), theirs = modelLightmapMean(lit[1], model);
        for (size_t ch = 0; ch < 3; ++ch)
            EXPECT_NEAR(ours[ch], theirs[ch], 0.5) << "model " << model << " channel " << ch;
    }
    fs::remove_all(compiles.work);
}

INSTANTIATE_TEST_SUITE_P(Samples, EntityAmbientReference, ::testing::Values(0));

}  // namespace
}  // namespace q3::bspstage
