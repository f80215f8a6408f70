// Prints the GLSL SH irradiance functions (committed as docs/glsl/sh_irradiance.glsl).
#include <cstdio>

#include "sh_glsl.h"

int main() {
    const std::string text = q3::sh::irradianceGlsl();
    return std::fwrite(text.data(), 1, text.size(), stdout) == text.size() ? 0 : 1;
}
