// Shader-indexed terrain against q3map2 2.5.17n on the terrain_indexmap sample: a func_group's
// _indexmap, _layers, _shader and _offsets re-shade its q3map_terrain faces and patch with layer
// shaders, vertex alphas and height offsets. With -meta (the sample's options) and with plain -bsp,
// and with the index map as an 8-bit PCX and BMP (terrain_indexmap_pcx, _bmp), every lump but the
// entities and the .srf and .prt equal q3map2's.
#include <gtest/gtest.h>

#include <cstring>
#include <set>
#include <string>

#include "bsp_reference.h"
#include "bspfile.h"
#include "reference_fixture.h"
#include "test_data.h"

namespace q3::bspstage {
namespace {

namespace fs = std::filesystem;
using namespace q3::bspstage::test;

struct TerrainCase {
    const char* sample;
    bool meta;
};

class TerrainReference : public conformance::ReferenceTest<TerrainCase> {};

TEST_P(TerrainReference, EveryLumpButTheEntitiesEqualsQ3map2s) {
    const std::string name = GetParam().sample;
    const SampleCompiles compiles = GetParam().meta ? compileSampleBothWays(reference(), name)
                                                    : compileSampleBothWaysWith(reference(), name, {});
    expectSampleOutputsEqual(compiles, name);
    const bsp::Bsp a = bsp::readBsp(compiles.ours / (name + ".bsp"));
    // The sample must exercise what it claims: every layer shader, blending alphas and offsets.
    std::set<std::string> layerShaders;
    for (const bsp::Shader& s : a.shaders) {
        const std::string shader(s.name, strnlen(s.name, sizeof s.name));
        if (shader.rfind("textures/samples/terrain_", 0) == 0) layerShaders.insert(shader);
    }
    EXPECT_EQ(layerShaders, (std::set<std::string>{"textures/samples/terrain_0", "textures/samples/terrain_1",
                                                   "textures/samples/terrain_2", "textures/samples/terrain_0to1",
                                                   "textures/samples/terrain_0to2", "textures/samples/terrain_1to2"}));
    size_t transparent = 0, patchRaised = 0;
    for (const bsp::DrawVert& v : a.drawVerts) {
        transparent += v.color[3] == 0;
        patchRaised += v.xyz[2] == 128.0f || v.xyz[2] == 136.0f;  // the flat patch at z 120, offset 8 or 16
    }
    EXPECT_GT(transparent, 20u);
    EXPECT_GT(patchRaised, 4u);
    fs::remove_all(compiles.work);
}

// The .tga index map with and without -meta; the 8-bit palette .pcx and .bmp ones with -meta.
INSTANTIATE_TEST_SUITE_P(Samples, TerrainReference,
                         ::testing::Values(TerrainCase{"terrain_indexmap", true}, TerrainCase{"terrain_indexmap", false},
                                           TerrainCase{"terrain_indexmap_pcx", true},
                                           TerrainCase{"terrain_indexmap_bmp", true}));

}  // namespace
}  // namespace q3::bspstage
