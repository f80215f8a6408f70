// Whole-file reads and atomic writes. Every output of the compiler goes through writeFileAtomic so
// that an interrupted run never leaves a half-written file in place of a good one.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace q3 {

// Thrown for any file-system failure; the message names the file and the reason.
struct FileError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

std::vector<uint8_t> readFileBytes(const std::filesystem::path& path);
std::string readFileText(const std::filesystem::path& path);

// Writes to a uniquely named temporary file in the target's folder, flushes it to disk and renames
// it over the target. On failure the temporary is removed and the target is left as it was.
void writeFileAtomic(const std::filesystem::path& path, std::span<const uint8_t> bytes);
void writeFileAtomic(const std::filesystem::path& path, const std::string& text);

// Streaming form of writeFileAtomic for outputs too large to build in memory first: bytes go to
// the temporary file as they come; commit() flushes it to disk and renames it over the target.
// Destroyed without commit() (an exception, an early return), the temporary is removed.
// A file past its first buffer goes on with direct I/O (O_DIRECT) where the file system takes it:
// an SH lump of tens of megabytes then goes to disk from the buffer instead of through fresh page
// cache, which costs several times more (docs/performance.md).
class AtomicFileWriter {
public:
    explicit AtomicFileWriter(std::filesystem::path target);
    ~AtomicFileWriter();
    AtomicFileWriter(const AtomicFileWriter&) = delete;
    AtomicFileWriter& operator=(const AtomicFileWriter&) = delete;

    void write(const void* data, size_t size);
    void commit();

private:
    struct FreeAligned {
        void operator()(uint8_t* p) const;
    };
    void flushBuffer();
    void setDirect(bool on);

    std::filesystem::path target_;
    std::filesystem::path temp_;
    int fd_ = -1;
    bool direct_ = false;  // O_DIRECT on: whole buffers at aligned offsets only
    std::unique_ptr<uint8_t[], FreeAligned> buffer_;  // kBufferSize bytes, page aligned
    size_t used_ = 0;
};

// The prefix of temporary files written by writeFileAtomic ("<name>.tmp-<pid>-<n>"), so that a
// later run can remove leftovers of a killed one.
std::string atomicTempPrefix(const std::filesystem::path& target);
// Removes temporaries left beside `target` by a run that was killed. Returns how many were removed.
int removeStaleTemporaries(const std::filesystem::path& target);

}  // namespace q3
