// A stand-in for NetRadiant's build monitor: listens on 127.0.0.1 (ephemeral port), accepts one
// connection and collects the l_net-framed chunks it receives until the sender hangs up.
#pragma once

#include <atomic>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace q3::test {

class TcpListener {
public:
    struct Behaviour {
        // Close the connection after this many chunks (0: read until the sender closes).
        int closeAfterChunks = 0;
        // Accept but never read (a listener that hangs); the receive buffer is made small.
        bool neverRead = false;
    };

    explicit TcpListener(Behaviour behaviour);
    ~TcpListener();

    uint16_t port() const { return port_; }
    // Waits for the reading thread to finish (sender closed, or the listener closed early).
    void join();
    // Chunk texts (without length prefix and NUL), and whether every frame was well formed.
    std::vector<std::string> chunks() const;
    std::string joined() const;
    std::vector<std::string> framingErrors() const;

private:
    void run();

    Behaviour behaviour_;
    int listenFd_ = -1;
    uint16_t port_ = 0;
    std::thread thread_;
    std::atomic<bool> stop_{false};
    mutable std::mutex mutex_;
    std::vector<std::string> chunks_;
    std::vector<std::string> errors_;
};

// A port on 127.0.0.1 nobody listens on (bound, then released).
uint16_t closedPort();

}  // namespace q3::test
