#include <gtest/gtest.h>

#include "vfs.h"

namespace q3 {
namespace {

TEST(GameProfiles, Quake3AndQuakeLiveUseBaseq3) {
    ASSERT_NE(findGameProfile("quake3"), nullptr);
    EXPECT_EQ(findGameProfile("quake3")->baseGame, "baseq3");
    ASSERT_NE(findGameProfile("QuakeLive"), nullptr);
    EXPECT_EQ(findGameProfile("quakelive")->baseGame, "baseq3");
    EXPECT_EQ(findGameProfile("doom3"), nullptr);
}

TEST(DetectGamePaths, MapInsideGameFolder) {
    auto detected = detectGamePaths("/games/openarena/baseoa/maps/oacmpdm1.bsp");
    ASSERT_TRUE(detected);
    EXPECT_EQ(detected->basePath, std::filesystem::path("/games/openarena"));
    EXPECT_EQ(detected->gameDir, "baseoa");
}

TEST(DetectGamePaths, UsesTheLastMapsComponentAndNormalises) {
    auto detected = detectGamePaths("/maps/q3/./baseq3/extra/../MAPS/sub.map");
    ASSERT_TRUE(detected);
    EXPECT_EQ(detected->basePath, std::filesystem::path("/maps/q3"));
    EXPECT_EQ(detected->gameDir, "baseq3");
}

TEST(DetectGamePaths, NothingToDetect) {
    EXPECT_FALSE(detectGamePaths(""));
    EXPECT_FALSE(detectGamePaths("/tmp/x.bsp"));
    EXPECT_FALSE(detectGamePaths("/maps/x.bsp"));  // no game folder above "maps"
}

TEST(DetectGamePaths, RelativePathIsResolvedAgainstTheWorkingFolder) {
    auto detected = detectGamePaths("baseq3/maps/x.bsp");
    ASSERT_TRUE(detected);
    EXPECT_EQ(detected->basePath, std::filesystem::current_path().lexically_normal());
    EXPECT_EQ(detected->gameDir, "baseq3");
}

TEST(NormalizeVfsPath, LowercaseForwardSlashes) {
    EXPECT_EQ(normalizeVfsPath("Textures\\Base//Floor.TGA"), "textures/base/floor.tga");
    EXPECT_EQ(normalizeVfsPath("/scripts/x.shader"), "scripts/x.shader");
    EXPECT_EQ(normalizeVfsPath("./a/b"), "a/b");
}

}  // namespace
}  // namespace q3
