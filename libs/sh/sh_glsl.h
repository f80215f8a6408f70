// GLSL source of the SH irradiance evaluation, generated from the constant table of
// sh_constants.h so shaders and the C++ library share one definition.
#pragma once

#include <string>

namespace q3::sh {

// Two functions: shIrradiance(vec3 c[9], vec3 n) and shIrradianceClamped (max with 0).
std::string irradianceGlsl();

}  // namespace q3::sh
