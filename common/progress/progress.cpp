#include "progress.h"

#include <chrono>
#include <cmath>
#include <unistd.h>

#include "progress_format.h"

namespace q3 {

namespace {
// Redraw the bar at most this often; a terminal cannot show more and printing costs time.
constexpr double kBarRedrawSeconds = 0.1;
}  // namespace

ProgressMode progressModeFor(std::FILE* stream) {
    return stream && isatty(fileno(stream)) ? ProgressMode::Bar : ProgressMode::Dots;
}

double steadySeconds() {
    using namespace std::chrono;
    return duration<double>(steady_clock::now().time_since_epoch()).count();
}

Progress::Progress(std::size_t total, ProgressMode mode, Output output, ProgressClock clock)
    : total_(total), mode_(mode), output_(std::move(output)), clock_(std::move(clock)) {
    start_ = clock_();
    if (mode_ == ProgressMode::Dots && total_ > 0) {
        output_(pacifierMarks(-1, 0));
        shownStep_ = 0;
    } else if (mode_ == ProgressMode::Bar) {
        draw(false);
    }
}

ProgressConsole ProgressConsole::of(std::FILE* stream) {
    return ProgressConsole{stream, progressModeFor(stream) == ProgressMode::Bar, steadySeconds};
}

Progress Progress::forConsole(Log& log, std::size_t total, bool show, std::FILE* console) {
    return forConsole(log, total, show, ProgressConsole::of(console));
}

Progress Progress::forConsole(Log& log, std::size_t total, bool show, const ProgressConsole& console) {
    if (!show) return Progress(total, ProgressMode::Silent, [](std::string_view) {}, console.clock);
    if (console.isTerminal && console.stream) {
        std::FILE* stream = console.stream;
        return Progress(
            total, ProgressMode::Bar,
            [stream](std::string_view text) {
                std::fwrite(text.data(), 1, text.size(), stream);
                std::fflush(stream);
            },
            console.clock);
    }
    return Progress(total, ProgressMode::Dots, [&log](std::string_view text) { log.raw(text); }, console.clock);
}

Progress::Progress(Progress&& other) noexcept
    : total_(other.total_), mode_(other.mode_), output_(std::move(other.output_)),
      clock_(std::move(other.clock_)), start_(other.start_), done_(other.done_.load()),
      shownStep_(other.shownStep_.load()), lastDraw_(other.lastDraw_), nextDraw_(other.nextDraw_.load()),
      finished_(other.finished_) {
    other.finished_ = true;  // the moved-from object prints nothing
}

Progress::~Progress() { finish(); }

void Progress::advance(std::size_t n) {
    std::size_t now = done_.fetch_add(n) + n;
    if (mode_ == ProgressMode::Dots) {
        int step = pacifierStep(now, total_);
        if (step <= shownStep_.load(std::memory_order_relaxed)) return;
        std::lock_guard lock(printMutex_);
        if (finished_) return;
        // Another thread may have printed further meanwhile; print only what is still missing, so
        // that the marks always come out in order and exactly once.
        int shown = shownStep_.load();
        step = pacifierStep(done_.load(), total_);
        if (step > shown) {
            output_(pacifierMarks(shown, step));
            shownStep_ = step;
        }
    } else if (mode_ == ProgressMode::Bar) {
        if (clock_() < nextDraw_.load(std::memory_order_relaxed)) return;
        std::lock_guard lock(printMutex_);
        if (finished_) return;
        if (clock_() - lastDraw_ >= kBarRedrawSeconds) draw(false);
    }
}

void Progress::draw(bool final) {
    double now = clock_();
    double fraction = total_ == 0 ? 1.0 : double(std::min(done_.load(), total_)) / double(total_);
    std::string line(1, '\r');
    line += formatProgressBar(fraction, now - start_);
    if (final) line += '\n';
    output_(line);
    lastDraw_ = now;
    nextDraw_ = now + kBarRedrawSeconds;
}

void Progress::finish() {
    std::lock_guard lock(printMutex_);
    if (finished_) return;
    finished_ = true;
    if (mode_ == ProgressMode::Dots) {
        int shown = shownStep_.load();
        int step = pacifierStep(done_.load(), total_);
        if (total_ == 0) step = shown;  // an empty job shows no marks, as in q3map2
        std::string tail = pacifierMarks(shown, step);
        long seconds = static_cast<long>(std::floor(clock_() - start_));
        output_(tail + " (" + std::to_string(seconds) + ")\n");
    } else if (mode_ == ProgressMode::Bar) {
        draw(true);
    }
}

}  // namespace q3
