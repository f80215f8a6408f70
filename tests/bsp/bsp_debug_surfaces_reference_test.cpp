// -debugsurfaces against q3map2 2.5.17n on oacmpdm7 (world and brush models): every surface has the
// same type and the same vertex colours (q3map2's twelve colours by draw surface number, counted on
// across models), and the debugsurfaces shader enters the shader lump as q3map2's does.
#include <gtest/gtest.h>

#include <unistd.h>

#include <set>
#include <tuple>

#include "bsp_options.h"
#include "bsp_reference.h"
#include "bspfile.h"
#include "reference_fixture.h"
#include "test_data.h"

namespace q3::bspstage {
namespace {

namespace fs = std::filesystem;
using namespace q3::bspstage::test;

using Colours = std::set<std::tuple<uint8_t, uint8_t, uint8_t>>;

std::vector<std::pair<int, Colours>> surfaceColours(const bsp::Bsp& b) {
    std::vector<std::pair<int, Colours>> out;
    for (const bsp::Surface& s : b.surfaces) {
        Colours c;
        for (int v = s.firstVert; v < s.firstVert + s.numVerts; ++v) {
            const uint8_t* rgb = b.drawVerts[size_t(v)].color;
            c.insert({rgb[0], rgb[1], rgb[2]});
        }
        out.emplace_back(s.surfaceType, c);
    }
    return out;
}

class DebugSurfacesReference : public conformance::ReferenceTest<int> {};

TEST_P(DebugSurfacesReference, ColoursAndTypesEqualQ3map2s) {
    const fs::path mapSource = oacmpSource("oacmpdm7");
    ASSERT_FALSE(mapSource.empty());
    const fs::path refDir = referenceCompile(reference(), mapSource, "-debugsurfaces", false);
    const fs::path work = q3::test::tempDir() / ("debug-surfaces-" + std::to_string(::getpid()));
    BspOptions options;
    options.debugSurfaces = true;
    const fs::path ourBsp = ourCompile(mapSource, work, options);
    const bsp::Bsp ours = bsp::readBsp(ourBsp), theirs = bsp::readBsp(refDir / "oacmpdm7.bsp");
    EXPECT_TRUE(bsp::lumpBytes(ours, bsp::LUMP_SHADERS) == bsp::lumpBytes(theirs, bsp::LUMP_SHADERS));
    ASSERT_GT(ours.models.size(), 1u) << "the map should have brush models";
    const auto a = surfaceColours(ours), b = surfaceColours(theirs);
    ASSERT_EQ(a.size(), b.size());
    size_t coloured = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i], b[i]) << "surface " << i;
        coloured += a[i].second.size() == 1 ? 1 : 0;
    }
    EXPECT_GT(coloured, a.size() * 9 / 10) << "each surface has one colour";
    fs::remove_all(work);
}

INSTANTIATE_TEST_SUITE_P(Oacmp, DebugSurfacesReference, ::testing::Values(0));

}  // namespace
}  // namespace q3::bspstage
