// The feedback stream as a Log sink, and the entry points main and the stages use:
//
//   auto feedback = q3::connectNetRadiant(options.connect, log);   // nullptr: warned, carry on
//   ...every log line now also reaches NetRadiant...
//   q3::reportLeak(log, feedback.get(), leakPath);                  // -bsp, when the map leaks
//
// The Log keeps the stream alive through its sink; the stream closes its document when the last
// owner lets go, or earlier with feedback->close().
#pragma once

#include <memory>
#include <span>
#include <string>
#include <string_view>

#include "feedback_stream.h"
#include "log.h"
#include "vec3.h"

namespace q3 {

// Connects to the editor at `address` ("host:port", "host", "[v6]:port") and attaches the stream
// to the log. A malformed address or a listener that cannot be reached gives one warning through
// the log and nullptr: the compile runs on without feedback, as q3map2 does.
std::shared_ptr<FeedbackStream> connectNetRadiant(std::string_view address, Log& log,
                                                  FeedbackStreamOptions options = {});

// Sends every line the log prints (with its level) to the stream as a <message> element.
void attachToLog(Log& log, std::shared_ptr<FeedbackStream> stream);

// Keeps the current thread's log lines out of the stream while alive (the line is already going
// to the editor as geometry). Does nothing for a null stream.
class FeedbackEchoMute {
public:
    explicit FeedbackEchoMute(FeedbackStream* stream);
    ~FeedbackEchoMute();
    FeedbackEchoMute(const FeedbackEchoMute&) = delete;
    FeedbackEchoMute& operator=(const FeedbackEchoMute&) = delete;

private:
    FeedbackStream* stream_;
};

// A leak, q3map2 style: the "leaked" banner on the console, and the path (outside first, leaking
// entity last) to the editor as a polyline under a level-3 "MAP LEAKED" message. `stream` may be
// null.
void reportLeak(Log& log, FeedbackStream* stream, std::span<const Vec3> path);

// A problem brush: the editor gets a <select> it can jump to; returns the console line
// "Entity e, Brush b: message". A warning is also printed (and counted) through the log; for an
// error the caller throws CompileError with the returned line.
std::string reportBrushProblem(Log& log, FeedbackStream* stream, int entity, int brush,
                               std::string_view message, bool isError);

}  // namespace q3
