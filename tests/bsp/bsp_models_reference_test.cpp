// misc_model surfaces against q3map2 2.5.17n: the misc_models sample (a model of every format the
// samples hold, moved, scaled, mirrored, remapped, skinned, colour to alpha) and oacmpdm1 (MD3
// torches), compiled by both; every triangle-soup surface must have the same shader, vertices
// (position, texture coordinates, normal, colour) and indexes, bit for bit.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstring>

#include "bsp_reference.h"
#include "bsp_stage.h"
#include "bspfile.h"
#include "log.h"
#include "reference_fixture.h"
#include "test_data.h"

namespace q3::bspstage {
namespace {

namespace fs = std::filesystem;
using namespace q3::bspstage::test;

constexpr int kTriangleSoup = 3;

struct TriangleSurface {
    std::string shader;
    std::vector<uint8_t> verts;  // the vertex records' bytes
    std::vector<int32_t> indexes;
};

std::vector<TriangleSurface> triangleSurfaces(const fs::path& bspPath) {
    const bsp::Bsp b = bsp::readBsp(bspPath);
    std::vector<TriangleSurface> out;
    for (const bsp::Surface& s : b.surfaces) {
        if (s.surfaceType != kTriangleSoup) continue;
        TriangleSurface t;
        t.shader = b.shaders.at(size_t(s.shaderNum)).name;
        const auto* first = reinterpret_cast<const uint8_t*>(&b.drawVerts.at(size_t(s.firstVert)));
        t.verts.assign(first, first + size_t(s.numVerts) * sizeof(bsp::DrawVert));
        t.indexes.assign(b.drawIndexes.begin() + s.firstIndex, b.drawIndexes.begin() + s.firstIndex + s.numIndexes);
        out.push_back(std::move(t));
    }
    return out;
}

void expectSameTriangleSurfaces(const fs::path& ours, const fs::path& theirs, size_t expected) {
    const std::vector<TriangleSurface> a = triangleSurfaces(ours), b = triangleSurfaces(theirs);
    ASSERT_EQ(a.size(), b.size());
    EXPECT_EQ(a.size(), expected);
    for (size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i].shader, b[i].shader) << "triangle surface " << i;
        EXPECT_TRUE(a[i].verts == b[i].verts) << "triangle surface " << i << " (" << a[i].shader << "): vertices differ";
        EXPECT_EQ(a[i].indexes, b[i].indexes) << "triangle surface " << i << " (" << a[i].shader << ")";
    }
}

class MiscModelReference : public conformance::ReferenceTest<int> {};

TEST_P(MiscModelReference, SampleModelSurfacesEqualQ3map2s) {
    const auto [work, ours, theirs] = compileSampleBothWays(reference(), "misc_models");
    // 13 surfaces: the missing model gives none, the skin keeps the post's one surface.
    expectSameTriangleSurfaces(ours / "misc_models.bsp", theirs / "misc_models.bsp", 13);
    fs::remove_all(work);
}

TEST_P(MiscModelReference, OacmpDm1TorchesEqualQ3map2s) {
    const fs::path mapSource = oacmpSource("oacmpdm1");
    ASSERT_FALSE(mapSource.empty());
    const fs::path refDir = referenceCompile(reference(), mapSource, {}, false);
    const fs::path work = q3::test::tempDir() / ("misc-models-dm1-" + std::to_string(::getpid()));
    const fs::path ourBsp = ourCompile(mapSource, work);
    expectSameTriangleSurfaces(ourBsp, refDir / "oacmpdm1.bsp", 26);
    fs::remove_all(work);
}

INSTANTIATE_TEST_SUITE_P(Models, MiscModelReference, ::testing::Values(0));

}  // namespace
}  // namespace q3::bspstage
