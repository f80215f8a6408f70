// A read-only memory map of a whole file. Archives are mapped instead of read through stdio so that
// opening one and jumping between its entries costs no system calls.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>

namespace q3 {

class MappedFile {
public:
    // Throws FileError naming the file when it cannot be opened or mapped.
    static std::shared_ptr<const MappedFile> open(const std::filesystem::path& path);
    ~MappedFile();
    MappedFile(const MappedFile&) = delete;
    MappedFile& operator=(const MappedFile&) = delete;

    std::span<const uint8_t> bytes() const { return {data_, size_}; }

private:
    MappedFile(const uint8_t* data, size_t size) : data_(data), size_(size) {}
    const uint8_t* data_ = nullptr;
    size_t size_ = 0;
};

}  // namespace q3
