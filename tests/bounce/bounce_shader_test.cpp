// The shader side of -bounce: q3map_bounceScale and its older name q3map_bounce set the shader's
// re-emission scale, 1 when absent, and the surfaceparms that stop a surface from bouncing.
#include <gtest/gtest.h>

#include <vector>

#include "bounce_lights.h"
#include "log.h"
#include "shader_parser.h"

namespace q3::light {
namespace {

std::vector<ShaderInfo> parse(std::string_view text) {
    Log log(false);
    return parseShaderScript(text, "scripts/bounce.shader", log);
}

TEST(BounceShader, BounceScaleAndItsAlias) {
    const std::vector<ShaderInfo> shaders = parse(R"(textures/a/scaled
{
    q3map_bounceScale 0.5
}
textures/a/alias
{
    q3map_bounce 0.25
}
textures/a/plain
{
}
textures/a/off
{
    q3map_bounceScale 0
}
)");
    ASSERT_EQ(shaders.size(), 4u);
    EXPECT_FLOAT_EQ(shaders[0].bounceScale, 0.5f);
    EXPECT_FLOAT_EQ(shaders[1].bounceScale, 0.25f);
    EXPECT_FLOAT_EQ(shaders[2].bounceScale, 1.0f);
    EXPECT_FLOAT_EQ(shaders[3].bounceScale, 0.0f);
    EXPECT_TRUE(surfaceBounces(nullptr, shaders[1].bounceScale));
    EXPECT_FALSE(surfaceBounces(nullptr, shaders[3].bounceScale));
}

}  // namespace
}  // namespace q3::light
