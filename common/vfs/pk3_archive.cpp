// Zip archives through minizip's unzip API.
#include "pk3_archive.h"

#include <algorithm>
#include <cstring>
#include <memory>
#include <mutex>

#include <unzip.h>

#include "file_io.h"
#include "mapped_file.h"
#include "vfs.h"

namespace q3 {

namespace {

struct ZipCloser {
    void operator()(void* handle) const { unzClose(handle); }
};
using ZipHandle = std::unique_ptr<void, ZipCloser>;

// minizip's file functions over a memory map: each opened stream is a cursor into the mapped bytes.
struct MapCursor {
    std::span<const uint8_t> bytes;
    uint64_t position = 0;
};

voidpf ZCALLBACK openCursor(voidpf opaque, const void*, int mode) {
    if ((mode & ZLIB_FILEFUNC_MODE_READWRITEFILTER) != ZLIB_FILEFUNC_MODE_READ) return nullptr;
    return new MapCursor{static_cast<const MappedFile*>(opaque)->bytes(), 0};
}

uLong ZCALLBACK readCursor(voidpf, voidpf stream, void* buffer, uLong size) {
    auto* cursor = static_cast<MapCursor*>(stream);
    // minizip reads the directory's records a byte at a time: those without a library call.
    if (size == 1 && cursor->position < cursor->bytes.size()) {
        *static_cast<uint8_t*>(buffer) = cursor->bytes[cursor->position++];
        return 1;
    }
    const uint64_t available = cursor->position < cursor->bytes.size() ? cursor->bytes.size() - cursor->position : 0;
    const uLong count = static_cast<uLong>(std::min<uint64_t>(size, available));
    if (count > 0) std::memcpy(buffer, cursor->bytes.data() + cursor->position, count);
    cursor->position += count;
    return count;
}

uLong ZCALLBACK writeCursor(voidpf, voidpf, const void*, uLong) { return 0; }

ZPOS64_T ZCALLBACK tellCursor(voidpf, voidpf stream) { return static_cast<MapCursor*>(stream)->position; }

long ZCALLBACK seekCursor(voidpf, voidpf stream, ZPOS64_T offset, int origin) {
    auto* cursor = static_cast<MapCursor*>(stream);
    uint64_t base = 0;
    if (origin == ZLIB_FILEFUNC_SEEK_CUR) base = cursor->position;
    else if (origin == ZLIB_FILEFUNC_SEEK_END) base = cursor->bytes.size();
    else if (origin != ZLIB_FILEFUNC_SEEK_SET) return -1;
    if (offset > cursor->bytes.size() - std::min<uint64_t>(base, cursor->bytes.size())) return -1;
    cursor->position = base + offset;
    return 0;
}

int ZCALLBACK closeCursor(voidpf, voidpf stream) {
    delete static_cast<MapCursor*>(stream);
    return 0;
}

int ZCALLBACK cursorError(voidpf, voidpf) { return 0; }

ZipHandle openZip(const MappedFile& file, const std::filesystem::path& path) {
    zlib_filefunc64_def functions{openCursor, readCursor,  writeCursor, tellCursor,
                                  seekCursor, closeCursor, cursorError, const_cast<MappedFile*>(&file)};
    return ZipHandle(unzOpen2_64(path.string().c_str(), &functions));
}

}  // namespace

// Zip handles not in use by a read. A handle is returned only after a read that closed its entry
// cleanly; one that failed is closed instead.
struct Pk3Archive::HandlePool {
    std::mutex mutex;
    std::vector<ZipHandle> idle;

    ZipHandle take() {
        std::lock_guard lock(mutex);
        if (idle.empty()) return nullptr;
        ZipHandle handle = std::move(idle.back());
        idle.pop_back();
        return handle;
    }
    void give(ZipHandle handle) {
        std::lock_guard lock(mutex);
        idle.push_back(std::move(handle));
    }
};

std::optional<Pk3Archive> Pk3Archive::open(const std::filesystem::path& path, std::string& error) {
    std::shared_ptr<const MappedFile> file;
    try {
        file = MappedFile::open(path);
    } catch (const FileError&) {
        error = "not a readable file";
        return std::nullopt;
    }
    ZipHandle zip = openZip(*file, path);
    if (!zip) {
        error = "not a readable zip archive (corrupt or truncated)";
        return std::nullopt;
    }
    Pk3Archive archive;
    archive.path_ = path;
    archive.file_ = file;
    int status = unzGoToFirstFile(zip.get());
    while (status == UNZ_OK) {
        unz_file_info64 info{};
        char name[1024];
        if (unzGetCurrentFileInfo64(zip.get(), &info, name, sizeof name, nullptr, 0, nullptr, 0) != UNZ_OK) {
            error = "unreadable central directory record";
            return std::nullopt;
        }
        unz64_file_pos position{};
        unzGetFilePos64(zip.get(), &position);
        std::string entryName(name);
        std::string key = normalizeVfsPath(entryName);
        if (!key.empty() && key.back() != '/') {
            // A name stored twice (differing only in case) keeps its first record.
            archive.entries_.try_emplace(key, Entry{entryName, position.pos_in_zip_directory, position.num_of_file,
                                                    info.uncompressed_size});
        }
        status = unzGoToNextFile(zip.get());
    }
    if (status != UNZ_END_OF_LIST_OF_FILE) {
        error = "damaged central directory";
        return std::nullopt;
    }
    archive.handles_ = std::make_shared<HandlePool>();
    archive.handles_->give(std::move(zip));
    return archive;
}

const Pk3Archive::Entry* Pk3Archive::find(const std::string& normalizedName) const {
    auto it = entries_.find(normalizedName);
    return it == entries_.end() ? nullptr : &it->second;
}

std::vector<uint8_t> Pk3Archive::read(const Entry& entry) const {
    auto fail = [&](const std::string& what) -> FileError {
        return FileError(path_.string() + ": cannot read " + entry.name + ": " + what);
    };
    ZipHandle zip = handles_->take();
    if (!zip) zip = openZip(*file_, path_);
    if (!zip) throw fail("archive can no longer be opened");
    unz64_file_pos position{entry.directoryOffset, entry.fileNumber};
    if (unzGoToFilePos64(zip.get(), &position) != UNZ_OK) throw fail("entry not found");
    if (unzOpenCurrentFile(zip.get()) != UNZ_OK) throw fail("bad local header or unsupported compression");
    // Grow while reading rather than trusting the declared size, which a damaged archive may inflate.
    std::vector<uint8_t> bytes;
    bytes.reserve(size_t(std::min<uint64_t>(entry.size, 64u << 20)));
    uint8_t chunk[65536];
    for (;;) {
        int got = unzReadCurrentFile(zip.get(), chunk, sizeof chunk);
        if (got < 0) {
            unzCloseCurrentFile(zip.get());
            throw fail(got == UNZ_CRCERROR ? "CRC mismatch" : "compressed data is damaged or truncated");
        }
        if (got == 0) break;
        bytes.insert(bytes.end(), chunk, chunk + got);
        if (bytes.size() > entry.size) break;
    }
    const int closeStatus = unzCloseCurrentFile(zip.get());
    if (bytes.size() != entry.size)
        throw fail("size " + std::to_string(bytes.size()) + " does not match the declared " + std::to_string(entry.size));
    if (closeStatus == UNZ_CRCERROR) throw fail("CRC mismatch");
    if (closeStatus != UNZ_OK) throw fail("compressed data is damaged or truncated");
    handles_->give(std::move(zip));
    return bytes;
}

}  // namespace q3
