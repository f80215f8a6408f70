// Runs a command as a child process and measures it: exit status, output, wall time and peak
// resident memory (getrusage of the child through wait4). A run that exceeds its time budget is
// killed; an address-space cap (not under AddressSanitizer, which reserves terabytes) turns a
// runaway allocation into a failed allocation instead of an out-of-memory kill of the machine.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace q3::test {

struct MeasuredRun {
    int exitCode = -1;      // valid when !signalled
    bool signalled = false;  // ended by a signal (crash, or killed after the time budget)
    int signal = 0;
    bool timedOut = false;
    double seconds = 0.0;
    long peakRssKb = 0;     // ru_maxrss of the child
    std::string output;     // stdout and stderr together

    // The lines of `output` that start with `prefix`.
    std::vector<std::string> linesStartingWith(const std::string& prefix) const;
    // One line summary for failure messages: status, time, memory and the end of the output.
    std::string describe() const;
};

struct RunLimits {
    double seconds = 120.0;
    uint64_t addressSpaceBytes = 8ull << 30;  // ignored under AddressSanitizer
};

// Runs argv[0] (a path) with argv; throws std::runtime_error when it cannot be started.
MeasuredRun runMeasured(const std::vector<std::string>& argv, const RunLimits& limits = {});

}  // namespace q3::test
