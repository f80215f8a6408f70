// The text of progress displays, as pure functions of the state they show.
//
// q3map2's pacifier (RunThreadsOn / GetThreadWork) divides the work into 40 steps and prints a
// digit every fourth step and a dot otherwise: "0...1...2...3...4...5...6...7...8...9...". It
// counts items as they are handed out, so it stops at 9; this project counts them as they
// complete, so a finished run reaches "10". A step that jumps several marks prints every mark it
// passes, so the text depends only on how far the work got: the same whatever the thread count.
#pragma once

#include <cstddef>
#include <string>

namespace q3 {

inline constexpr int kPacifierSteps = 40;

// The step (0..40) reached after `done` of `total` items; an empty job is complete at once.
int pacifierStep(std::size_t done, std::size_t total);
// The marks for steps after `fromStep` up to and including `toStep` ("0" for step 0, "1" for 4,
// "." between); empty when toStep <= fromStep. Start from -1 to include the leading "0".
std::string pacifierMarks(int fromStep, int toStep);
// The whole line for a finished job: marks from -1 to 40 and q3map2's " (seconds)" ending.
std::string pacifierLine(long wholeSeconds);

// A duration as "m:ss", or "h:mm:ss" from an hour up. Negative or non-finite values show "--:--".
std::string formatDuration(double seconds);

// One line of the terminal bar: "[#####.....]  50%  1:02 elapsed, ETA 1:02". The ETA is the
// elapsed time scaled by the remaining fraction ("--:--" before any progress). `barWidth` is the
// number of cells between the brackets.
std::string formatProgressBar(double fraction, double elapsedSeconds, int barWidth = 40);

}  // namespace q3
