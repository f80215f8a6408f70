// Prints the generated GLSL: the SH irradiance functions by default (docs/glsl/sh_irradiance.glsl),
// the WORLDLIGHTS evaluation with the argument "world-lights" (docs/glsl/world_lights.glsl).
#include <cstdio>
#include <cstring>

#include "sh_glsl.h"
#include "world_lights_glsl.h"

int main(int argc, char** argv) {
    if (argc > 2 || (argc == 2 && std::strcmp(argv[1], "world-lights") != 0)) {
        std::fprintf(stderr, "usage: %s [world-lights]\n", argv[0]);
        return 2;
    }
    const std::string text = argc == 2 ? q3::sh::worldLightsGlsl() : q3::sh::irradianceGlsl();
    return std::fwrite(text.data(), 1, text.size(), stdout) == text.size() ? 0 : 1;
}
