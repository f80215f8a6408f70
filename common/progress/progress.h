// Progress of one parallel job, shown as q3map2 does when the output is not a terminal
// ("0...1...2...3...4...5...6...7...8...9...10 (3)") or, on a terminal, as a bar with elapsed time
// and ETA redrawn in place. advance() may be called from any thread (oneTBB loops); in dots mode
// the text is the same whatever the thread count.
//
//   q3::Progress progress = q3::Progress::forConsole(log, surfaces.size());
//   tbb::parallel_for(..., [&](auto range) { ...; progress.advance(range.size()); });
//   progress.finish();
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdio>
#include <functional>
#include <mutex>
#include <string_view>

#include "log.h"

namespace q3 {

enum class ProgressMode {
    Dots,    // q3map2's pacifier, for logs and pipes (and NetRadiant)
    Bar,     // a redrawn bar, for a terminal
    Silent,  // nothing (q3map2 runs some loops without a pacifier)
};

// Bar when `stream` is a terminal, Dots otherwise.
ProgressMode progressModeFor(std::FILE* stream);

// Seconds from an arbitrary origin; tests pass a fake.
using ProgressClock = std::function<double()>;
double steadySeconds();

// The console a progress display is shown on. `isTerminal` picks the bar over the dots; it is
// normally read from the stream, and set by hand where the caller knows better (tests, a pipe that
// ends in a terminal emulator).
struct ProgressConsole {
    std::FILE* stream = stdout;
    bool isTerminal = false;
    ProgressClock clock = steadySeconds;

    static ProgressConsole of(std::FILE* stream);  // isTerminal from isatty()
};

class Progress {
public:
    using Output = std::function<void(std::string_view)>;

    // Dots mode prints "0" at once (nothing for an empty job). `output` receives text without
    // added newlines; in bar mode each redraw starts with '\r'.
    Progress(std::size_t total, ProgressMode mode, Output output, ProgressClock clock = steadySeconds);
    // Chooses the mode from `console`: dots go through log.raw() (so they also reach NetRadiant),
    // the bar goes straight to the terminal (carriage returns have no place in a log). With
    // show == false nothing is printed.
    static Progress forConsole(Log& log, std::size_t total, bool show = true,
                               std::FILE* console = stdout);
    static Progress forConsole(Log& log, std::size_t total, bool show, const ProgressConsole& console);

    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;
    Progress(Progress&& other) noexcept;
    ~Progress();  // finish()

    // Marks n more items done. Thread-safe and cheap when nothing needs printing.
    void advance(std::size_t n = 1);
    // Completes the display: dots get the remaining marks (when every item was reported) and
    // " (seconds)\n"; the bar is drawn at its final state and ended with a newline. Idempotent.
    void finish();

    std::size_t done() const { return done_.load(); }
    std::size_t total() const { return total_; }

private:
    void draw(bool final);

    std::size_t total_;
    ProgressMode mode_;
    Output output_;
    ProgressClock clock_;
    double start_;
    std::atomic<std::size_t> done_{0};
    std::atomic<int> shownStep_{-1};   // dots: last step printed
    std::mutex printMutex_;
    double lastDraw_ = -1;              // bar: time of the last redraw
    std::atomic<double> nextDraw_{0};   // bar: no redraw before this time (checked without the lock)
    bool finished_ = false;
};

}  // namespace q3
