#include "phase_timer.h"

#include <cstdio>

namespace q3 {

PhaseTimer::PhaseTimer(ProgressClock clock) : clock_(std::move(clock)) { start_ = clock_(); }

void PhaseTimer::begin(std::string name) {
    end();
    running_ = std::move(name);
    runningSince_ = clock_();
    isRunning_ = true;
}

void PhaseTimer::end() {
    if (!isRunning_) return;
    phases_.push_back({std::move(running_), clock_() - runningSince_});
    running_.clear();
    isRunning_ = false;
}

double PhaseTimer::elapsedSeconds() const { return clock_() - start_; }

std::vector<std::string> PhaseTimer::summaryLines() const {
    std::vector<std::string> lines;
    char buffer[64];
    for (const PhaseTime& phase : phases_) {
        std::snprintf(buffer, sizeof buffer, "%9.2f seconds  ", phase.seconds);
        lines.push_back(buffer + phase.name);
    }
    std::snprintf(buffer, sizeof buffer, "%9.0f seconds elapsed", elapsedSeconds());
    lines.emplace_back(buffer);
    return lines;
}

void PhaseTimer::printSummary(Log& log) const {
    for (const std::string& line : summaryLines()) log.info(line);
}

}  // namespace q3
