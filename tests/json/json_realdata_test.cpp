// Every OpenArena BSP (written by other compilers, with other header layouts): unpack then pack gives
// identical lump payloads and version. One test per map, so ctest spreads them over the cores.
#include "json_test_util.h"

#include "test_data.h"

#include <gtest/gtest.h>

namespace q3 {
namespace {
namespace fs = std::filesystem;

TEST(JsonRealData, AllOpenArenaMapsAreCovered) {
    EXPECT_GE(test::allRealBsps().size(), 100u);
    if (!test::realBspsAreSampled())
        EXPECT_EQ(test::realBspsForRegistration().size(), test::allRealBsps().size());
}

class JsonRealMap : public ::testing::TestWithParam<fs::path> {};

TEST_P(JsonRealMap, UnpackThenPackKeepsLumpPayloadsAndVersion) {
    const fs::path& path = GetParam();
    bsp::Bsp original = bsp::readBsp(path);
    fs::path folder = test::tempDir() / path.stem();
    Log log(false);
    json::unpackBsp(original, folder, {}, log);
    bsp::Bsp packed = json::packFolder(folder, {}, log);
    EXPECT_EQ(packed.version, original.version);
    EXPECT_EQ(packed.headerLumps, original.headerLumps);
    for (int lump = 0; lump < bsp::kMaxLumps; ++lump)
        EXPECT_EQ(bsp::lumpBytes(packed, lump), bsp::lumpBytes(original, lump)) << bsp::lumpName(lump);
    // What our writer makes of the map comes back byte for byte.
    EXPECT_TRUE(bsp::serializeBsp(packed) == bsp::serializeBsp(original));
    fs::remove_all(folder.parent_path());
}

INSTANTIATE_TEST_SUITE_P(Maps, JsonRealMap, ::testing::ValuesIn(test::realBspsForRegistration()),
                         [](const auto& info) {
                             std::string name = info.param.parent_path().parent_path().filename().string() + "_" +
                                                info.param.stem().string();
                             for (char& c : name)
                                 if (!isalnum(static_cast<unsigned char>(c))) c = '_';
                             return name;
                         });
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(JsonRealMap);

}  // namespace
}  // namespace q3
