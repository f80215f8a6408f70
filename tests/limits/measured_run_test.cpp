// The measuring harness itself: it must see crashes, enforce its time budget and report the peak
// memory of the child, or the limits tests could pass without checking anything.
#include "measured_run.h"

#include <gtest/gtest.h>

namespace {

TEST(MeasuredRun, ReportsExitCodeAndOutput) {
    const q3::test::MeasuredRun run = q3::test::runMeasured({"/bin/sh", "-c", "echo ERROR: one; echo two >&2; exit 3"});
    EXPECT_FALSE(run.signalled);
    EXPECT_EQ(run.exitCode, 3);
    ASSERT_EQ(run.linesStartingWith("ERROR:").size(), 1u);
    EXPECT_NE(run.output.find("two"), std::string::npos);
}

TEST(MeasuredRun, SeesACrash) {
    const q3::test::MeasuredRun run = q3::test::runMeasured({"/bin/sh", "-c", "kill -SEGV $$"});
    EXPECT_TRUE(run.signalled);
    EXPECT_EQ(run.signal, 11);
    EXPECT_FALSE(run.timedOut);
}

TEST(MeasuredRun, KillsARunPastItsTimeBudget) {
    q3::test::RunLimits limits;
    limits.seconds = 0.3;
    const q3::test::MeasuredRun run = q3::test::runMeasured({"/bin/sleep", "30"}, limits);
    EXPECT_TRUE(run.timedOut);
    EXPECT_TRUE(run.signalled);
    EXPECT_LT(run.seconds, 10.0);
}

TEST(MeasuredRun, MeasuresThePeakMemoryOfTheChild) {
    // dd reads 200 MiB of zeros into one buffer, so its resident set passes 200 MiB once.
    const q3::test::MeasuredRun run =
        q3::test::runMeasured({"/bin/dd", "if=/dev/zero", "of=/dev/null", "bs=200M", "count=1"});
    ASSERT_EQ(run.exitCode, 0) << run.describe();
    EXPECT_GT(run.peakRssKb, 200L * 1024) << run.describe();
    EXPECT_LT(run.peakRssKb, 400L * 1024) << run.describe();
}

TEST(MeasuredRun, AMissingProgramIsExitCode127) {
    EXPECT_EQ(q3::test::runMeasured({"/nonexistent/program"}).exitCode, 127);
}

}  // namespace
