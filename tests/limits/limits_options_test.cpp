// Absurd option values and huge light-grid requests: a usage error naming the option, or a
// warning and a bounded grid, never an allocation failure; peak memory of each run measured.
#include "bspfile.h"
#include "limits_support.h"
#include "synthetic_bsp.h"
#include "test_data.h"

#include <gtest/gtest.h>

#include <fstream>

namespace {
namespace fs = std::filesystem;
using q3::test::q3map2Command;
using q3::test::runQ3map2;

struct UsageCase {
    std::string name;
    std::vector<std::string> common;  // before the stage
    std::vector<std::string> stage;   // after -light
    std::string needle;               // must appear in the error line
};

class AbsurdOption : public ::testing::TestWithParam<UsageCase> {};

TEST_P(AbsurdOption, IsAOneLineUsageError) {
    const UsageCase& c = GetParam();
    const fs::path game = q3::test::tempDir();
    const fs::path bsp = q3::test::writeRoom(game);
    std::vector<std::string> stage = {"-light", "-fast"};
    stage.insert(stage.end(), c.stage.begin(), c.stage.end());
    const q3::test::MeasuredRun run = runQ3map2(q3map2Command(game, c.common, stage, bsp));
    q3::test::expectOneLineError(run, 2, c.needle);
}

INSTANTIATE_TEST_SUITE_P(
    Limits, AbsurdOption,
    ::testing::Values(UsageCase{"threads_100000", {"-threads", "100000"}, {}, "-threads"},
                      UsageCase{"threads_0", {"-threads", "0"}, {}, "-threads"},
                      UsageCase{"super_1000", {}, {"-super", "1000"}, "-super"},
                      UsageCase{"samples_1000000", {}, {"-samples", "1000000"}, "-samples"},
                      UsageCase{"samples_huge_integer", {}, {"-samples", "99999999999999999999"}, "-samples"},
                      UsageCase{"lightmapsize_3", {}, {"-lightmapsize", "3"}, "-lightmapsize"},
                      UsageCase{"lightmapsize_huge", {}, {"-lightmapsize", "1073741824"}, "-lightmapsize"},
                      UsageCase{"gridsh_zero", {}, {"-sh", "-gridsh", "0", "8", "8"}, "-gridsh"},
                      UsageCase{"gridsh_nan", {}, {"-sh", "-gridsh", "nan", "8", "8"}, "-gridsh"},
                      UsageCase{"gridscalesh_inf", {}, {"-sh", "-gridscalesh", "inf"}, "-gridscalesh"},
                      UsageCase{"gridscalesh_negative", {}, {"-sh", "-gridscalesh", "-4"}, "-gridscalesh"}),
    [](const ::testing::TestParamInfo<UsageCase>& info) { return info.param.name; });

// Values at the top of the accepted ranges still finish within bounded memory on a small map.
TEST(LimitsOptions, LargestAcceptedThreadCountRuns) {
    const fs::path game = q3::test::tempDir();
    const fs::path bsp = q3::test::writeRoom(game);
    q3::test::expectSuccess(runQ3map2(q3map2Command(game, {"-threads", "1024"}, {"-light", "-fast"}, bsp)));
}

TEST(LimitsOptions, LargestAcceptedSupersamplingAndSamplesRun) {
    const fs::path game = q3::test::tempDir();
    const fs::path bsp = q3::test::writeRoom(game);
    q3::test::expectSuccess(
        runQ3map2(q3map2Command(game, {}, {"-light", "-fast", "-super", "8", "-samples", "16"}, bsp)));
}

// One 16384 x 16384 RGB page alone is 768 MiB (q3map2 allocates whole pages too); the room needs
// exactly one, so the run must stay near that.
TEST(LimitsOptions, LargestAcceptedLightmapPageRuns) {
    const fs::path game = q3::test::tempDir();
    const fs::path bsp = q3::test::writeRoom(game);
    q3::test::expectSuccess(runQ3map2(q3map2Command(game, {}, {"-light", "-fast", "-lightmapsize", "16384"}, bsp)), "",
                            q3::test::limitsRssBoundMb() + 1024);
}

// -gridsh below the smallest cell and an enormous -gridscalesh: the cell is raised to the minimum
// with a warning, and the grid stays small on a 256-unit room.
TEST(LimitsGrid, TinyExplicitShCellIsRaisedWithAWarning) {
    const fs::path game = q3::test::tempDir();
    const fs::path bsp = q3::test::writeRoom(game);
    q3::test::expectSuccess(runQ3map2(q3map2Command(game, {}, {"-light", "-fast", "-sh", "-gridsh", "1", "1", "1"}, bsp)),
                            "raised to");
}

TEST(LimitsGrid, HugeShGridScaleIsRaisedWithAWarning) {
    const fs::path game = q3::test::tempDir();
    const fs::path bsp = q3::test::writeRoom(game);
    q3::test::expectSuccess(runQ3map2(q3map2Command(game, {}, {"-light", "-fast", "-sh", "-gridscalesh", "1e9"}, bsp)),
                            "raised to");
}

// Worldspawn "gridsize" values asking for billions of points, or nonsense: numbers give a bounded
// grid (cells raised to the minimum, or grown to the point limit), non-numbers an error naming
// the file; memory stays bounded either way.
struct GridSizeCase {
    std::string name;
    std::string value;
    bool refused = false;  // an error rather than a grid
};

class WorldspawnGridSize : public ::testing::TestWithParam<GridSizeCase> {};

TEST_P(WorldspawnGridSize, GivesABoundedGridOrAClearError) {
    const fs::path game = q3::test::tempDir();
    const fs::path bsp = q3::test::writeRoom(game, "\"gridsize\" \"" + GetParam().value + "\"\n");
    for (const std::vector<std::string>& stage :
         {std::vector<std::string>{"-light", "-fast"}, std::vector<std::string>{"-light", "-fast", "-sh"}}) {
        const q3::test::MeasuredRun run = runQ3map2(q3map2Command(game, {}, stage, bsp));
        if (GetParam().refused) q3::test::expectOneLineError(run, 1, bsp.filename().string());
        else q3::test::expectSuccess(run);
    }
}

INSTANTIATE_TEST_SUITE_P(Limits, WorldspawnGridSize,
                         ::testing::Values(GridSizeCase{"tiny", "0.001 0.001 0.001"},
                                           GridSizeCase{"one_unit", "1 1 1"}, GridSizeCase{"zero", "0 0 0"},
                                           GridSizeCase{"negative", "-64 -64 -128"},
                                           GridSizeCase{"huge", "1e30 1e30 1e30"},
                                           GridSizeCase{"not_finite", "nan inf -inf", true},
                                           GridSizeCase{"garbage", "lots of points", true}),
                         [](const ::testing::TestParamInfo<GridSizeCase>& info) { return info.param.name; });

}  // namespace

namespace {

// A world 128k units wide with an 8-unit grid asks for billions of points: the legacy grid grows
// its cells to stay within the engine's 1,048,576 points and the SH grid within its own budget,
// each in bounded time and memory.
TEST(LimitsGrid, WideWorldWithTinyCellsStaysWithinTheLegacyPointLimit) {
    const fs::path game = q3::test::tempDir();
    const fs::path bsp = q3::test::writeWideRoom(game, 65536.0f, "\"gridsize\" \"8 8 8\"\n");
    const q3::test::MeasuredRun run = runQ3map2(q3map2Command(game, {}, {"-light", "-fast"}, bsp));
    q3::test::expectSuccess(run, "grid size grown");
    const size_t points = q3::bsp::readBsp(bsp).lightGrid.size();
    EXPECT_LE(points, 1048576u);
    EXPECT_GT(points, 1048576u / 2) << "the grid grew far more than the limit needs";
}

// The SH grid's budget is a 256 MiB lump (docs/sh-grid-format.md), about 2.5 million points, so
// this run is heavy and sanitizer builds, which sample their heavy tests, leave it out. The light
// stage holds the grid once, as its lump image; the bound allows four times the lump. The lump
// itself must reach the cap, not pass it.
#if Q3MAP_TEST_MAP_STRIDE <= 1
TEST(LimitsGrid, WideWorldWithTinyShCellsStaysWithinTheLumpBudget) {
    const fs::path game = q3::test::tempDir();
    const fs::path bsp = q3::test::writeWideRoom(game, 65536.0f, "\"gridsize\" \"8 8 8\"\n");
    const q3::test::MeasuredRun run =
        runQ3map2(q3map2Command(game, {}, {"-light", "-fast", "-sh", "-gridsh", "8", "8", "8"}, bsp), 300.0);
    constexpr long kLumpBudgetMb = 256;
    q3::test::expectSuccess(run, "to keep lump 18 within 256 MiB", 4 * kLumpBudgetMb);
    // Lump 18's header entry, read without loading the whole gigabyte.
    std::vector<uint8_t> header(8 + 19 * 8);
    std::ifstream in(bsp, std::ios::binary);
    ASSERT_TRUE(in.read(reinterpret_cast<char*>(header.data()), std::streamsize(header.size())));
    const int64_t shLumpBytes = q3::bsp::test::rawEntries(header, 19).at(18).length;
    EXPECT_LE(shLumpBytes, int64_t(kLumpBudgetMb) << 20);
    // Each growth step enlarges the cell by 8 units, so the final grid lands within a step of the cap.
    EXPECT_GT(shLumpBytes, int64_t(kLumpBudgetMb) << 19) << "the SH grid shrank far below its budget";
    in.close();
    fs::remove_all(game);  // a quarter gigabyte of output is not worth keeping for inspection
}
#endif

}  // namespace
