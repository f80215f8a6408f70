// The live XML document q3map2 streams to NetRadiant with -connect. Every element is written with
// libxml2's xmlTextWriter and sent (framed as in feedback_protocol.h) as soon as it is complete,
// so the editor shows messages while the compile runs. Safe to use from several threads.
//
// When the listener goes away (EPIPE, ECONNRESET, a send that times out) the stream reports it once
// through its notice callback ("lost connection to NetRadiant; continuing") and every later call
// does nothing: the compile carries on without feedback.
#pragma once

#include <chrono>
#include <functional>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <string_view>
#include <thread>

#include "feedback_protocol.h"
#include "feedback_socket.h"
#include "vec3.h"

namespace q3 {

struct FeedbackStreamOptions {
    std::chrono::milliseconds connectTimeout{5000};
    // A listener that stops reading for this long counts as gone.
    std::chrono::milliseconds sendTimeout{10000};
    // Where the stream's own notices go (the connection loss). They must not go through the Log
    // the stream is attached to, whose lock is held while sinks run. Default: stderr.
    std::function<void(std::string_view)> notice;
};

inline constexpr std::string_view kLostConnectionNotice = "lost connection to NetRadiant; continuing";

class FeedbackStream {
public:
    // Connects and sends the document header (<?xml version="1.0"?> and the opening
    // <q3map_feedback version="1">). Returns nullptr with the reason in *error when the listener
    // cannot be reached.
    static std::unique_ptr<FeedbackStream> open(const FeedbackAddress& address,
                                                FeedbackStreamOptions options, std::string* error);
    ~FeedbackStream();  // close()
    FeedbackStream(const FeedbackStream&) = delete;
    FeedbackStream& operator=(const FeedbackStream&) = delete;

    // <message level="N">text</message>; text is sent as given (console lines keep their '\n').
    void message(FeedbackLevel level, std::string_view text);
    // A console line from the Log; skipped on a thread inside a FeedbackEchoMute (below).
    void messageFromLog(LogLevel level, std::string_view text);

    // A leak: <message level="3">MAP LEAKED\n<polyline><point>x y z</point>...</polyline></message>,
    // the points running from the outside to the leaking entity, printed "%f %f %f" as q3map2's
    // leak file does. NetRadiant draws it as its point file.
    void leak(std::span<const Vec3> path, std::string_view text = "MAP LEAKED\n");
    // A problem brush NetRadiant can select: <select level="2|3">Entity e, Brush b: text<brush>e b
    // </brush></select>.
    void brushSelect(int entity, int brush, std::string_view text, bool isError);
    // A problem at a point: <pointmsg level="N">text<point>x y z</point></pointmsg>.
    void point(std::string_view text, Vec3 where, FeedbackLevel level = FeedbackLevel::Error);
    // A problem polygon: <windingmsg level="N">text<winding>n (x y z)(x y z)...</winding>
    // </windingmsg>.
    void winding(std::string_view text, std::span<const Vec3> points,
                 FeedbackLevel level = FeedbackLevel::Error);

    // Closes the root element and the connection. Further calls do nothing.
    void close();
    // False once closed or the listener is gone.
    bool connected() const;

    // While set for a thread, messageFromLog() from that thread is not sent: used when a problem
    // goes to the editor as geometry and its console line should not be sent a second time.
    void setEchoMutedThread(std::thread::id thread);
    void clearEchoMutedThread();

    struct Impl;

private:
    explicit FeedbackStream(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

}  // namespace q3
