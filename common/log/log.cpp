#include "log.h"

#include <cstdio>

namespace q3 {

void Log::addSink(Sink sink) {
    std::lock_guard lock(mutex_);
    sinks_.push_back(std::move(sink));
}

void Log::debug(std::string_view text) {
    if (verbose_) emit(LogLevel::Verbose, text, true);
}
void Log::info(std::string_view text) { emit(LogLevel::Info, text, true); }
void Log::warning(std::string_view text) { emit(LogLevel::Warning, text, true); }
void Log::error(std::string_view text) { emit(LogLevel::Error, text, true); }
void Log::raw(std::string_view text) { emit(LogLevel::Info, text, false); }

int Log::warningCount() const {
    std::lock_guard lock(mutex_);
    return warnings_;
}

void Log::replayInto(Log& other) const {
    std::vector<HeldMessage> held;
    {
        std::lock_guard lock(mutex_);
        held = held_;
    }
    for (const HeldMessage& m : held) other.emit(m.level, m.text, m.newline);
}

void Log::emit(LogLevel level, std::string_view text, bool newline) {
    std::lock_guard lock(mutex_);
    if (level == LogLevel::Warning) ++warnings_;
    if (holding_) {
        held_.push_back({level, std::string(text), newline});
        return;
    }
    std::string line;
    if (level == LogLevel::Warning) line = "WARNING: ";
    else if (level == LogLevel::Error) line = "ERROR: ";
    line += text;
    if (newline) line += '\n';
    if (console_) {
        FILE* out = level == LogLevel::Error ? stderr : stdout;
        std::fwrite(line.data(), 1, line.size(), out);
        std::fflush(out);
    }
    for (const Sink& sink : sinks_) sink(level, line);
}

}  // namespace q3
