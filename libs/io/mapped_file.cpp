#include "mapped_file.h"

#include <cerrno>
#include <cstring>

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include "file_io.h"

namespace q3 {

std::shared_ptr<const MappedFile> MappedFile::open(const std::filesystem::path& path) {
    auto fail = [&](const char* what) {
        return FileError(path.string() + ": cannot " + what + ": " + std::strerror(errno));
    };
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) throw fail("open");
    struct stat info {};
    if (::fstat(fd, &info) != 0) {
        FileError error = fail("stat");
        ::close(fd);
        throw error;
    }
    const size_t size = static_cast<size_t>(info.st_size);
    void* data = nullptr;
    if (size > 0) {
        data = ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE, fd, 0);
        if (data == MAP_FAILED) {
            FileError error = fail("map");
            ::close(fd);
            throw error;
        }
    }
    ::close(fd);  // the mapping keeps the file's pages reachable
    return std::shared_ptr<const MappedFile>(new MappedFile(static_cast<const uint8_t*>(data), size));
}

MappedFile::~MappedFile() {
    if (data_) ::munmap(const_cast<uint8_t*>(data_), size_);
}

}  // namespace q3
