// The WORLDLIGHTS lump in the JSON folder: readable records, a byte-identical round trip, and
// edits that break a record rejected at -pack.
#include "json_test_util.h"

#include "../sh/world_lights_samples.h"
#include "file_io.h"
#include "json_error.h"
#include "test_data.h"

#include <gtest/gtest.h>

namespace q3 {
namespace {

bsp::Bsp withWorldLights() {
    bsp::Bsp b = test::smallBsp();
    b.setBspx("OTHER_LUMP", {1, 2, 3, 4, 5});
    b.setBspx(sh::kWorldLightsLumpName, sh::encodeWorldLights(sh::test::sampleWorldLights()));
    return b;
}

TEST(JsonWorldLights, RoundTripIsByteIdenticalAndReadable) {
    const bsp::Bsp b = withWorldLights();
    const std::filesystem::path folder = test::tempDir() / "worldlights";
    EXPECT_EQ(test::unpackThenPack(b, folder), bsp::serializeBsp(b));
    const std::string text = readFileText(folder / "BSPXLumps.json");
    EXPECT_NE(text.find("\"lights\""), std::string::npos) << text;
    EXPECT_NE(text.find("\"controlled\""), std::string::npos);
    EXPECT_NE(text.find("\"parallel\""), std::string::npos);
    EXPECT_NE(text.find("\"falloffConstants\""), std::string::npos);
}

TEST(JsonWorldLights, BrokenRecordsAreRejectedAtPack) {
    const struct {
        const char* from;
        const char* to;
        const char* expected;
    } edits[] = {
        {"\"type\": \"point\"", "\"type\": \"lamp\"", "unknown name \"lamp\""},
        {"\"inShGrid\": 1", "\"inShGrid\": 2", "expected 0 or 1"},
        {"\"falloff\": \"parallel\"", "\"falloff\": \"linear\"", "a sun with a falloff model other than parallel"},
        {"\"radius\": 700", "\"radius\": -5", "radius -5 is not in"},
    };
    for (const auto& edit : edits) {
        const std::filesystem::path folder = test::tempDir() / "worldlights_bad";
        Log log(false);
        json::unpackBsp(withWorldLights(), folder, {}, log);
        test::replaceInFile(folder / "BSPXLumps.json", edit.from, edit.to);
        try {
            json::packFolder(folder, {}, log);
            ADD_FAILURE() << edit.to << " was accepted";
        } catch (const json::JsonError& e) {
            EXPECT_NE(std::string(e.what()).find(edit.expected), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find("BSPXLump"), std::string::npos) << e.what();
        }
    }
}

TEST(JsonWorldLights, MalformedLumpIsAnUnpackError) {
    bsp::Bsp b = test::smallBsp();
    std::vector<uint8_t> lump = sh::encodeWorldLights(sh::test::sampleWorldLights());
    lump[8] = 9;  // count
    b.setBspx(sh::kWorldLightsLumpName, lump);
    Log log(false);
    try {
        json::unpackBsp(b, test::tempDir() / "worldlights_malformed", {}, log);
        ADD_FAILURE() << "a malformed lump was unpacked";
    } catch (const bsp::BspError& e) {
        EXPECT_NE(std::string(e.what()).find("WORLDLIGHTS: 9 lights need"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace q3
