// Wall time of a stage's named phases ("load", "trace", "grid", "write"), for the closing summary
// and the -stats file. Phases follow one another; beginning one ends the previous.
#pragma once

#include <string>
#include <vector>

#include "progress.h"

namespace q3 {

struct PhaseTime {
    std::string name;
    double seconds = 0;
};

class PhaseTimer {
public:
    explicit PhaseTimer(ProgressClock clock = steadySeconds);

    void begin(std::string name);
    void end();  // ends the running phase, if any

    // Ends the phase it began when it goes out of scope.
    class Scope {
    public:
        Scope(PhaseTimer& timer, std::string name) : timer_(timer) { timer_.begin(std::move(name)); }
        ~Scope() { timer_.end(); }
        Scope(const Scope&) = delete;
        Scope& operator=(const Scope&) = delete;

    private:
        PhaseTimer& timer_;
    };
    Scope scope(std::string name) { return Scope(*this, std::move(name)); }

    // Finished phases in order; a phase begun twice is listed twice.
    const std::vector<PhaseTime>& phases() const { return phases_; }
    // Time since the timer was made.
    double elapsedSeconds() const;

    // q3map2-style closing lines: one "%9.2f seconds  <phase>" per phase, then
    // "%9.0f seconds elapsed" for the whole run.
    std::vector<std::string> summaryLines() const;
    void printSummary(Log& log) const;

private:
    ProgressClock clock_;
    double start_;
    std::vector<PhaseTime> phases_;
    std::string running_;
    double runningSince_ = 0;
    bool isRunning_ = false;
};

}  // namespace q3
