// Plain -bsp of the one-feature samples against q3map2 2.5.17n: brush windings are built as
// q3map2 builds them (around the brush's centre, from base windings fitted to its box), so faces
// start at the same corner and these samples come out byte for byte as q3map2's, entities apart.
#include <gtest/gtest.h>

#include "bsp_reference.h"
#include "reference_fixture.h"

namespace q3::bspstage {
namespace {

using namespace q3::bspstage::test;

class PlainSampleReference : public conformance::ReferenceTest<const char*> {};

TEST_P(PlainSampleReference, EveryLumpButTheEntitiesEqualsQ3map2s) {
    const SampleCompiles compiles = compileSampleBothWays(reference(), GetParam());
    expectSampleOutputsEqual(compiles, GetParam());
    std::filesystem::remove_all(compiles.work);
}

INSTANTIATE_TEST_SUITE_P(Samples, PlainSampleReference,
                         ::testing::Values("areaportal", "box_room", "detail_hint", "entity_ambient", "keep_lights",
                                           "leaking_room", "misc_models", "patch_room",
                                           "pillar_lights", "skybox", "two_rooms_door", "water_fog"));

}  // namespace
}  // namespace q3::bspstage
