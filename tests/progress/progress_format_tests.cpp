// The pure text of progress displays.
#include <gtest/gtest.h>

#include "progress_format.h"

namespace q3 {
namespace {

TEST(ProgressFormat, PacifierStepsOfForty) {
    EXPECT_EQ(pacifierStep(0, 100), 0);
    EXPECT_EQ(pacifierStep(9, 100), 3);
    EXPECT_EQ(pacifierStep(10, 100), 4);
    EXPECT_EQ(pacifierStep(99, 100), 39);
    EXPECT_EQ(pacifierStep(100, 100), 40);
    EXPECT_EQ(pacifierStep(150, 100), 40);  // over-reporting is clamped
    EXPECT_EQ(pacifierStep(0, 0), 40);      // an empty job is complete
    EXPECT_EQ(pacifierStep(3'000'000'000ull, 4'000'000'000ull), 30);  // no overflow
}

TEST(ProgressFormat, PacifierMarks) {
    EXPECT_EQ(pacifierMarks(-1, 0), "0");
    EXPECT_EQ(pacifierMarks(0, 4), "...1");
    EXPECT_EQ(pacifierMarks(-1, 9), "0...1...2.");
    EXPECT_EQ(pacifierMarks(9, 13), "..3.");
    EXPECT_EQ(pacifierMarks(36, 40), "...10");
    EXPECT_EQ(pacifierMarks(5, 5), "");
    EXPECT_EQ(pacifierMarks(7, 3), "");
    EXPECT_EQ(pacifierMarks(38, 99), ".10");  // never past 40
    EXPECT_EQ(pacifierLine(3), "0...1...2...3...4...5...6...7...8...9...10 (3)\n");
}

TEST(ProgressFormat, Durations) {
    EXPECT_EQ(formatDuration(0), "0:00");
    EXPECT_EQ(formatDuration(59.99), "0:59");
    EXPECT_EQ(formatDuration(61), "1:01");
    EXPECT_EQ(formatDuration(3599), "59:59");
    EXPECT_EQ(formatDuration(3600), "1:00:00");
    EXPECT_EQ(formatDuration(3 * 3600 + 25 * 60 + 7), "3:25:07");
    EXPECT_EQ(formatDuration(-1), "--:--");
    EXPECT_EQ(formatDuration(1.0 / 0.0), "--:--");
}

TEST(ProgressFormat, Bar) {
    EXPECT_EQ(formatProgressBar(0.0, 0.0, 10), "[..........]    0%  0:00 elapsed, ETA --:--");
    EXPECT_EQ(formatProgressBar(0.5, 62.0, 10), "[#####.....]   50%  1:02 elapsed, ETA 1:02");
    EXPECT_EQ(formatProgressBar(0.25, 30.0, 8), "[##......]   25%  0:30 elapsed, ETA 1:30");
    EXPECT_EQ(formatProgressBar(1.0, 3725.0, 4), "[####]  100%  1:02:05 elapsed, ETA 0:00");
    EXPECT_EQ(formatProgressBar(0.999, 10.0, 10), "[#########.]   99%  0:10 elapsed, ETA 0:00");
    // Out-of-range input is clamped rather than drawn past the brackets.
    EXPECT_EQ(formatProgressBar(1.7, 5.0, 4), "[####]  100%  0:05 elapsed, ETA 0:00");
    EXPECT_EQ(formatProgressBar(-0.2, 5.0, 4), "[....]    0%  0:05 elapsed, ETA --:--");
    EXPECT_EQ(formatProgressBar(0.0 / 0.0, 5.0, 4), "[....]    0%  0:05 elapsed, ETA --:--");
}

}  // namespace
}  // namespace q3
