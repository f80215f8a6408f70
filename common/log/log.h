// Compiler messages. One Log is created by main and passed down; it prints to the console and to
// any extra sinks (the NetRadiant feedback stream, a test's capture), counts warnings, and is safe
// to use from worker threads.
#pragma once

#include <functional>
#include <mutex>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace q3 {

enum class LogLevel { Verbose, Info, Warning, Error };

// A failure that ends the current compile with exit code 1. The message is one line and names the
// file and what is wrong.
struct CompileError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

class Log {
public:
    using Sink = std::function<void(LogLevel, std::string_view)>;

    // With console == false nothing is printed (tests); sinks still receive messages.
    explicit Log(bool console = true) : console_(console) {}

    void setVerbose(bool on) { verbose_ = on; }
    bool verbose() const { return verbose_; }
    void setConsole(bool on) { console_ = on; }

    void addSink(Sink sink);

    void debug(std::string_view text);  // only with -v
    void info(std::string_view text);
    void warning(std::string_view text);  // printed as "WARNING: ..." and counted
    void error(std::string_view text);    // printed as "ERROR: ..."
    // Text without a newline appended (progress dots).
    void raw(std::string_view text);

    int warningCount() const;

    // Holds messages back instead of printing them or passing them to sinks (warnings are still
    // counted here), so that work done in parallel can report in a fixed order: replayInto() then
    // passes them on, in the order they came, to another log.
    void holdMessages() { holding_ = true; }
    void replayInto(Log& other) const;

private:
    struct HeldMessage {
        LogLevel level;
        std::string text;
        bool newline;
    };
    void emit(LogLevel level, std::string_view text, bool newline);

    mutable std::mutex mutex_;
    std::vector<Sink> sinks_;
    bool verbose_ = false;
    bool console_ = true;
    int warnings_ = 0;
    bool holding_ = false;
    std::vector<HeldMessage> held_;
};

}  // namespace q3
