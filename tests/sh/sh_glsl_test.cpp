// The GLSL snippet: generated from the library's constant table, committed unchanged, compiles,
// and its formula is the one the C++ evaluator uses.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "sh.h"
#include "sh_glsl.h"
#include "test_data.h"

namespace q3::sh {
namespace {

std::string readText(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream out;
    out << in.rdbuf();
    return out.str();
}

void writeText(const std::filesystem::path& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
}

std::string wrapInFragmentShader(const std::string& snippet) {
    return "#version 450\n" + snippet +
           "layout(location = 0) in vec3 normal;\n"
           "layout(location = 0) out vec4 color;\n"
           "layout(binding = 0) uniform Probe { vec3 coeffs[9]; } probe;\n"
           "void main()\n{\n"
           "    vec3 c[9] = probe.coeffs;\n"
           "    color = vec4(shIrradianceClamped(c, normalize(normal)) + 0.0 * shIrradiance(c, normal), 1.0);\n"
           "}\n";
}

int validate(const std::filesystem::path& shader, std::string& output) {
    return q3::test::runCommand(std::string("'") + Q3SH_GLSLANG + "' '" + shader.string() + "'", &output);
}

TEST(ShGlsl, CommittedFileIsTheGeneratorOutput) {
    const std::string committed = readText(Q3SH_COMMITTED_GLSL);
    ASSERT_FALSE(committed.empty()) << "missing " << Q3SH_COMMITTED_GLSL;
    EXPECT_EQ(committed, irradianceGlsl()) << "regenerate with q3sh-glsl > docs/glsl/sh_irradiance.glsl";
    std::string printed;
    ASSERT_EQ(q3::test::runCommand(std::string("'") + Q3SH_GLSL_GENERATOR + "'", &printed), 0);
    EXPECT_EQ(printed, committed);
}

TEST(ShGlsl, SnippetCarriesEveryConstantOfTheTable) {
    const std::string glsl = irradianceGlsl();
    for (int i = 0; i < kCoeffCount; ++i) {
        char constant[32];
        std::snprintf(constant, sizeof constant, "%.15f", kBasis[i].constant);
        const std::string term = "c[" + std::to_string(i) + "] * ";
        const size_t at = glsl.find(term);
        ASSERT_NE(at, std::string::npos) << term;
        EXPECT_NE(glsl.find(constant, at), std::string::npos) << i;
        if (kBasis[i].poly != BasisPolynomial::One) {
            EXPECT_NE(glsl.find(polynomialSource(kBasis[i].poly), at), std::string::npos) << i;
        }
    }
}

TEST(ShGlsl, CompilesWithGlslang) {
    const std::filesystem::path dir = q3::test::tempDir();
    const std::filesystem::path shader = dir / "sh_probe.frag";
    writeText(shader, wrapInFragmentShader(readText(Q3SH_COMMITTED_GLSL)));
    std::string output;
    EXPECT_EQ(validate(shader, output), 0) << output;
}

TEST(ShGlsl, ValidatorRejectsABrokenSnippet) {
    // The compile check can fail: the same wrapper around a snippet with a typo does not compile.
    std::string broken = irradianceGlsl();
    broken.replace(broken.find("vec3 e = vec3(0.0);"), 19, "vec3 e = vec3(0.0)");
    const std::filesystem::path shader = q3::test::tempDir() / "broken.frag";
    writeText(shader, wrapInFragmentShader(broken));
    std::string output;
    EXPECT_NE(validate(shader, output), 0) << output;
}

}  // namespace
}  // namespace q3::sh
