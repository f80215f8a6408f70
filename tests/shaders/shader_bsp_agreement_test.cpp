// Cross-check of the surfaceparm table against q3map2's own output: the shader lump of every real
// BSP stores the flags q3map2 computed from the scripts. Scripts changed between the maps'
// compiles and this data set, so agreement is high but not total.
#include <gtest/gtest.h>

#include <cstring>

#include "bspfile.h"
#include "shader_loader.h"
#include "shader_test_util.h"
#include "test_data.h"
#include "vfs.h"

namespace q3 {
namespace {

using test::CapturedLog;

TEST(ShaderBspAgreement, FlagsMatchWhatQ3map2WroteIntoTheRealMaps) {
    CapturedLog cap;
    VfsOptions options;
    options.basePaths = {test::openArenaBase()};
    options.baseGame = "baseoa";
    Vfs vfs(options, cap.log);
    ShaderTable table = loadShaderTable(vfs, cap.log);

    const auto bsps = test::allRealBsps();
    ASSERT_GE(bsps.size(), 100u);
    int compared = 0, surfaceMatches = 0, contentMatches = 0;
    for (const auto& path : bsps) {
        bsp::Bsp map = bsp::readBsp(path);
        for (const bsp::Shader& record : map.shaders) {
            const ShaderInfo* shader = table.findExplicit(std::string(record.name, strnlen(record.name, 64)));
            if (!shader) continue;
            ++compared;
            surfaceMatches += static_cast<uint32_t>(record.surfaceFlags) == shader->surfaceFlags;
            contentMatches += static_cast<uint32_t>(record.contentFlags) == shader->contentFlags;
        }
    }
    // About 1700 BSP shader records have a script in the data set.
    ASSERT_GT(compared, 1500);
    EXPECT_GT(surfaceMatches, compared * 9 / 10) << surfaceMatches << " of " << compared;
    EXPECT_GT(contentMatches, compared * 98 / 100) << contentMatches << " of " << compared;
}

}  // namespace
}  // namespace q3
