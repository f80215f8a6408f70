#include "tcp_listener.h"

#include <arpa/inet.h>
#include <cstring>
#include <netinet/in.h>
#include <poll.h>
#include <stdexcept>
#include <sys/socket.h>
#include <unistd.h>

namespace q3::test {

namespace {

int bindLoopback(uint16_t* port, int receiveBuffer) {
    int fd = ::socket(AF_INET, SOCK_STREAM, 0);
    if (fd < 0) throw std::runtime_error("socket() failed");
    if (receiveBuffer > 0) setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &receiveBuffer, sizeof receiveBuffer);
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    addr.sin_port = 0;
    if (::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0)
        throw std::runtime_error("bind() failed");
    socklen_t length = sizeof addr;
    getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &length);
    *port = ntohs(addr.sin_port);
    return fd;
}

// Reads exactly n bytes; false at end of stream or on error.
bool readExactly(int fd, char* out, size_t n) {
    size_t got = 0;
    while (got < n) {
        ssize_t r = ::recv(fd, out + got, n - got, 0);
        if (r <= 0) return false;
        got += static_cast<size_t>(r);
    }
    return true;
}

}  // namespace

TcpListener::TcpListener(Behaviour behaviour) : behaviour_(behaviour) {
    listenFd_ = bindLoopback(&port_, behaviour.neverRead ? 2048 : 0);
    if (::listen(listenFd_, 1) != 0) throw std::runtime_error("listen() failed");
    thread_ = std::thread([this] { run(); });
}

TcpListener::~TcpListener() {
    stop_ = true;
    join();
    if (listenFd_ >= 0) ::close(listenFd_);
}

void TcpListener::join() {
    if (thread_.joinable()) thread_.join();
}

void TcpListener::run() {
    // Accept with a bound so that a test whose sender never connects still ends.
    pollfd p{listenFd_, POLLIN, 0};
    if (::poll(&p, 1, 10000) <= 0) return;
    int fd = ::accept(listenFd_, nullptr, nullptr);
    if (fd < 0) return;
    if (behaviour_.neverRead) {
        while (!stop_) ::usleep(10000);
        ::close(fd);
        return;
    }
    int count = 0;
    for (;;) {
        if (behaviour_.closeAfterChunks > 0 && count >= behaviour_.closeAfterChunks) break;
        unsigned char prefix[4];
        if (!readExactly(fd, reinterpret_cast<char*>(prefix), 4)) break;
        uint32_t length = prefix[0] | (prefix[1] << 8) | (prefix[2] << 16) | (uint32_t(prefix[3]) << 24);
        std::lock_guard lock(mutex_);
        if (length == 0 || length > 1024) {
            errors_.push_back("bad chunk length " + std::to_string(length));
            break;
        }
        std::string body(length, '\0');
        if (!readExactly(fd, body.data(), length)) {
            errors_.push_back("truncated chunk");
            break;
        }
        if (body.back() != '\0') errors_.push_back("chunk without NUL terminator");
        body.pop_back();
        if (body.find('\0') != std::string::npos) errors_.push_back("NUL inside a chunk");
        chunks_.push_back(std::move(body));
        ++count;
    }
    ::close(fd);
}

std::vector<std::string> TcpListener::chunks() const {
    std::lock_guard lock(mutex_);
    return chunks_;
}

std::string TcpListener::joined() const {
    std::string all;
    for (const std::string& c : chunks()) all += c;
    return all;
}

std::vector<std::string> TcpListener::framingErrors() const {
    std::lock_guard lock(mutex_);
    return errors_;
}

uint16_t closedPort() {
    uint16_t port = 0;
    int fd = bindLoopback(&port, 0);
    ::close(fd);
    return port;
}

}  // namespace q3::test
