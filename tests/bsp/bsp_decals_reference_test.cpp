// _decal entities against q3map2 2.5.17n on the decals sample (-meta): the same tree, brushes and
// surface layout, the same number of decal surfaces, and every decal surface made of the same
// vertices (position, texture coordinates, normal, alpha fade). Where a decal covers a whole brush
// face, its first vertex may differ (our face windings can start one point later than q3map2's,
// which no face surface shows), so a decal's vertices are compared as a set, not in order, and
// index runs may be shared differently (firstIndex). Other surfaces keep their vertices in order;
// patch vertex normals may differ in the last bit.
#include <gtest/gtest.h>


#include <algorithm>
#include <cstring>
#include <tuple>

#include "bsp_reference.h"
#include "bspfile.h"
#include "file_io.h"
#include "reference_fixture.h"
#include "test_data.h"

namespace q3::bspstage {
namespace {

namespace fs = std::filesystem;
using namespace q3::bspstage::test;

constexpr const char* kDecalShader = "textures/samples/decal";

std::string shaderName(const bsp::Bsp& b, const bsp::Surface& s) {
    const bsp::Shader& sh = b.shaders[size_t(s.shaderNum)];
    return std::string(sh.name, strnlen(sh.name, sizeof sh.name));
}

// A vertex as sortable numbers; adding 0.0f turns -0 into +0, which compares equal anyway.
using VertexKey = std::tuple<float, float, float, float, float, float, float, float, int, int, int, int>;

std::vector<VertexKey> sortedVertices(const bsp::Bsp& b, const bsp::Surface& s) {
    std::vector<VertexKey> keys;
    for (int i = 0; i < s.numVerts; ++i) {
        const bsp::DrawVert& v = b.drawVerts[size_t(s.firstVert + i)];
        keys.emplace_back(v.xyz[0], v.xyz[1], v.xyz[2], v.st[0], v.st[1], v.normal[0] + 0.0f, v.normal[1] + 0.0f,
                          v.normal[2] + 0.0f, v.color[0], v.color[1], v.color[2], v.color[3]);
    }
    std::sort(keys.begin(), keys.end());
    return keys;
}

int srfDecalSurfaces(const std::string& srf) {
    int count = 0;
    const std::string shader = std::string("\tshader ") + kDecalShader + "\n";
    for (size_t at = srf.find(shader); at != std::string::npos; at = srf.find(shader, at + 1)) ++count;
    return count;
}

class DecalsReference : public conformance::ReferenceTest<int> {};

TEST_P(DecalsReference, DecalSurfacesMatchQ3map2s) {
    const auto [work, ours, theirs] = compileSampleBothWays(reference(), "decals");
    const bsp::Bsp a = bsp::readBsp(ours / "decals.bsp"), b = bsp::readBsp(theirs / "decals.bsp");
    for (int lump : {bsp::LUMP_SHADERS, bsp::LUMP_PLANES, bsp::LUMP_NODES, bsp::LUMP_LEAFS, bsp::LUMP_LEAFSURFACES,
                     bsp::LUMP_LEAFBRUSHES, bsp::LUMP_MODELS, bsp::LUMP_BRUSHES, bsp::LUMP_BRUSHSIDES,
                     })
        EXPECT_TRUE(bsp::lumpBytes(a, lump) == bsp::lumpBytes(b, lump)) << bsp::lumpName(lump);
    EXPECT_EQ(readFileText(ours / "decals.prt"), readFileText(theirs / "decals.prt"));
    ASSERT_EQ(a.surfaces.size(), b.surfaces.size());
    ASSERT_EQ(a.drawVerts.size(), b.drawVerts.size());

    int decals = 0;
    for (size_t i = 0; i < a.surfaces.size(); ++i) {
        const bsp::Surface &sa = a.surfaces[i], &sb = b.surfaces[i];
        ASSERT_EQ(shaderName(a, sa), shaderName(b, sb)) << "surface " << i;
        EXPECT_EQ(sa.surfaceType, sb.surfaceType) << "surface " << i;
        EXPECT_EQ(sa.firstVert, sb.firstVert) << "surface " << i;
        ASSERT_EQ(sa.numVerts, sb.numVerts) << "surface " << i;
        EXPECT_EQ(sa.numIndexes, sb.numIndexes) << "surface " << i;
        if (shaderName(a, sa) != kDecalShader) {
            for (int k = 0; k < sa.numVerts; ++k) {
                const bsp::DrawVert &va = a.drawVerts[size_t(sa.firstVert + k)], &vb = b.drawVerts[size_t(sb.firstVert + k)];
                EXPECT_TRUE(std::memcmp(va.xyz, vb.xyz, sizeof va.xyz) == 0 && std::memcmp(va.st, vb.st, sizeof va.st) == 0 &&
                            std::memcmp(va.color, vb.color, sizeof va.color) == 0)
                    << "surface " << i << " vertex " << k;
                for (int c = 0; c < 3; ++c) EXPECT_NEAR(va.normal[c], vb.normal[c], 1e-6) << "surface " << i;
            }
            continue;
        }
        ++decals;
        EXPECT_EQ(sortedVertices(a, sa), sortedVertices(b, sb)) << "decal surface " << i;
    }
    // The sample must exercise what it claims: decals on the floor, a patch, the wall and the
    // pillar, merged by -meta into several surfaces; and the .srf lists as many.
    EXPECT_GE(decals, 10);
    const int srfDecals = srfDecalSurfaces(readFileText(ours / "decals.srf"));
    EXPECT_EQ(srfDecals, srfDecalSurfaces(readFileText(theirs / "decals.srf")));
    EXPECT_EQ(srfDecals, decals);
    // The _decal entities are gone from the entity lump and made no model.
    EXPECT_EQ(a.entities.find("_decal"), std::string::npos);
    EXPECT_EQ(a.models.size(), 1u);
    fs::remove_all(work);
}

INSTANTIATE_TEST_SUITE_P(Samples, DecalsReference, ::testing::Values(0));

}  // namespace
}  // namespace q3::bspstage
