// A TCP connection to the editor's build monitor (POSIX sockets). Sending never raises SIGPIPE and
// never blocks for longer than the send timeout, so a listener that goes away or stops reading
// cannot stop the compile.
#pragma once

#include <chrono>
#include <optional>
#include <string>
#include <string_view>

#include "feedback_protocol.h"

namespace q3 {

class FeedbackSocket {
public:
    // Resolves the host (name or numeric) and connects, trying each address in turn, each for at
    // most connectTimeout. On failure returns nullopt and puts the reason in *error.
    static std::optional<FeedbackSocket> connect(const FeedbackAddress& address,
                                                 std::chrono::milliseconds connectTimeout,
                                                 std::chrono::milliseconds sendTimeout,
                                                 std::string* error);

    FeedbackSocket(FeedbackSocket&& other) noexcept;
    FeedbackSocket& operator=(FeedbackSocket&& other) noexcept;
    FeedbackSocket(const FeedbackSocket&) = delete;
    FeedbackSocket& operator=(const FeedbackSocket&) = delete;
    ~FeedbackSocket();

    // Writes every byte. Returns false when the connection is gone (reset, closed, or the send
    // timed out) with the reason in *error; the socket is then closed.
    bool sendAll(std::string_view bytes, std::string* error);
    bool isOpen() const { return fd_ >= 0; }
    void close();

private:
    explicit FeedbackSocket(int fd) : fd_(fd) {}
    int fd_ = -1;
};

}  // namespace q3
