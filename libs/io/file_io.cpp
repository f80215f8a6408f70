#include "file_io.h"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <sys/stat.h>
#include <unistd.h>

namespace q3 {
namespace fs = std::filesystem;

namespace {

std::string errnoText() { return std::strerror(errno); }

// Direct I/O wants the buffer, the length and the file offset aligned to the device's logical
// block; a page covers every usual one. A whole buffer is a whole number of pages.
constexpr size_t kDirectAlign = 4096;
constexpr size_t kBufferSize = size_t(1) << 20;

}  // namespace

std::vector<uint8_t> readFileBytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw FileError(path.string() + ": cannot open file: " + errnoText());
    in.seekg(0, std::ios::end);
    std::streamoff size = in.tellg();
    if (size < 0) throw FileError(path.string() + ": cannot read file size");
    in.seekg(0, std::ios::beg);
    std::vector<uint8_t> bytes(static_cast<size_t>(size));
    if (size > 0 && !in.read(reinterpret_cast<char*>(bytes.data()), size))
        throw FileError(path.string() + ": read failed");
    return bytes;
}

std::string readFileText(const fs::path& path) {
    std::vector<uint8_t> bytes = readFileBytes(path);
    return std::string(bytes.begin(), bytes.end());
}

std::string atomicTempPrefix(const fs::path& target) {
    return target.filename().string() + ".tmp-";
}

void AtomicFileWriter::FreeAligned::operator()(uint8_t* p) const { std::free(p); }

AtomicFileWriter::AtomicFileWriter(fs::path target) : target_(std::move(target)) {
    static std::atomic<unsigned> counter{0};
    fs::path dir = target_.parent_path().empty() ? fs::path(".") : target_.parent_path();
    temp_ = dir / (atomicTempPrefix(target_) + std::to_string(::getpid()) + "-" + std::to_string(counter.fetch_add(1)));
    buffer_.reset(static_cast<uint8_t*>(std::aligned_alloc(kDirectAlign, kBufferSize)));
    if (!buffer_) throw FileError(target_.string() + ": out of memory for the write buffer");
    fd_ = ::open(temp_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (fd_ < 0) throw FileError(target_.string() + ": cannot create temporary file: " + errnoText());
}

AtomicFileWriter::~AtomicFileWriter() {
    if (fd_ >= 0) {
        ::close(fd_);
        ::unlink(temp_.c_str());
    }
}

void AtomicFileWriter::setDirect(bool on) {
    if (direct_ == on) return;
    const int flags = ::fcntl(fd_, F_GETFL);
    // A file system without direct I/O refuses the flag: the file stays buffered.
    if (flags >= 0 && ::fcntl(fd_, F_SETFL, on ? flags | O_DIRECT : flags & ~O_DIRECT) == 0) direct_ = on;
}

void AtomicFileWriter::flushBuffer() {
    const uint8_t* data = buffer_.get();
    size_t size = used_;
    used_ = 0;
    // Only a whole buffer goes direct; a short last one goes through the page cache.
    setDirect(size == kBufferSize);
    while (size > 0) {
        ssize_t n = ::write(fd_, data, size);
        if (n < 0 && errno == EINVAL && direct_) {
            // Direct I/O refused this write (alignment the device wants beyond a page, or an
            // offset left unaligned by a short write): the rest goes buffered.
            setDirect(false);
            if (direct_) throw FileError(target_.string() + ": write failed: " + errnoText());
            continue;
        }
        if (n < 0) {
            if (errno == EINTR) continue;
            throw FileError(target_.string() + ": write failed: " + errnoText());
        }
        data += n;
        size -= static_cast<size_t>(n);
    }
}

void AtomicFileWriter::write(const void* data, size_t size) {
    if (fd_ < 0) throw FileError(target_.string() + ": write after commit");
    const uint8_t* bytes = static_cast<const uint8_t*>(data);
    while (size > 0) {
        const size_t n = std::min(size, kBufferSize - used_);
        std::memcpy(buffer_.get() + used_, bytes, n);
        used_ += n;
        bytes += n;
        size -= n;
        if (used_ == kBufferSize) flushBuffer();
    }
}

void AtomicFileWriter::commit() {
    if (fd_ < 0) throw FileError(target_.string() + ": committed twice");
    flushBuffer();
    if (::fsync(fd_) != 0) throw FileError(target_.string() + ": fsync failed: " + errnoText());
    // Keep the permissions of the file we replace.
    struct stat st {};
    if (::stat(target_.c_str(), &st) == 0) ::fchmod(fd_, st.st_mode & 07777);
    int fd = fd_;
    fd_ = -1;
    if (::close(fd) != 0) {
        ::unlink(temp_.c_str());
        throw FileError(target_.string() + ": close failed: " + errnoText());
    }
    if (::rename(temp_.c_str(), target_.c_str()) != 0) {
        ::unlink(temp_.c_str());
        throw FileError(target_.string() + ": cannot replace file: " + errnoText());
    }
}

void writeFileAtomic(const fs::path& path, std::span<const uint8_t> bytes) {
    AtomicFileWriter writer(path);
    writer.write(bytes.data(), bytes.size());
    writer.commit();
}

void writeFileAtomic(const fs::path& path, const std::string& text) {
    writeFileAtomic(path, std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(text.data()), text.size()));
}

int removeStaleTemporaries(const fs::path& target) {
    fs::path dir = target.parent_path().empty() ? fs::path(".") : target.parent_path();
    std::string prefix = atomicTempPrefix(target);
    int removed = 0;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(dir, ec)) {
        std::string name = entry.path().filename().string();
        if (name.rfind(prefix, 0) == 0 && fs::remove(entry.path(), ec)) ++removed;
    }
    return removed;
}

}  // namespace q3
