// GLSL evaluation of WORLDLIGHTS records for shaders that light models with the light cache's
// local lights (docs/lightcache.md): the source is generated from the same enums and constants
// as evaluateWorldLight, and the packing below is the layout its uniform struct expects.
#pragma once

#include <string>

#include "world_lights.h"

namespace q3::sh {

// One record as five vec4 (80 bytes, the same under std140 and std430):
//   originRadius      xyz origin (suns: 0),          w radius (0: no end)
//   intensityFalloff  rgb intensity,                 w falloff model (WorldLightFalloff)
//   directionWeight   xyz spot axis / sun direction, w incidence weight
//   falloffConstants  the record's four falloff constants
//   coneType          xyz cone constants 0..2,       w type (WorldLightType); cone constant 3 is always 0
struct WorldLightGpu {
    float originRadius[4];
    float intensityFalloff[4];
    float directionWeight[4];
    float falloffConstants[4];
    float coneType[4];
};
static_assert(sizeof(WorldLightGpu) == 80);

WorldLightGpu packWorldLightGpu(const WorldLight& light);

// GLSL declaring `struct WorldLightGpu`, `vec3 worldLightIrradiance(WorldLightGpu l, vec3 p,
// vec3 n)` (evaluateWorldLight) and `vec3 worldLightsIrradiance(WorldLightGpu lights[4], int count,
// vec3 p, vec3 n)` (the sum over the first `count`). Written so that the same text also compiles as
// C++ over small vec3/vec4 structs, which is how the tests check it against evaluateWorldLight.
std::string worldLightsGlsl();

}  // namespace q3::sh
