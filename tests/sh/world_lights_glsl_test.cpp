// The GLSL of WORLDLIGHTS records: generated from the library's enums and constants, committed
// unchanged, compiles with glslangValidator, and, compiled as C++ over a small vec3 shim, gives
// what evaluateWorldLight gives for every type and falloff model at thousands of points.
#include <gtest/gtest.h>

#include <fstream>
#include <random>
#include <sstream>

#include "sh_test_support.h"
#include "test_data.h"
#include "world_lights_glsl.h"
#include "world_lights_samples.h"

namespace glsl_as_cpp {
#include "glsl_cpp_shim.h"
#include Q3SH_COMMITTED_WORLD_LIGHTS_GLSL
}  // namespace glsl_as_cpp

namespace q3::sh {
namespace {

std::string readText(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream out;
    out << in.rdbuf();
    return out.str();
}

glsl_as_cpp::vec4 vec4Of(const float v[4]) { return {v[0], v[1], v[2], v[3]}; }

glsl_as_cpp::WorldLightGpu transcribed(const WorldLight& light) {
    const WorldLightGpu g = packWorldLightGpu(light);
    return {vec4Of(g.originRadius), vec4Of(g.intensityFalloff), vec4Of(g.directionWeight), vec4Of(g.falloffConstants),
            vec4Of(g.coneType)};
}

// The codec samples plus the models they lack: a q3map2 spot with extra distance and linear
// falloff, a controlled point light, a controlled spot without ambient, a grazing sun.
std::vector<WorldLight> everyKindOfLight() {
    std::vector<WorldLight> lights = test::sampleWorldLights();
    WorldLight linearSpot = lights[2];
    linearSpot.falloff = WorldLightFalloff::Linear;
    linearSpot.falloffConstants = {16, 12, 0.01f, 0.003f};
    lights.push_back(linearSpot);
    WorldLight controlledPoint = lights[3];
    controlledPoint.type = WorldLightType::Point;
    controlledPoint.cone = {0, 0, 0, 0};
    controlledPoint.falloffConstants = {0, 300, 1, 0};
    lights.push_back(controlledPoint);
    WorldLight narrow = lights[3];
    narrow.cone = {10, 10, 0, 0};  // inner = outer: a hard edge
    narrow.incidenceWeight = 1;
    lights.push_back(narrow);
    WorldLight lowSun = lights[4];
    lowSun.direction = {0.8f, 0, 0.6f};
    lowSun.intensity = {3, 2, 1};
    lights.push_back(lowSun);
    return lights;
}

TEST(WorldLightsGlsl, CommittedFileIsTheGeneratorOutput) {
    const std::string committed = readText(Q3SH_COMMITTED_WORLD_LIGHTS_GLSL);
    ASSERT_FALSE(committed.empty()) << "missing " << Q3SH_COMMITTED_WORLD_LIGHTS_GLSL;
    EXPECT_EQ(committed, worldLightsGlsl()) << "regenerate with q3sh-glsl world-lights > docs/glsl/world_lights.glsl";
    std::string printed;
    ASSERT_EQ(q3::test::runCommand(std::string("'") + Q3SH_GLSL_GENERATOR + "' world-lights", &printed), 0);
    EXPECT_EQ(printed, committed);
    EXPECT_NE(q3::test::runCommand(std::string("'") + Q3SH_GLSL_GENERATOR + "' nonsense 2>/dev/null", &printed), 0);
}

TEST(WorldLightsGlsl, ConstantsAreTheLibrarys) {
    const std::string glsl = worldLightsGlsl();
    EXPECT_NE(glsl.find("const int WL_TYPE_SUN = " + std::to_string(uint32_t(WorldLightType::Sun)) + ";"), std::string::npos);
    EXPECT_NE(glsl.find("const int WL_FALLOFF_CONTROLLED = " + std::to_string(uint32_t(WorldLightFalloff::Controlled)) + ";"),
              std::string::npos);
    EXPECT_EQ(float(glsl_as_cpp::WL_DEGREES_PER_RADIAN), kDegreesPerRadian);
    EXPECT_EQ(float(glsl_as_cpp::WL_CONTROLLED_SQUARE_START), kControlledSquareStart);
    EXPECT_EQ(glsl_as_cpp::WL_FALLOFF_LINEAR, int(WorldLightFalloff::Linear));
    EXPECT_EQ(glsl_as_cpp::WL_TYPE_SPOT, int(WorldLightType::Spot));
}

TEST(WorldLightsGlsl, CompilesWithGlslang) {
    const std::string shader = "#version 450\n" + readText(Q3SH_COMMITTED_WORLD_LIGHTS_GLSL) +
                               "layout(location = 0) in vec3 worldPos;\n"
                               "layout(location = 1) in vec3 normal;\n"
                               "layout(location = 0) out vec4 color;\n"
                               "layout(std140, binding = 0) uniform Lights { WorldLightGpu lights[4]; int count; } u;\n"
                               "void main()\n{\n"
                               "    color = vec4(worldLightsIrradiance(u.lights, u.count, worldPos, normalize(normal)), 1.0);\n"
                               "}\n";
    const std::filesystem::path path = q3::test::tempDir() / "world_lights.frag";
    std::ofstream(path, std::ios::binary) << shader;
    std::string output;
    EXPECT_EQ(q3::test::runCommand(std::string("'") + Q3SH_GLSLANG + "' '" + path.string() + "'", &output), 0) << output;
}

TEST(WorldLightsGlsl, SameIrradianceAsEvaluateWorldLight) {
    std::mt19937 rng(20240611);
    std::uniform_real_distribution<float> offset(-500, 500);
    int compared = 0, lit = 0;
    for (const WorldLight& light : everyKindOfLight()) {
        const int litBefore = lit;
        const glsl_as_cpp::WorldLightGpu gpu = transcribed(light);
        const float scale = std::max({std::fabs(light.intensity[0]), std::fabs(light.intensity[1]), std::fabs(light.intensity[2])});
        for (int k = 0; k < 4000; ++k) {
            // A third of the points near the light, where the clamps matter, a third around a spot's
            // axis, where its cone and fade are.
            const float spread = k % 3 == 0 ? 0.1f : (k % 3 == 1 ? 1.0f : 0.12f);
            const float along = k % 3 == 2 ? std::fabs(offset(rng)) * 0.8f : 0.0f;
            const std::array<float, 3> p{light.origin[0] + light.direction[0] * along + offset(rng) * spread,
                                         light.origin[1] + light.direction[1] * along + offset(rng) * spread,
                                         light.origin[2] + light.direction[2] * along + offset(rng) * spread};
            const Vec3d d = test::randomDirection(rng);
            const std::array<float, 3> n{float(d.x), float(d.y), float(d.z)};
            const std::array<float, 3> expected = evaluateWorldLight(light, p, n);
            const glsl_as_cpp::vec3 got = glsl_as_cpp::worldLightIrradiance(gpu, {p[0], p[1], p[2]}, {n[0], n[1], n[2]});
            const float values[3] = {got.x, got.y, got.z};
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(values[c], expected[size_t(c)], 1e-6f * scale + 1e-5f * std::fabs(expected[size_t(c)]))
                    << "light type " << int(light.type) << " falloff " << int(light.falloff) << " point " << p[0]
                    << " " << p[1] << " " << p[2];
            lit += expected[0] != 0;
            ++compared;
        }
        EXPECT_GT(lit - litBefore, 200) << "light type " << int(light.type) << " falloff " << int(light.falloff);
        // At the light itself.
        const glsl_as_cpp::vec3 at = glsl_as_cpp::worldLightIrradiance(gpu, {light.origin[0], light.origin[1], light.origin[2]},
                                                                       {0, 0, 1});
        EXPECT_NEAR(at.x, evaluateWorldLight(light, light.origin, {0, 0, 1})[0], 1e-6f * scale);
    }
    EXPECT_GT(lit, compared / 5);  // the comparison is not mostly of zeros
}

TEST(WorldLightsGlsl, TheSumTakesTheFirstCountLights) {
    const std::vector<WorldLight> lights = everyKindOfLight();
    glsl_as_cpp::WorldLightGpu four[4] = {transcribed(lights[0]), transcribed(lights[1]), transcribed(lights[5]),
                                          transcribed(lights[4])};
    const std::array<float, 3> p{100, -40, 60}, n{0, 0.6f, 0.8f};
    for (int count = 0; count <= 4; ++count) {
        float expected = 0;
        for (int i = 0; i < count; ++i) expected += evaluateWorldLight(lights[size_t(i < 2 ? i : (i == 2 ? 5 : 4))], p, n)[0];
        const glsl_as_cpp::vec3 got = glsl_as_cpp::worldLightsIrradiance(four, count, {p[0], p[1], p[2]}, {n[0], n[1], n[2]});
        EXPECT_NEAR(got.x, expected, 1e-5f) << count;
    }
}

}  // namespace
}  // namespace q3::sh
