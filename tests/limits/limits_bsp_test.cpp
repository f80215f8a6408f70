// Hostile and extreme BSPs through the q3map2 executable: lumps claiming billions of records, an
// SH grid header or BSPX directory claiming more than the file holds (one clear error naming the
// file, small memory), and a map filled to the engine's limits (bounded success).
#include "bspfile.h"
#include "limits_support.h"
#include "synthetic_bsp.h"
#include "test_data.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstring>

namespace {
namespace fs = std::filesystem;
using q3::test::q3map2Command;
using q3::test::runQ3map2;

std::vector<uint8_t> roomImage() { return q3::bsp::serializeBsp(q3::bsp::test::makeSyntheticBsp()); }

// Both readers of a whole BSP: -info and the light stage.
void expectRejectedEverywhere(const fs::path& game, const fs::path& bsp) {
    for (const std::vector<std::string>& stage :
         {std::vector<std::string>{"-info"}, std::vector<std::string>{"-light", "-fast", "-sh"}}) {
        SCOPED_TRACE(stage.front());
        q3::test::expectOneLineError(runQ3map2(q3map2Command(game, {}, stage, bsp)), 1, bsp.filename().string());
    }
}

struct LumpClaim {
    std::string name;
    int32_t offset;  // -1: keep the lump's own offset
    int32_t length;
};

class HostileLumpEntry : public ::testing::TestWithParam<LumpClaim> {};

// Every lump of the header in turn claims the impossible.
TEST_P(HostileLumpEntry, EveryLumpIsRejectedWithOneLine) {
    const LumpClaim& claim = GetParam();
    const fs::path game = q3::test::tempDir();
    const std::vector<uint8_t> image = roomImage();
    const std::vector<q3::bsp::test::RawEntry> entries = q3::bsp::test::rawEntries(image, 17);
    for (int lump = 0; lump < 17; ++lump) {
        SCOPED_TRACE("lump " + std::to_string(lump));
        std::vector<uint8_t> hostile = image;
        q3::bsp::test::setRawEntry(hostile, lump, claim.offset < 0 ? entries[size_t(lump)].offset : claim.offset,
                                   claim.length);
        const fs::path bsp = q3::test::writeMapFile(game, "hostile.bsp", hostile);
        expectRejectedEverywhere(game, bsp);
    }
}

INSTANTIATE_TEST_SUITE_P(Limits, HostileLumpEntry,
                         ::testing::Values(LumpClaim{"two_billion_bytes", -1, 0x7ffffff0},
                                           LumpClaim{"offset_and_length_overflow", 0x7ffffff0, 0x7ffffff0},
                                           LumpClaim{"negative_length", -1, -72}),
                         [](const ::testing::TestParamInfo<LumpClaim>& info) { return info.param.name; });

// A v47 lump 18 whose header claims a billion points (or bounds whose product overflows 32 bits).
TEST(LimitsBsp, ShGridHeaderClaimingBillionsOfPointsIsRejected) {
    const fs::path game = q3::test::tempDir();
    for (const auto& [bounds, numPoints] :
         {std::pair<std::array<int32_t, 3>, int32_t>{{1000, 1000, 1000}, 1000000000},
          std::pair<std::array<int32_t, 3>, int32_t>{{65536, 65536, 2}, 0}}) {
        q3::bsp::Bsp room = q3::bsp::test::makeSyntheticBsp();
        std::vector<uint8_t> lump = q3::bsp::test::makeShGridLump(2, 2, 2);
        std::memcpy(lump.data() + 24, bounds.data(), 12);
        std::memcpy(lump.data() + 36, &numPoints, 4);
        // Stored as they are (attachShGrid would not check them either): the readers must refuse them.
        room.version = 47;
        room.headerLumps = 19;
        room.shGrid = lump;
        std::vector<uint8_t> image = q3::bsp::serializeBsp(room);
        const fs::path bsp = q3::test::writeMapFile(game, "shgrid.bsp", image);
        expectRejectedEverywhere(game, bsp);
    }
}

// A BSPX trailer whose directory claims two billion entries.
TEST(LimitsBsp, BspxDirectoryClaimingBillionsOfEntriesIsRejected) {
    const fs::path game = q3::test::tempDir();
    q3::bsp::Bsp room = q3::bsp::test::makeSyntheticBsp();
    room.setBspx("LIGHTINGDIR", std::vector<uint8_t>(64, 7));
    std::vector<uint8_t> image = q3::bsp::serializeBsp(room);
    const char magic[] = "BSPX";
    const auto at = std::search(image.begin(), image.end(), magic, magic + 4);
    ASSERT_NE(at, image.end());
    q3::bsp::test::storeU32(image, size_t(at - image.begin()) + 4, 0x7fffffffu);
    const fs::path bsp = q3::test::writeMapFile(game, "bspx.bsp", image);
    expectRejectedEverywhere(game, bsp);
}

// The room padded to Quake 3's limits (qfiles.h: 0x400 shaders, 0x80000 draw vertexes and indexes,
// 0x800000 lightmap bytes, 0x40000 entity characters) is read, lit and unpacked in bounded memory.
TEST(LimitsBsp, MapAtTheEngineLimitsIsLitWithinBoundedMemory) {
    constexpr size_t kMaxShaders = 0x400, kMaxDrawVerts = 0x80000, kMaxDrawIndexes = 0x80000;
    constexpr size_t kMaxLightingBytes = 0x800000, kMaxEntityChars = 0x40000;
    q3::bsp::Bsp room = q3::bsp::test::makeSyntheticBsp();
    while (room.shaders.size() < kMaxShaders) {
        q3::bsp::Shader shader = room.shaders.front();
        std::snprintf(shader.name, sizeof shader.name, "textures/limits/unused%zu", room.shaders.size());
        room.shaders.push_back(shader);
    }
    room.drawVerts.resize(kMaxDrawVerts, room.drawVerts.front());
    room.drawIndexes.resize(kMaxDrawIndexes - kMaxDrawIndexes % 3, 0);
    room.lightmaps.resize(kMaxLightingBytes / q3::bsp::kLightmapPageBytes * q3::bsp::kLightmapPageBytes, 128);
    room.entities.pop_back();  // the NUL
    for (int n = 0; room.entities.size() < kMaxEntityChars - 128; ++n)
        room.entities += "{\n\"classname\" \"info_null\"\n\"origin\" \"" + std::to_string(n % 200 - 100) + " 0 0\"\n}\n";
    room.entities += '\0';

    const fs::path game = q3::test::tempDir();
    const fs::path bsp = q3::test::writeMapFile(game, "limits.bsp", q3::bsp::serializeBsp(room));
    q3::test::expectSuccess(runQ3map2(q3map2Command(game, {}, {"-info"}, bsp)));
    q3::test::expectSuccess(runQ3map2(q3map2Command(game, {}, {"-light", "-fast", "-sh"}, bsp)));
    const q3::bsp::Bsp lit = q3::bsp::readBsp(bsp);
    EXPECT_EQ(lit.drawVerts.size(), kMaxDrawVerts);
    EXPECT_EQ(lit.shaders.size(), kMaxShaders);
    EXPECT_FALSE(lit.shGrid.empty());
    q3::test::expectSuccess(runQ3map2(q3map2Command(game, {}, {"-json", "-unpack"}, bsp), 300.0));
    fs::remove_all(game);  // about 200 MB of JSON
}

// The largest OpenArena map: its peak memory is printed with the run (and the bound checked).
TEST(LimitsBsp, LargestOpenArenaMapIsReadWithinBoundedMemory) {
    std::vector<fs::path> maps = q3::test::allRealBsps();
    ASSERT_FALSE(maps.empty());
    const fs::path largest = *std::max_element(maps.begin(), maps.end(), [](const fs::path& a, const fs::path& b) {
        return fs::file_size(a) < fs::file_size(b);
    });
    const std::vector<std::string> argv = {q3::test::q3map2Exe().string(), "-info", largest.string()};
    const q3::test::MeasuredRun run = runQ3map2(argv);
    q3::test::expectSuccess(run, largest.filename().string());
    std::printf("largest map %s (%ju bytes): -info peak RSS %ld MB\n", largest.filename().c_str(),
                uintmax_t(fs::file_size(largest)), run.peakRssKb / 1024);
}

}  // namespace
