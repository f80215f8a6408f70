// One .pk3 (zip) archive: its table of contents, read once, and entry extraction. The archive is
// memory-mapped and minizip reads it through that map. A read borrows a zip handle from the
// archive's pool (opening one only when every pooled handle is in use: an open scans up to 64 KiB
// backwards for the end records), so a Pk3Archive is safe to share between threads.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

namespace q3 {

class MappedFile;

class Pk3Archive {
public:
    struct Entry {
        std::string name;            // as stored in the archive
        uint64_t directoryOffset = 0;  // position of its central directory record
        uint64_t fileNumber = 0;
        uint64_t size = 0;             // uncompressed size declared by the archive
    };

    // nullopt with `error` set when the file is not a readable zip archive.
    static std::optional<Pk3Archive> open(const std::filesystem::path& path, std::string& error);

    const std::filesystem::path& path() const { return path_; }
    // Keyed by normalizeVfsPath(name); directories are not entries.
    const std::unordered_map<std::string, Entry>& entries() const { return entries_; }
    const Entry* find(const std::string& normalizedName) const;
    // Decompresses one entry; throws FileError naming the archive and the entry on any failure
    // (truncated data, bad CRC, size mismatch).
    std::vector<uint8_t> read(const Entry& entry) const;

private:
    struct HandlePool;
    std::filesystem::path path_;
    std::shared_ptr<const MappedFile> file_;
    std::unordered_map<std::string, Entry> entries_;
    std::shared_ptr<HandlePool> handles_;
};

}  // namespace q3
