// Every committed crash input goes through its target's entry (fuzz_entries.h); the entries
// themselves are checked on inputs they must accept and on inputs they must reject cleanly.
#include "fuzz_entries.h"

#include "bspfile.h"
#include "file_io.h"
#include "test_data.h"
#include "../sh/world_lights_samples.h"
#include "light_cache_test_bsp.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

namespace {
namespace fs = std::filesystem;
using q3::fuzz::FuzzContext;

const fs::path kRegressions = Q3MAP_FUZZ_REGRESSIONS;

std::span<const uint8_t> bytesOf(const std::string& text) {
    return {reinterpret_cast<const uint8_t*>(text.data()), text.size()};
}

void run(std::string_view target, std::span<const uint8_t> input, const FuzzContext& context) {
    const q3::fuzz::FuzzEntry* entry = q3::fuzz::findFuzzEntry(target);
    ASSERT_NE(entry, nullptr) << target;
    entry->run(input, context);
}

// Each folder under regressions/ is named after a target, so no input is silently skipped.
TEST(FuzzRegressions, FoldersNameKnownTargets) {
    ASSERT_TRUE(fs::is_directory(kRegressions)) << kRegressions;
    for (const auto& item : fs::directory_iterator(kRegressions)) {
        if (!item.is_directory()) continue;
        EXPECT_NE(q3::fuzz::findFuzzEntry(item.path().filename().string()), nullptr)
            << item.path() << " does not name a fuzz target";
    }
}

TEST(FuzzRegressions, EveryCrashInputIsHandled) {
    const FuzzContext context{q3::test::tempDir()};
    std::vector<fs::path> inputs;
    for (const auto& item : fs::recursive_directory_iterator(kRegressions))
        if (item.is_regular_file() && item.path().filename() != "README.md") inputs.push_back(item.path());
    std::sort(inputs.begin(), inputs.end());
    for (const fs::path& input : inputs) {
        SCOPED_TRACE(input.string());
        run(input.parent_path().filename().string(), q3::readFileBytes(input), context);
    }
    std::printf("%zu regression inputs replayed\n", inputs.size());
}

// The entries accept the inputs they are seeded with and reject garbage without escaping errors.
TEST(FuzzEntries, EveryEntryTakesEmptyAndGarbageInput) {
    const FuzzContext context{q3::test::tempDir()};
    const std::string garbage = "\x01\xff{ \"IBSP\" ( [ patchDef2 \n\x00\x00 PK\x03\x04";
    for (const q3::fuzz::FuzzEntry& entry : q3::fuzz::fuzzEntries()) {
        SCOPED_TRACE(std::string(entry.name));
        entry.run({}, context);
        entry.run(bytesOf(garbage), context);
    }
}

TEST(FuzzEntries, BspEntryRoundTripsOurOwnOutput) {
    const FuzzContext context{q3::test::tempDir()};
    const std::vector<uint8_t> image = q3::bsp::serializeBsp(q3::fuzz::jsonPackSourceBsp());
    run("bsp", image, context);
    run("sh_runtime", image, context);
}

// The world lights entry accepts the codec tests' lump and rejects a broken copy cleanly.
TEST(FuzzEntries, WorldLightsEntryTakesValidAndBrokenLumps) {
    const FuzzContext context{q3::test::tempDir()};
    std::vector<uint8_t> lump = q3::sh::encodeWorldLights(q3::sh::test::sampleWorldLights());
    run("world_lights", lump, context);
    lump[16] = 9;  // first record's type
    run("world_lights", lump, context);
    lump.resize(40);
    run("world_lights", lump, context);
}

// The light cache entry loads and queries the pillar room, and refuses a copy with a broken tree
// or a cut-off file cleanly.
TEST(FuzzEntries, LightCacheEntryTakesTheTestRoomAndBrokenCopies) {
    const FuzzContext context{q3::test::tempDir()};
    q3::sh::test::TestMap room = q3::sh::test::roomWithPillar();
    room.lights.push_back(q3::sh::test::testPointLight(100, 100, 100, 5000));
    run("lightcache", q3::sh::test::buildTestBsp(room), context);
    q3::sh::test::TestLumps lumps = q3::sh::test::testLumps(room);
    lumps.lumps[3][4] = 0;  // node 0's front child is node 0 itself
    run("lightcache", q3::sh::test::assembleTestBsp(lumps), context);
    std::vector<uint8_t> cut = q3::sh::test::buildTestBsp(room);
    cut.resize(cut.size() / 2);
    run("lightcache", cut, context);
}

TEST(FuzzEntries, JsonPackReplacesOneFileAndRestoresIt) {
    const FuzzContext context{q3::test::tempDir()};
    // A broken planes.json is a clean JsonError; the folder is valid again for the next input.
    run("json_pack", bytesOf("planes.json\n{ \"Plane#0\": [1, 2"), context);
    const fs::path work = context.scratch / "json_pack" / "work";
    ASSERT_TRUE(fs::exists(work / "planes.json"));
    EXPECT_EQ(q3::readFileText(work / "planes.json"), q3::readFileText(context.scratch / "json_pack" / "base" / "planes.json"));
    // Names outside the folder are ignored, never written.
    run("json_pack", bytesOf("../escape.json\n{}"), context);
    EXPECT_FALSE(fs::exists(context.scratch / "json_pack" / "escape.json"));
}

// The -bsp samples compile through the map_bsp entry (sealed ones with a portal file -vis reads),
// and so does the box room without its first wall (a leak).
TEST(FuzzEntries, MapBspEntryCompilesTheSamples) {
    const FuzzContext context{q3::test::tempDir()};
    size_t count = 0;
    for (const auto& item : fs::directory_iterator(Q3MAP_BSP_SAMPLE_MAPS)) {
        if (item.path().extension() != ".map") continue;
        SCOPED_TRACE(item.path().string());
        run("map_bsp", q3::readFileBytes(item.path()), context);
        ++count;
    }
    EXPECT_GE(count, 10u);
    std::string room = q3::readFileText(fs::path(Q3MAP_BSP_SAMPLE_MAPS) / "box_room.map");
    const size_t brush = room.find("{\n( ");
    ASSERT_NE(brush, std::string::npos);
    room.erase(brush, room.find("}\n", brush) + 2 - brush);
    run("map_bsp", bytesOf(room), context);
}

// Accepted portal files go through every vis pass (a leading "\v" adds -hint and -merge).
TEST(FuzzEntries, PrtEntryRunsThePassesOnSmallFiles) {
    const FuzzContext context{q3::test::tempDir()};
    const std::string zigZag =
        "PRT1\n4\n3\n0\n"
        "4 0 1 0 (0 0 0 ) (0 10 0 ) (0 10 10 ) (0 0 10 )\n"
        "4 1 2 1 (10 30 0 ) (10 40 0 ) (10 40 10 ) (10 30 10 )\n"
        "4 2 3 2 (20 0 0 ) (20 10 0 ) (20 10 10 ) (20 0 10 )\n";
    run("prt", bytesOf(zigZag), context);
    run("prt", bytesOf("\v" + zigZag), context);
    run("prt", bytesOf("\r" + zigZag), context);
    run("prt", bytesOf("PRT1\n4\n3\n0\n4 0 9 0"), context);  // rejected: cluster out of range
}

}  // namespace
