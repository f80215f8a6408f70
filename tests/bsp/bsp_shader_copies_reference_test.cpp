// Shader copies against q3map2 2.5.17n on the shader_copies sample (-meta): q3map_cloneShader,
// q3map_backShader, q3map_remapShader, q3map_tcMod and _celshader give the same bytes in every
// lump but the entities (which record the command line), and the same .srf and .prt.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>

#include "bsp_reference.h"
#include "bspfile.h"
#include "reference_fixture.h"
#include "test_data.h"

namespace q3::bspstage {
namespace {

namespace fs = std::filesystem;
using namespace q3::bspstage::test;

class ShaderCopiesReference : public conformance::ReferenceTest<int> {};

TEST_P(ShaderCopiesReference, EveryLumpButTheEntitiesEqualsQ3map2s) {
    const SampleCompiles compiles = compileSampleBothWays(reference(), "shader_copies");
    expectSampleOutputsEqual(compiles, "shader_copies");
    const bsp::Bsp a = bsp::readBsp(compiles.ours / "shader_copies.bsp");
    // The sample must exercise what it claims: the remap target and every copy's shader are named.
    std::vector<std::string> names;
    for (const bsp::Shader& s : a.shaders) names.emplace_back(s.name, strnlen(s.name, sizeof s.name));
    for (const char* name : {"textures/samples/remaptarget", "textures/samples/clonecopy", "textures/samples/backcopy",
                             "textures/samples/cel"})
        EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
    EXPECT_EQ(std::find(names.begin(), names.end(), "textures/samples/remapped"), names.end());
    fs::remove_all(compiles.work);
}

INSTANTIATE_TEST_SUITE_P(Samples, ShaderCopiesReference, ::testing::Values(0));

}  // namespace
}  // namespace q3::bspstage
