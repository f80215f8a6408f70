// Forced meta misc_models against q3map2 2.5.17n on the model_forcemeta sample. Without -meta the
// model surfaces under a q3map_forceMeta shader become meta surfaces while those forced by
// spawnflag 4 stay triangle soups; with -meta both are merged. The surfaces take the misc_model's
// own lighting keys and cel shader. Either way every lump but the entities, the .srf and the .prt
// are q3map2's byte for byte.
#include <gtest/gtest.h>

#include <string>

#include "bsp_reference.h"
#include "bspfile.h"
#include "file_io.h"
#include "reference_fixture.h"

namespace q3::bspstage {
namespace {

namespace fs = std::filesystem;
using namespace q3::bspstage::test;

int surfacesOf(const bsp::Bsp& bsp, const std::string& shader, int type) {
    int n = 0;
    for (const bsp::Surface& s : bsp.surfaces)
        n += bsp.shaders[size_t(s.shaderNum)].name == shader && s.surfaceType == type ? 1 : 0;
    return n;
}

class ModelForceMetaReference : public conformance::ReferenceTest<int> {};

TEST_P(ModelForceMetaReference, WithoutMetaEveryLumpButTheEntitiesEqualsQ3map2s) {
    const SampleCompiles compiles = compileSampleBothWays(reference(), "model_forcemeta");
    expectSampleOutputsEqual(compiles, "model_forcemeta");
    const bsp::Bsp ours = bsp::readBsp(compiles.ours / "model_forcemeta.bsp");
    // The sample shows both kinds: the forceMeta shader's pillar merged into planar meta
    // surfaces, the spawnflag 4 crate and ramp left as triangle soups, the ramp clipped.
    EXPECT_EQ(surfacesOf(ours, "textures/samples/forcemeta", bsp::MST_PLANAR), 5);
    EXPECT_EQ(surfacesOf(ours, "models/samples/crate", bsp::MST_TRIANGLE_SOUP), 1);
    EXPECT_EQ(surfacesOf(ours, "textures/samples/floor", bsp::MST_TRIANGLE_SOUP), 1);
    EXPECT_GT(ours.brushes.size(), 6u) << "the ramp's clip brushes";
    // The models' own keys: the cone's cel shader, the crate's sample size and ambient light.
    int cel = 0;
    for (const bsp::Surface& s : ours.surfaces) cel += ours.shaders[size_t(s.shaderNum)].name == std::string("textures/samples/cel");
    EXPECT_EQ(cel, 1);
    const std::string srf = readFileText(compiles.ours / "model_forcemeta.srf");
    EXPECT_NE(srf.find("sampleSize 8"), std::string::npos);
    EXPECT_NE(srf.find("ambientColor ( 5.000000 0.000000 0.000000 )"), std::string::npos);
    fs::remove_all(compiles.work);
}

TEST_P(ModelForceMetaReference, WithMetaEveryLumpButTheEntitiesEqualsQ3map2s) {
    const SampleCompiles compiles = compileSampleBothWays(reference(), "model_forcemeta", {"-meta"});
    expectSampleOutputsEqual(compiles, "model_forcemeta");
    const bsp::Bsp ours = bsp::readBsp(compiles.ours / "model_forcemeta.bsp");
    EXPECT_EQ(surfacesOf(ours, "models/samples/crate", bsp::MST_TRIANGLE_SOUP), 0);
    EXPECT_EQ(surfacesOf(ours, "models/samples/crate", bsp::MST_PLANAR), 5);
    fs::remove_all(compiles.work);
}

INSTANTIATE_TEST_SUITE_P(Samples, ModelForceMetaReference, ::testing::Values(0));

}  // namespace
}  // namespace q3::bspstage
