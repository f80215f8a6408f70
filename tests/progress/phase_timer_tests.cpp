// Phase timing on a fake clock.
#include <gtest/gtest.h>

#include "phase_timer.h"

namespace q3 {
namespace {

TEST(PhaseTimer, RecordsPhasesInOrderAndPrintsSummaryLines) {
    double now = 10.0;
    PhaseTimer timer([&] { return now; });
    timer.begin("load");
    now += 1.25;
    timer.begin("trace");  // ends "load"
    now += 61.5;
    {
        auto scope = timer.scope("write");
        now += 0.004;
    }
    now += 0.5;  // between phases: counted in the total only
    timer.end();  // nothing running: no effect

    ASSERT_EQ(timer.phases().size(), 3u);
    EXPECT_EQ(timer.phases()[0].name, "load");
    EXPECT_DOUBLE_EQ(timer.phases()[0].seconds, 1.25);
    EXPECT_EQ(timer.phases()[1].name, "trace");
    EXPECT_DOUBLE_EQ(timer.phases()[1].seconds, 61.5);
    EXPECT_NEAR(timer.phases()[2].seconds, 0.004, 1e-9);
    EXPECT_NEAR(timer.elapsedSeconds(), 63.254, 1e-9);

    std::vector<std::string> lines = timer.summaryLines();
    ASSERT_EQ(lines.size(), 4u);
    EXPECT_EQ(lines[0], "     1.25 seconds  load");
    EXPECT_EQ(lines[1], "    61.50 seconds  trace");
    EXPECT_EQ(lines[2], "     0.00 seconds  write");
    EXPECT_EQ(lines[3], "       63 seconds elapsed");

    Log log(false);
    std::string printed;
    log.addSink([&](LogLevel, std::string_view text) { printed += text; });
    timer.printSummary(log);
    EXPECT_EQ(printed, lines[0] + "\n" + lines[1] + "\n" + lines[2] + "\n" + lines[3] + "\n");
}

TEST(PhaseTimer, RepeatedPhaseIsListedTwice) {
    double now = 0;
    PhaseTimer timer([&] { return now; });
    timer.begin("bounce");
    now += 2;
    timer.begin("bounce");
    now += 3;
    timer.end();
    ASSERT_EQ(timer.phases().size(), 2u);
    EXPECT_DOUBLE_EQ(timer.phases()[1].seconds, 3);
}

}  // namespace
}  // namespace q3
