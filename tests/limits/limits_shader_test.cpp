// Shader scripts that reference themselves, nest deeply or come in absurd numbers: the light stage
// still ends with a bounded result (or one error line naming the script), in bounded time and
// memory. The room's shaders are textures/base/wall and textures/fog/thick.
#include "file_io.h"
#include "limits_support.h"
#include "test_data.h"

#include <gtest/gtest.h>

#include <functional>

namespace {
namespace fs = std::filesystem;
using q3::test::q3map2Command;
using q3::test::runQ3map2;

struct ScriptCase {
    std::string name;
    std::function<std::string()> shaderText;       // scripts/limits.shader
    std::function<std::string()> shaderListText;   // scripts/shaderlist.txt ("" = none)
    bool refused = false;                          // an error naming the script rather than a lit map
};

std::string repeated(const std::string& piece, size_t times) {
    std::string out;
    out.reserve(piece.size() * times);
    for (size_t i = 0; i < times; ++i) out += piece;
    return out;
}

std::string baseShaderChain(size_t length) {
    std::string text = "textures/chain/s0\n{\n\tsurfaceparm nolightmap\n}\n";
    for (size_t i = 1; i < length; ++i)
        text += "textures/chain/s" + std::to_string(i) + "\n{\n\tq3map_baseShader textures/chain/s" +
                std::to_string(i - 1) + "\n}\n";
    return text + "textures/base/wall\n{\n\tq3map_baseShader textures/chain/s" + std::to_string(length - 1) + "\n}\n";
}

std::vector<ScriptCase> scriptCases() {
    const auto none = [] { return std::string(); };
    return {
        {"base_shader_cycle",
         [] {
             return std::string("textures/base/wall\n{\n\tq3map_baseShader textures/base/other\n}\n"
                                "textures/base/other\n{\n\tq3map_baseShader textures/base/wall\n}\n");
         },
         none},
        {"base_shader_self", [] { return std::string("textures/base/wall\n{\n\tq3map_baseShader textures/base/wall\n}\n"); },
         none},
        {"base_shader_chain_20000", [] { return baseShaderChain(20000); }, none},
        {"deprecation_cycle",
         [] {
             return std::string("textures/base/wall\n{\n\tq3map_deprecateShader textures/base/other\n}\n"
                                "textures/base/other\n{\n\tq3map_deprecateShader textures/base/wall\n}\n");
         },
         none},
        // Stages do not nest: the first '}' closes the stage, the next the shader, and the rest are
        // stray braces the parser refuses.
        {"stages_nested_100000_deep",
         [] { return "textures/base/wall\n{\n" + repeated("{\n", 100000) + repeated("}\n", 100001); }, none, true},
        {"unclosed_nesting",
         [] { return "textures/base/wall\n{\n" + repeated("{\n", 100000); }, none},
        {"shaderlist_names_itself_and_repeats",
         [] { return std::string("textures/base/wall\n{\n\tsurfaceparm nolightmap\n}\n"); },
         [] { return "shaderlist\nshaderlist.txt\n" + repeated("limits\n", 100000); }},
        {"shaderlist_names_50000_missing_scripts",
         [] { return std::string("textures/base/wall\n{\n\tsurfaceparm nolightmap\n}\n"); },
         [] {
             std::string text = "limits\n";
             for (int i = 0; i < 50000; ++i) text += "missing" + std::to_string(i) + "\n";
             return text;
         }},
    };
}

class HostileShaderScript : public ::testing::TestWithParam<ScriptCase> {};

TEST_P(HostileShaderScript, LightStageEndsBoundedWithAResultOrOneError) {
    const ScriptCase& c = GetParam();
    const fs::path game = q3::test::tempDir();
    const fs::path bsp = q3::test::writeRoom(game);
    const fs::path scripts = game / "baseoa" / "scripts";
    fs::create_directories(scripts);
    q3::writeFileAtomic(scripts / "limits.shader", c.shaderText());
    const std::string list = c.shaderListText();
    if (!list.empty()) q3::writeFileAtomic(scripts / "shaderlist.txt", list);

    const q3::test::MeasuredRun run = runQ3map2(q3map2Command(game, {}, {"-light", "-fast"}, bsp), 60.0);
    if (c.refused) q3::test::expectOneLineError(run, 1, "limits.shader");
    else q3::test::expectSuccess(run);
    EXPECT_LT(run.seconds, 30.0) << run.describe();
}

INSTANTIATE_TEST_SUITE_P(Limits, HostileShaderScript, ::testing::ValuesIn(scriptCases()),
                         [](const ::testing::TestParamInfo<ScriptCase>& info) { return info.param.name; });

}  // namespace
