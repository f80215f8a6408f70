// Regression test of the -bsp samples: each compiles to the same bytes as its golden files,
// lump by lump (regenerate them with `bspgolden` after an intended change, never from here).
#include <gtest/gtest.h>

#include <unistd.h>

#include <array>
#include <sstream>

#include "bsp_samples.h"
#include "bsp_stage.h"
#include "log.h"
#include "bspfile.h"
#include "file_io.h"

namespace q3::bspstage::test {
namespace {

namespace fs = std::filesystem;

class BspSamples : public ::testing::TestWithParam<std::string> {};

TEST_P(BspSamples, OutputsEqualTheGoldenFiles) {
    const std::string name = GetParam();
    const fs::path work = fs::temp_directory_path() / ("bsp-sample-" + name + "-" + std::to_string(::getpid()));
    const fs::path out = compileSample(name, work);
    const std::vector<std::string> produced = sampleOutputExtensions(out, name);
    EXPECT_EQ(produced, sampleOutputExtensions(goldenDir(), name)) << "files written for " << name;
    for (const std::string& ext : produced) {
        const fs::path golden = goldenDir() / (name + ext);
        ASSERT_TRUE(fs::exists(golden)) << golden;
        if (ext == ".bsp") {
            const bsp::Bsp ours = bsp::readBsp(out / (name + ext));
            const bsp::Bsp expected = bsp::readBsp(golden);
            for (int lump = 0; lump < bsp::kMaxLumps; ++lump)
                EXPECT_TRUE(bsp::lumpBytes(ours, lump) == bsp::lumpBytes(expected, lump))
                    << name << ".bsp: lump " << bsp::lumpName(lump) << " differs from the golden file";
            EXPECT_EQ(ours.headerLumps, expected.headerLumps);
        } else {
            EXPECT_EQ(readFileText(out / (name + ext)), readFileText(golden)) << name << ext;
        }
    }
    fs::remove_all(work);
}

// -onlyents on a compiled sample: every lump but the entities stays, the entities come from the
// edited .map, and worldspawn keeps the compile's recorded command line.
TEST(BspOnlyEnts, ReplacesTheEntityLumpOnly) {
    const fs::path work = fs::temp_directory_path() / ("bsp-onlyents-" + std::to_string(::getpid()));
    const fs::path out = compileSample("box_room", work);
    const bsp::Bsp before = bsp::readBsp(out / "box_room.bsp");
    std::string text = readFileText(out / "box_room.map");
    const std::string message = "\"message\" \"box room\"";
    const size_t at = text.find(message);
    ASSERT_NE(at, std::string::npos);
    text.replace(at, message.size(), "\"message\" \"edited room\"");
    writeFileAtomic(out / "box_room.map", text);
    CommonOptions common;
    common.basePaths.push_back(work.string());
    common.baseGame = "samples";
    common.mapPath = out / "box_room.bsp";
    common.commandLine = "-bsp -onlyents";
    BspOptions options;
    options.onlyEnts = true;
    Log log(false);
    runBspStage(options, common, log);
    const bsp::Bsp after = bsp::readBsp(out / "box_room.bsp");
    for (int lump = 1; lump < bsp::kMaxLumps; ++lump)
        EXPECT_TRUE(bsp::lumpBytes(after, lump) == bsp::lumpBytes(before, lump)) << bsp::lumpName(lump);
    const std::vector<bsp::Entity> entities = bsp::parseEntities(after.entities, "after");
    ASSERT_FALSE(entities.empty());
    EXPECT_EQ(entities[0].value("message"), "edited room");
    EXPECT_EQ(entities[0].value("_q3map2_cmdline"), "-bsp");  // the compile's, not -onlyents'
    EXPECT_EQ(entities.size(), bsp::parseEntities(before.entities, "before").size());
    fs::remove_all(work);
}

// The leaking sample: q3map2's leak messages name the entity the outside reached (the light, entity
// 2), and the .lin runs from outside the world's brushes to that entity's origin; the sealed
// samples write a .prt and no .lin.
TEST(BspLeak, LineRunsFromOutsideToTheNamedEntity) {
    const fs::path work = fs::temp_directory_path() / ("bsp-leak-" + std::to_string(::getpid()));
    Log log(false);
    std::string messages;
    log.addSink([&](LogLevel, std::string_view text) { messages += std::string(text) + "\n"; });
    const fs::path out = compileSample("leaking_room", work, &log);
    EXPECT_NE(messages.find("******* leaked *******"), std::string::npos) << messages;
    EXPECT_NE(messages.find("Entity 2, Brush 0: Entity leaked"), std::string::npos) << messages;
    ASSERT_TRUE(fs::exists(out / "leaking_room.lin"));
    EXPECT_FALSE(fs::exists(out / "leaking_room.prt"));
    std::vector<std::array<double, 3>> points;
    std::istringstream lines(readFileText(out / "leaking_room.lin"));
    for (std::array<double, 3> p; lines >> p[0] >> p[1] >> p[2];) points.push_back(p);
    ASSERT_GE(points.size(), 2u);
    EXPECT_EQ(points.back(), (std::array<double, 3>{256, 256, 200})) << "ends at the light's origin";
    // The room's brushes span -16..528 on X and Y, -16..272 on Z.
    const std::array<double, 3> first = points.front();
    EXPECT_TRUE(first[0] > 528 || first[0] < -16 || first[1] > 528 || first[1] < -16 || first[2] > 272 || first[2] < -16)
        << "starts outside: " << first[0] << " " << first[1] << " " << first[2];
    const fs::path sealed = compileSample("box_room", work / "sealed");
    EXPECT_TRUE(fs::exists(sealed / "box_room.prt"));
    EXPECT_FALSE(fs::exists(sealed / "box_room.lin"));
    fs::remove_all(work);
}

INSTANTIATE_TEST_SUITE_P(Samples, BspSamples, ::testing::ValuesIn(sampleNames()),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

}  // namespace
}  // namespace q3::bspstage::test
