#include "file_io.h"

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <sys/stat.h>
#include <unistd.h>

namespace q3 {
namespace fs = std::filesystem;

namespace {

std::string errnoText() { return std::strerror(errno); }

void writeAll(int fd, const uint8_t* data, size_t size, const fs::path& shownAs) {
    while (size > 0) {
        ssize_t n = ::write(fd, data, size);
        if (n < 0) {
            if (errno == EINTR) continue;
            throw FileError(shownAs.string() + ": write failed: " + errnoText());
        }
        data += n;
        size -= static_cast<size_t>(n);
    }
}

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

void writeFileAtomic(const fs::path& path, std::span<const uint8_t> bytes) {
    static std::atomic<unsigned> counter{0};
    fs::path dir = path.parent_path().empty() ? fs::path(".") : path.parent_path();
    fs::path temp = dir / (atomicTempPrefix(path) + std::to_string(::getpid()) + "-" +
                           std::to_string(counter.fetch_add(1)));
    int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (fd < 0) throw FileError(path.string() + ": cannot create temporary file: " + errnoText());
    try {
        writeAll(fd, bytes.data(), bytes.size(), path);
        if (::fsync(fd) != 0) throw FileError(path.string() + ": fsync failed: " + errnoText());
        // Keep the permissions of the file we replace.
        struct stat st {};
        if (::stat(path.c_str(), &st) == 0) ::fchmod(fd, st.st_mode & 07777);
        if (::close(fd) != 0) {
            fd = -1;
            throw FileError(path.string() + ": close failed: " + errnoText());
        }
        fd = -1;
        if (::rename(temp.c_str(), path.c_str()) != 0)
            throw FileError(path.string() + ": cannot replace file: " + errnoText());
    } catch (...) {
        if (fd >= 0) ::close(fd);
        ::unlink(temp.c_str());
        throw;
    }
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
