// misc_model autoclip against q3map2 2.5.17n on the model_clip sample: the same clip brushes
// (coplanar triangles merged into one brush per polygon), in the same order with the same side
// planes up to the last bits of the bevels, and the same contents at points around the models and
// behind every clipped triangle but the cone's.
#include <gtest/gtest.h>

#include "bsp_compare.h"
#include "bsp_reference.h"
#include "bspfile.h"
#include "reference_fixture.h"
#include "test_data.h"

namespace q3::bspstage {
namespace {

namespace fs = std::filesystem;
using namespace q3::bspstage::test;

class ModelClipReference : public conformance::ReferenceTest<int> {};

TEST_P(ModelClipReference, ContentsAroundClippedModelsEqualQ3map2s) {
    const SampleCompiles compiles = compileSampleBothWays(reference(), "model_clip");
    const fs::path& work = compiles.work;
    const bsp::Bsp ours = bsp::readBsp(compiles.ours / "model_clip.bsp");
    const bsp::Bsp theirs = bsp::readBsp(compiles.theirs / "model_clip.bsp");
    EXPECT_TRUE(bsp::lumpBytes(ours, bsp::LUMP_BRUSHES) == bsp::lumpBytes(theirs, bsp::LUMP_BRUSHES));
    const BrushPlaneComparison planes = compareBrushPlanes(ours, theirs);
    EXPECT_EQ(planes.otherSideCount, 0);
    EXPECT_LT(planes.worstPlane, 1e-4);
    // Boxes around the crate, the pillar, the ramp and the cone.
    const Bounds boxes[4] = {{{96, 96, 0}, {160, 160, 40}},
                             {{368, 112, 0}, {400, 144, 136}},
                             {{56, 376, 0}, {136, 440, 40}},
                             {{368, 368, 0}, {400, 400, 44}}};
    unsigned state = 12345;
    auto unit = [&] {
        state = state * 1103515245u + 12345u;
        return float((state >> 8) & 0xffff) / 65535.0f;
    };
    int points = 0, equal = 0, solid = 0;
    for (const Bounds& box : boxes)
        for (int i = 0; i < 4000; ++i) {
            const Vec3 p = box.mins + (box.maxs - box.mins) * Vec3{unit(), unit(), unit()};
            const int a = pointContents(ours, p), b = pointContents(theirs, p);
            ++points;
            equal += a == b ? 1 : 0;
            solid += b != 0 ? 1 : 0;
        }
    // And one unit behind the middle of every clipped triangle: inside its clip brush in both.
    int behind = 0, behindSolid = 0;
    for (const bsp::Surface& s : ours.surfaces) {
        // Not the cone: extruded along Z its brushes are thinner than a unit across its steep sides.
        if (s.surfaceType != bsp::MST_TRIANGLE_SOUP || std::string(ours.shaders[size_t(s.shaderNum)].name) == "models/samples/")
            continue;
        for (int i = 0; i + 2 < s.numIndexes; i += 3) {
            Vec3 c[3];
            for (int k = 0; k < 3; ++k)
                c[k] = Vec3::fromArray(ours.drawVerts[size_t(s.firstVert + ours.drawIndexes[size_t(s.firstIndex + i + k)])].xyz);
            const Vec3 inward = normalize(cross(c[2] - c[0], c[1] - c[0])) * -1.0f;
            const Vec3 p = (c[0] + c[1] + c[2]) / 3.0f + inward;
            const int a = pointContents(ours, p), b = pointContents(theirs, p);
            ++behind;
            equal += a == b ? 1 : 0;
            ++points;
            behindSolid += (a != 0 && b != 0) ? 1 : 0;
        }
    }
    EXPECT_GT(solid, points / 50) << "the reference's clip brushes should fill part of the boxes";
    EXPECT_GE(behind, 30);
    EXPECT_GE(behindSolid, behind * 9 / 10) << "points behind clipped triangles are solid in both";
    EXPECT_EQ(equal, points) << equal << " of " << points << " points agree";
    std::printf("model clip contents: %d of %d points agree (%d solid in q3map2's; %d of %d behind triangles solid in "
                "both); side planes within %.3g\n",
                equal, points, solid, behindSolid, behind, planes.worstPlane);
    fs::remove_all(work);
}

INSTANTIATE_TEST_SUITE_P(Samples, ModelClipReference, ::testing::Values(0));

}  // namespace
}  // namespace q3::bspstage
