// Progress objects: exact dots text for several totals, the same text from concurrent advance()
// whatever the thread count, and the bar's redraws on a fake clock.
#include <gtest/gtest.h>

#include <atomic>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include "progress.h"

namespace q3 {
namespace {

struct Capture {
    std::mutex mutex;
    std::string text;
    std::vector<std::string> writes;
    Progress::Output output() {
        return [this](std::string_view s) {
            std::lock_guard lock(mutex);
            text += s;
            writes.emplace_back(s);
        };
    }
};

struct FakeClock {
    std::atomic<double> now{100.0};
    ProgressClock clock() {
        return [this] { return now.load(); };
    }
};

const std::string kFullDots = "0...1...2...3...4...5...6...7...8...9...10";

std::string runSequential(size_t total, size_t chunk, FakeClock& clock) {
    Capture capture;
    {
        Progress progress(total, ProgressMode::Dots, capture.output(), clock.clock());
        for (size_t done = 0; done < total; done += chunk) progress.advance(std::min(chunk, total - done));
        clock.now = clock.now + 2.6;
    }
    return capture.text;
}

TEST(Progress, DotsTextForSeveralTotals) {
    FakeClock clock;
    for (size_t total : {1u, 2u, 3u, 7u, 39u, 40u, 41u, 100u, 1000u, 12345u})
        EXPECT_EQ(runSequential(total, 1, clock), kFullDots + " (2)\n") << "total " << total;
    // Chunked advance (a parallel_for range at a time) prints the same marks.
    EXPECT_EQ(runSequential(1000, 333, clock), kFullDots + " (2)\n");
}

TEST(Progress, DotsAppearAsWorkCompletes) {
    FakeClock clock;
    Capture capture;
    Progress progress(10, ProgressMode::Dots, capture.output(), clock.clock());
    EXPECT_EQ(capture.text, "0");
    progress.advance(1);  // step 4
    EXPECT_EQ(capture.text, "0...1");
    progress.advance(4);  // step 20
    EXPECT_EQ(capture.text, "0...1...2...3...4...5");
    progress.advance(5);
    EXPECT_EQ(capture.text, kFullDots);
    progress.finish();
    progress.finish();  // idempotent
    EXPECT_EQ(capture.text, kFullDots + " (0)\n");
}

TEST(Progress, UnfinishedJobStopsWhereItGot) {
    FakeClock clock;
    Capture capture;
    {
        Progress progress(100, ProgressMode::Dots, capture.output(), clock.clock());
        progress.advance(50);
    }
    EXPECT_EQ(capture.text, "0...1...2...3...4...5 (0)\n");
}

TEST(Progress, EmptyJobPrintsOnlyTheTime) {
    FakeClock clock;
    Capture capture;
    {
        Progress progress(0, ProgressMode::Dots, capture.output(), clock.clock());
    }
    EXPECT_EQ(capture.text, " (0)\n");
}

TEST(Progress, SilentPrintsNothing) {
    FakeClock clock;
    Capture capture;
    {
        Progress progress(10, ProgressMode::Silent, capture.output(), clock.clock());
        progress.advance(10);
    }
    EXPECT_EQ(capture.text, "");
}

TEST(Progress, ConcurrentAdvanceGivesTheSameTextWhateverTheThreadCount) {
    FakeClock clock;
    const size_t total = 20000;
    for (int threads : {1, 2, 3, 8}) {
        Capture capture;
        {
            tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
            Progress progress(total, ProgressMode::Dots, capture.output(), clock.clock());
            tbb::parallel_for(size_t(0), total, [&](size_t) { progress.advance(); });
        }
        EXPECT_EQ(capture.text, kFullDots + " (0)\n") << threads << " threads";
    }
    // Plain threads, each reporting its share in chunks of a different size.
    Capture capture;
    {
        Progress progress(total, ProgressMode::Dots, capture.output(), clock.clock());
        const size_t workers = 6;
        std::vector<std::thread> threads;
        for (size_t t = 0; t < workers; ++t)
            threads.emplace_back([&, t] {
                size_t share = total / workers + (t == workers - 1 ? total % workers : 0);
                for (size_t left = share; left > 0;) {
                    size_t n = std::min(left, t + 1);
                    progress.advance(n);
                    left -= n;
                }
            });
        for (auto& th : threads) th.join();
        EXPECT_EQ(progress.done(), total);
    }
    EXPECT_EQ(capture.text, kFullDots + " (0)\n");
}

TEST(Progress, BarRedrawsInPlaceAtMostTenTimesASecond) {
    FakeClock clock;
    Capture capture;
    Progress progress(200, ProgressMode::Bar, capture.output(), clock.clock());
    ASSERT_EQ(capture.writes.size(), 1u);  // the empty bar
    EXPECT_EQ(capture.writes[0].substr(0, 2), "\r[");
    progress.advance(50);  // same instant: no redraw
    EXPECT_EQ(capture.writes.size(), 1u);
    clock.now = clock.now + 10.0;
    progress.advance(50);
    ASSERT_EQ(capture.writes.size(), 2u);
    EXPECT_EQ(capture.writes[1], "\r[####################....................]   50%  0:10 elapsed, ETA 0:10");
    clock.now = clock.now + 10.0;
    progress.advance(100);
    progress.finish();
    EXPECT_EQ(capture.writes.back(), "\r[########################################]  100%  0:20 elapsed, ETA 0:00\n");
    for (size_t i = 0; i + 1 < capture.writes.size(); ++i)
        EXPECT_EQ(capture.writes[i].find('\n'), std::string::npos);
}

TEST(Progress, ModeFollowsTheStream) {
    std::FILE* file = std::tmpfile();
    ASSERT_NE(file, nullptr);
    EXPECT_EQ(progressModeFor(file), ProgressMode::Dots);
    std::fclose(file);
    EXPECT_EQ(progressModeFor(nullptr), ProgressMode::Dots);
}

TEST(Progress, ConsoleDotsGoThroughTheLog) {
    Log log(false);
    std::string seen;
    log.addSink([&](LogLevel level, std::string_view text) {
        EXPECT_EQ(level, LogLevel::Info);
        seen += text;
    });
    std::FILE* notATerminal = std::tmpfile();
    ASSERT_NE(notATerminal, nullptr);
    {
        Progress progress = Progress::forConsole(log, 5, true, notATerminal);
        progress.advance(5);
    }
    std::fclose(notATerminal);
    EXPECT_EQ(seen.substr(0, kFullDots.size()), kFullDots);
    EXPECT_EQ(seen.back(), '\n');
}

std::string readBack(std::FILE* file) {
    std::fflush(file);
    std::rewind(file);
    std::string text;
    char buffer[256];
    for (size_t n; (n = std::fread(buffer, 1, sizeof buffer, file)) > 0;) text.append(buffer, n);
    return text;
}

TEST(Progress, ConsoleThatIsATerminalShowsTheBarWithElapsedTimeAndEta) {
    Log log(false);
    std::string logged;
    log.addSink([&](LogLevel, std::string_view text) { logged += text; });
    std::FILE* terminal = std::tmpfile();
    ASSERT_NE(terminal, nullptr);
    FakeClock clock;
    {
        Progress progress = Progress::forConsole(log, 8, true, ProgressConsole{terminal, true, clock.clock()});
        clock.now = clock.now + 30.0;
        progress.advance(2);  // 25% after 30 s: 90 s to go
        clock.now = clock.now + 0.05;
        progress.advance(2);  // within a tenth of a second of the last redraw: not drawn
        clock.now = clock.now + 89.95;
        progress.advance(4);
    }
    const std::string bar = "\r[........................................]    0%  0:00 elapsed, ETA --:--"
                            "\r[##########..............................]   25%  0:30 elapsed, ETA 1:30"
                            "\r[########################################]  100%  2:00 elapsed, ETA 0:00"
                            "\r[########################################]  100%  2:00 elapsed, ETA 0:00\n";
    EXPECT_EQ(readBack(terminal), bar);
    std::fclose(terminal);
    EXPECT_EQ(logged, "");  // carriage returns stay out of the log and the NetRadiant stream
}

TEST(Progress, ConsoleThatIsNotATerminalPrintsDotsToTheLogOnly) {
    Log log(false);
    std::string logged;
    log.addSink([&](LogLevel, std::string_view text) { logged += text; });
    std::FILE* file = std::tmpfile();
    ASSERT_NE(file, nullptr);
    FakeClock clock;
    {
        Progress progress = Progress::forConsole(log, 8, true, ProgressConsole{file, false, clock.clock()});
        progress.advance(4);
        EXPECT_EQ(logged, "0...1...2...3...4...5");
        clock.now = clock.now + 7.9;
        progress.advance(4);
    }
    EXPECT_EQ(logged, kFullDots + " (7)\n");
    EXPECT_EQ(readBack(file), "");
    std::fclose(file);
}

TEST(Progress, HiddenConsoleProgressPrintsNothingAnywhere) {
    Log log(false);
    std::string logged;
    log.addSink([&](LogLevel, std::string_view text) { logged += text; });
    std::FILE* terminal = std::tmpfile();
    ASSERT_NE(terminal, nullptr);
    FakeClock clock;
    {
        Progress progress = Progress::forConsole(log, 8, false, ProgressConsole{terminal, true, clock.clock()});
        progress.advance(8);
    }
    EXPECT_EQ(readBack(terminal), "");
    std::fclose(terminal);
    EXPECT_EQ(logged, "");
}

TEST(Progress, ConsoleOfAFileIsNotATerminal) {
    std::FILE* file = std::tmpfile();
    ASSERT_NE(file, nullptr);
    ProgressConsole console = ProgressConsole::of(file);
    EXPECT_EQ(console.stream, file);
    EXPECT_FALSE(console.isTerminal);
    std::fclose(file);
}

}  // namespace
}  // namespace q3
