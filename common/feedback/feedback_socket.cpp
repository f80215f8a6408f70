#include "feedback_socket.h"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/types.h>
#include <unistd.h>

namespace q3 {

namespace {

#ifdef MSG_NOSIGNAL
constexpr int kSendFlags = MSG_NOSIGNAL;
#else
constexpr int kSendFlags = 0;  // SO_NOSIGPIPE is set on the socket instead
#endif

timeval toTimeval(std::chrono::milliseconds ms) {
    timeval tv{};
    tv.tv_sec = static_cast<time_t>(ms.count() / 1000);
    tv.tv_usec = static_cast<suseconds_t>((ms.count() % 1000) * 1000);
    return tv;
}

// Non-blocking connect bounded by a timeout; leaves the socket blocking again on success.
bool connectWithTimeout(int fd, const sockaddr* addr, socklen_t length,
                        std::chrono::milliseconds timeout, std::string* error) {
    int flags = fcntl(fd, F_GETFL, 0);
    fcntl(fd, F_SETFL, flags | O_NONBLOCK);
    int rc = ::connect(fd, addr, length);
    if (rc != 0 && errno != EINPROGRESS) {
        *error = std::strerror(errno);
        return false;
    }
    if (rc != 0) {
        pollfd p{fd, POLLOUT, 0};
        int ready;
        do ready = ::poll(&p, 1, static_cast<int>(timeout.count()));
        while (ready < 0 && errno == EINTR);
        if (ready == 0) {
            *error = "connection timed out";
            return false;
        }
        int soError = 0;
        socklen_t soLength = sizeof soError;
        if (ready < 0 || getsockopt(fd, SOL_SOCKET, SO_ERROR, &soError, &soLength) != 0) {
            *error = std::strerror(errno);
            return false;
        }
        if (soError != 0) {
            *error = std::strerror(soError);
            return false;
        }
    }
    fcntl(fd, F_SETFL, flags);
    return true;
}

}  // namespace

std::optional<FeedbackSocket> FeedbackSocket::connect(const FeedbackAddress& address,
                                                      std::chrono::milliseconds connectTimeout,
                                                      std::chrono::milliseconds sendTimeout,
                                                      std::string* error) {
    addrinfo hints{};
    hints.ai_family = AF_UNSPEC;
    hints.ai_socktype = SOCK_STREAM;
    hints.ai_protocol = IPPROTO_TCP;
    addrinfo* found = nullptr;
    std::string port = std::to_string(address.port);
    int rc = getaddrinfo(address.host.c_str(), port.c_str(), &hints, &found);
    if (rc != 0) {
        *error = std::string("cannot resolve host: ") + gai_strerror(rc);
        return std::nullopt;
    }
    std::string lastError = "no address";
    for (addrinfo* ai = found; ai; ai = ai->ai_next) {
        int fd = ::socket(ai->ai_family, ai->ai_socktype | SOCK_CLOEXEC, ai->ai_protocol);
        if (fd < 0) {
            lastError = std::strerror(errno);
            continue;
        }
        if (!connectWithTimeout(fd, ai->ai_addr, ai->ai_addrlen, connectTimeout, &lastError)) {
            ::close(fd);
            continue;
        }
#ifdef SO_NOSIGPIPE
        int one = 1;
        setsockopt(fd, SOL_SOCKET, SO_NOSIGPIPE, &one, sizeof one);
#endif
        // Each message is one small write; send it at once rather than waiting to coalesce.
        int noDelay = 1;
        setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &noDelay, sizeof noDelay);
        timeval tv = toTimeval(sendTimeout);
        setsockopt(fd, SOL_SOCKET, SO_SNDTIMEO, &tv, sizeof tv);
        freeaddrinfo(found);
        return FeedbackSocket(fd);
    }
    freeaddrinfo(found);
    *error = lastError;
    return std::nullopt;
}

FeedbackSocket::FeedbackSocket(FeedbackSocket&& other) noexcept : fd_(other.fd_) { other.fd_ = -1; }

FeedbackSocket& FeedbackSocket::operator=(FeedbackSocket&& other) noexcept {
    if (this != &other) {
        close();
        fd_ = other.fd_;
        other.fd_ = -1;
    }
    return *this;
}

FeedbackSocket::~FeedbackSocket() { close(); }

void FeedbackSocket::close() {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
}

bool FeedbackSocket::sendAll(std::string_view bytes, std::string* error) {
    if (fd_ < 0) {
        *error = "not connected";
        return false;
    }
    size_t sent = 0;
    while (sent < bytes.size()) {
        ssize_t n = ::send(fd_, bytes.data() + sent, bytes.size() - sent, kSendFlags);
        if (n > 0) {
            sent += static_cast<size_t>(n);
            continue;
        }
        if (n < 0 && errno == EINTR) continue;
        if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK))
            *error = "the listener stopped reading (send timed out)";
        else
            *error = n < 0 ? std::strerror(errno) : "connection closed";
        close();
        return false;
    }
    return true;
}

}  // namespace q3
