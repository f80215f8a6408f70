// The -stats JSON summary: produced files validate against docs/stats-schema.json with RapidJSON's
// schema validator, and the schema rejects documents that break it.
#include <gtest/gtest.h>

#include <cmath>
#include <rapidjson/document.h>
#include <rapidjson/schema.h>
#include <rapidjson/stringbuffer.h>
#include <rapidjson/writer.h>

#include "file_io.h"
#include "run_stats.h"
#include "stats_schema.h"
#include "test_data.h"

namespace q3 {
namespace {

rapidjson::Document parseJson(const std::string& text) { return test::parseJsonText(text); }

RunStats sampleStats() {
    RunStats stats;
    stats.stage = "light";
    stats.map = "maps/oacmpdm1.bsp";
    stats.threads = 2;
    stats.phases = {{"load", 0.25}, {"trace", 12.5}, {"grid", 1.0}};
    stats.totalSeconds = 14.0;
    stats.raysTraced = 123456789012ull;
    stats.luxels = 4'000'000;
    stats.warnings = 3;
    stats.legacyGrid = GridDimensions{33, 20, 9};
    stats.shGrid = GridDimensions{65, 40, 17};
    stats.counters["surfaces"] = 912;
    stats.counters["bounceRays"] = 77;
    stats.counters["delta"] = -4;
    return stats;
}

TEST(RunStats, WrittenFileValidatesAndHoldsTheValues) {
    std::filesystem::path path = test::tempDir() / "stats.json";
    RunStats stats = sampleStats();
    writeRunStats(path, stats);
    std::string text = readFileText(path);
    EXPECT_EQ(text, runStatsToJson(stats));
    rapidjson::Document doc = parseJson(text);
    EXPECT_EQ(test::statsSchemaViolation(doc), "");

    EXPECT_EQ(doc["format"].GetInt(), kRunStatsFormat);
    EXPECT_STREQ(doc["stage"].GetString(), "light");
    EXPECT_STREQ(doc["map"].GetString(), "maps/oacmpdm1.bsp");
    EXPECT_EQ(doc["threads"].GetInt(), 2);
    ASSERT_EQ(doc["phases"].Size(), 3u);
    EXPECT_STREQ(doc["phases"][1]["name"].GetString(), "trace");
    EXPECT_DOUBLE_EQ(doc["phases"][1]["seconds"].GetDouble(), 12.5);
    EXPECT_EQ(doc["raysTraced"].GetUint64(), 123456789012ull);
    EXPECT_EQ(doc["luxels"].GetUint64(), 4'000'000u);
    EXPECT_EQ(doc["warnings"].GetInt(), 3);
    const auto& sh = doc["grids"]["sh"];
    EXPECT_EQ(sh["size"][0].GetInt(), 65);
    EXPECT_EQ(sh["size"][2].GetInt(), 17);
    EXPECT_EQ(sh["points"].GetUint64(), 65u * 40u * 17u);
    EXPECT_EQ(doc["grids"]["legacy"]["points"].GetUint64(), 33u * 20u * 9u);
    // Counters come out sorted by name.
    auto counter = doc["counters"].MemberBegin();
    EXPECT_STREQ(counter->name.GetString(), "bounceRays");
    ++counter;
    EXPECT_STREQ(counter->name.GetString(), "delta");
    EXPECT_EQ(counter->value.GetInt64(), -4);
}

TEST(RunStats, EmptySummaryValidatesWithNullGrids) {
    RunStats stats;
    stats.stage = "bsp";
    rapidjson::Document doc = parseJson(runStatsToJson(stats));
    EXPECT_EQ(test::statsSchemaViolation(doc), "");
    EXPECT_TRUE(doc["grids"]["legacy"].IsNull());
    EXPECT_TRUE(doc["grids"]["sh"].IsNull());
    EXPECT_EQ(doc["phases"].Size(), 0u);
}

TEST(RunStats, NonFiniteTimesAreWrittenAsZero) {
    RunStats stats = sampleStats();
    stats.totalSeconds = std::nan("");
    stats.phases[0].seconds = 1.0 / 0.0;
    rapidjson::Document doc = parseJson(runStatsToJson(stats));
    EXPECT_EQ(test::statsSchemaViolation(doc), "");
    EXPECT_EQ(doc["totalSeconds"].GetDouble(), 0.0);
    EXPECT_EQ(doc["phases"][0]["seconds"].GetDouble(), 0.0);
}

TEST(RunStats, SameStatsGiveTheSameBytes) {
    RunStats a = sampleStats();
    RunStats b = sampleStats();
    b.counters.clear();
    b.counters["delta"] = -4;
    b.counters["surfaces"] = 912;
    b.counters["bounceRays"] = 77;
    EXPECT_EQ(runStatsToJson(a), runStatsToJson(b));
}

TEST(RunStats, RecordsPhasesFromTheTimer) {
    double now = 5;
    PhaseTimer timer([&] { return now; });
    timer.begin("trace");
    now += 4;
    timer.end();
    RunStats stats;
    stats.stage = "light";
    stats.recordPhases(timer);
    ASSERT_EQ(stats.phases.size(), 1u);
    EXPECT_EQ(stats.phases[0].name, "trace");
    EXPECT_DOUBLE_EQ(stats.totalSeconds, 4);
}

TEST(RunStats, SchemaRejectsBrokenSummaries) {
    const std::string good = runStatsToJson(sampleStats());
    auto broken = [&](auto&& edit) {
        rapidjson::Document doc = parseJson(good);
        edit(doc);
        return test::statsSchemaViolation(doc);
    };
    EXPECT_NE(broken([](auto& d) { d.RemoveMember("warnings"); }), "");
    EXPECT_NE(broken([](auto& d) { d["warnings"].SetInt(-1); }), "");
    EXPECT_NE(broken([](auto& d) { d["format"].SetInt(2); }), "");
    EXPECT_NE(broken([](auto& d) { d["stage"].SetString(""); }), "");
    EXPECT_NE(broken([](auto& d) { d["grids"]["sh"]["size"].PopBack(); }), "");
    EXPECT_NE(broken([](auto& d) { d["counters"]["surfaces"].SetDouble(1.5); }), "");
    EXPECT_NE(broken([](auto& d) { d["phases"][0].RemoveMember("seconds"); }), "");
    EXPECT_NE(broken([](auto& d) { d.AddMember("extra", 1, d.GetAllocator()); }), "");
    EXPECT_EQ(broken([](auto&) {}), "");
}

TEST(RunStats, UnwritablePathThrowsFileError) {
    std::filesystem::path path = test::tempDir() / "no-such-folder" / "stats.json";
    EXPECT_THROW(writeRunStats(path, sampleStats()), FileError);
    EXPECT_FALSE(std::filesystem::exists(path));
}

}  // namespace
}  // namespace q3
