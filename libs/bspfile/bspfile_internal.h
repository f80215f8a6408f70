// Helpers shared by the BSP reader, writer and validator (not part of the public interface).
#pragma once

#include "bspfile.h"

#include <bit>
#include <cstdint>
#include <cstring>
#include <string_view>

namespace q3::bsp::detail {

static_assert(std::endian::native == std::endian::little, "BSP records are read in place: little-endian hosts only");

// "<file>: <lump>: <what>" as a BspError.
[[noreturn]] void fail(const std::string& file, std::string_view where, const std::string& what);
[[noreturn]] void failLump(const std::string& file, int lump, const std::string& what);

// Header size in bytes for a given number of lump entries.
constexpr size_t headerBytes(int entries) { return 8 + 8 * static_cast<size_t>(entries); }

constexpr size_t alignUp4(size_t n) { return (n + 3) & ~size_t(3); }

inline int32_t loadI32(const uint8_t* p) {
    int32_t v;
    std::memcpy(&v, p, sizeof v);
    return v;
}
inline uint32_t loadU32(const uint8_t* p) {
    uint32_t v;
    std::memcpy(&v, p, sizeof v);
    return v;
}
inline void appendU32(std::vector<uint8_t>& out, uint32_t v) {
    uint8_t b[4];
    std::memcpy(b, &v, sizeof v);
    out.insert(out.end(), b, b + 4);
}

// Copies a byte range into a vector of records; the caller has checked the length.
template <typename T>
std::vector<T> recordsFrom(const uint8_t* data, size_t bytes) {
    std::vector<T> out(bytes / sizeof(T));
    if (!out.empty()) std::memcpy(out.data(), data, out.size() * sizeof(T));
    return out;
}
template <typename T>
std::span<const uint8_t> bytesView(const std::vector<T>& records) {
    return {reinterpret_cast<const uint8_t*>(records.data()), records.size() * sizeof(T)};
}

// Where serialized bytes go: a vector, or a file written as they come (large maps are never held
// twice in memory).
class ByteSink {
public:
    virtual ~ByteSink() = default;
    virtual void append(std::span<const uint8_t> bytes) = 0;
    uint64_t size() const { return size_; }
    void pad4() {
        static constexpr uint8_t kZeros[4] = {0, 0, 0, 0};
        append({kZeros, size_t(alignUp4(size_t(size_)) - size_)});
    }

protected:
    uint64_t size_ = 0;
};

// BSPX trailer: parse the directory found at `start` (already known to hold "BSPX"), and append
// one after the lumps of `out` (padded to 4 bytes first).
// With `uncopied` named, the first lump of that name is left empty and its range in `file` is
// stored in *uncopiedRange (with its index in *uncopiedIndex), for the caller to fill without a copy.
struct UncopiedLump {
    std::string_view name;
    std::span<const uint8_t> range;
    size_t index = SIZE_MAX;
};
std::vector<BspxLump> parseBspxTrailer(std::span<const uint8_t> file, size_t start, const std::string& name,
                                       UncopiedLump* uncopied = nullptr);
void appendBspxTrailer(ByteSink& out, const std::vector<BspxLump>& lumps, const std::string& name);

}  // namespace q3::bsp::detail
