// The misc_model autoclip shapes against q3map2 2.5.17n on the model_clip_modes sample (-meta):
// the same clip brushes, merged the same way. Every lump but the entities, the planes and the
// brushes and their sides is q3map2's byte for byte; the brushes come in the same order with the
// same content shaders and side planes within 0.01 (the edge bevels follow the brush windings,
// whose float rounding differs from q3map2's in the last bits: one brush gets one bevel more), and
// what collision sees agrees at random points. With -debugclip the clip brushes' faces are drawn
// as q3map2 draws them (the same surfaces by shader and size).
#include <gtest/gtest.h>

#include <set>
#include <string>
#include <tuple>

#include "bsp_compare.h"
#include "bsp_reference.h"
#include "bspfile.h"
#include "reference_fixture.h"

namespace q3::bspstage {
namespace {

namespace fs = std::filesystem;
using namespace q3::bspstage::test;

class ModelClipModesReference : public conformance::ReferenceTest<int> {};

TEST_P(ModelClipModesReference, ClipBrushesEqualQ3map2sWithinBevelRounding) {
    const SampleCompiles compiles = compileSampleBothWays(reference(), "model_clip_modes");
    const bsp::Bsp ours = bsp::readBsp(compiles.ours / "model_clip_modes.bsp");
    const bsp::Bsp theirs = bsp::readBsp(compiles.theirs / "model_clip_modes.bsp");
    for (int lump = 0; lump < bsp::kMaxLumps; ++lump) {
        if (lump == bsp::LUMP_ENTITIES || lump == bsp::LUMP_PLANES || lump == bsp::LUMP_BRUSHES ||
            lump == bsp::LUMP_BRUSHSIDES)
            continue;
        EXPECT_TRUE(bsp::lumpBytes(ours, lump) == bsp::lumpBytes(theirs, lump)) << bsp::lumpName(lump);
    }
    EXPECT_EQ(ours.planes.size(), theirs.planes.size());
    ASSERT_EQ(ours.brushes.size(), theirs.brushes.size());
    EXPECT_GT(ours.brushes.size(), 100u) << "the sample's clip brushes";
    const BrushPlaneComparison planes = compareBrushPlanes(ours, theirs);
    EXPECT_EQ(planes.otherShader, 0);
    EXPECT_LE(planes.otherSideCount, 1);
    EXPECT_LT(planes.worstPlane, 0.01);
    int equal = 0, solid = 0;
    const std::vector<Vec3> points = randomPoints(theirs, 40000, 17);
    for (const Vec3& p : points) {
        const int a = pointContents(ours, p), b = pointContents(theirs, p);
        equal += a == b ? 1 : 0;
        solid += b != 0 ? 1 : 0;
    }
    EXPECT_GE(equal, int(points.size()) - 2) << equal << " of " << points.size() << " points agree";
    std::printf("model clip modes: %zu brushes, %d with another side count, side planes within %.4g; %d of %zu points "
                "agree (%d solid in q3map2's)\n",
                ours.brushes.size(), planes.otherSideCount, planes.worstPlane, equal, points.size(), solid);
    fs::remove_all(compiles.work);
}

// The surfaces by shader, type and vertex and index counts (q3map2 orders the debugclip surfaces by
// the heap addresses of shaders without a script, which change from run to run).
std::multiset<std::tuple<std::string, int, int, int>> surfaceKinds(const bsp::Bsp& bsp) {
    std::multiset<std::tuple<std::string, int, int, int>> out;
    for (const bsp::Surface& s : bsp.surfaces)
        out.emplace(bsp.shaders[size_t(s.shaderNum)].name, s.surfaceType, s.numVerts, s.numIndexes);
    return out;
}

TEST_P(ModelClipModesReference, DebugClipDrawsTheClipBrushFacesAsQ3map2Does) {
    const SampleCompiles compiles = compileSampleBothWays(reference(), "model_clip_modes", {"-debugclip"});
    const bsp::Bsp ours = bsp::readBsp(compiles.ours / "model_clip_modes.bsp");
    const bsp::Bsp theirs = bsp::readBsp(compiles.theirs / "model_clip_modes.bsp");
    EXPECT_TRUE(bsp::lumpBytes(ours, bsp::LUMP_SHADERS) == bsp::lumpBytes(theirs, bsp::LUMP_SHADERS));
    const auto kinds = surfaceKinds(ours);
    EXPECT_TRUE(kinds == surfaceKinds(theirs)) << ours.surfaces.size() << " against " << theirs.surfaces.size();
    int debugFaces = 0;
    for (const auto& [shader, type, verts, indexes] : kinds) debugFaces += shader.starts_with("debugclip") ? 1 : 0;
    EXPECT_GT(debugFaces, 100);
    fs::remove_all(compiles.work);
}

INSTANTIATE_TEST_SUITE_P(Samples, ModelClipModesReference, ::testing::Values(0));

}  // namespace
}  // namespace q3::bspstage
