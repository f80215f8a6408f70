#include "output_snapshot.h"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>

namespace q3::test {
namespace fs = std::filesystem;

namespace {

constexpr size_t kIbspHeaderEntries = 19;  // v47 has 18 lumps; read one more, bounded by the file

std::vector<uint8_t> readAll(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error(path.string() + ": cannot be read");
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

int32_t loadI32(const std::vector<uint8_t>& bytes, size_t at) {
    int32_t v = 0;
    std::memcpy(&v, bytes.data() + at, sizeof v);
    return v;
}

}  // namespace

FolderSnapshot snapshotFolder(const fs::path& root) {
    FolderSnapshot snapshot;
    for (const auto& item : fs::recursive_directory_iterator(root)) {
        if (!item.is_regular_file()) continue;
        snapshot[fs::relative(item.path(), root).generic_string()] = readAll(item.path());
    }
    return snapshot;
}

std::string bspRegionOf(const std::vector<uint8_t>& file, size_t offset) {
    if (file.size() < 8 || std::memcmp(file.data(), "IBSP", 4) != 0) return "";
    const size_t headerEnd = std::min(file.size(), 8 + 8 * kIbspHeaderEntries);
    for (size_t lump = 0; 8 + 8 * lump + 8 <= headerEnd; ++lump) {
        const int64_t start = loadI32(file, 8 + 8 * lump);
        const int64_t length = loadI32(file, 12 + 8 * lump);
        if (length > 0 && int64_t(offset) >= start && int64_t(offset) < start + length)
            return "lump " + std::to_string(lump);
    }
    return offset < headerEnd ? "header" : "";
}

std::string describeDifferences(const FolderSnapshot& expected, const FolderSnapshot& actual) {
    constexpr int kMaxLines = 6;
    std::string out;
    int lines = 0;
    const auto note = [&](const std::string& line) {
        if (lines++ < kMaxLines) out += line + "\n";
    };
    for (const auto& [name, bytes] : expected) {
        const auto it = actual.find(name);
        if (it == actual.end()) {
            note(name + ": missing from the second run");
            continue;
        }
        const std::vector<uint8_t>& other = it->second;
        if (bytes == other) continue;
        const auto mismatch = std::mismatch(bytes.begin(), bytes.end(), other.begin(), other.end());
        const size_t at = static_cast<size_t>(mismatch.first - bytes.begin());
        const std::string region = bspRegionOf(bytes, at);
        note(name + ": " + std::to_string(bytes.size()) + " vs " + std::to_string(other.size()) +
             " bytes, first difference at byte " + std::to_string(at) + (region.empty() ? "" : " (" + region + ")"));
    }
    for (const auto& [name, bytes] : actual)
        if (!expected.count(name)) note(name + ": only in the second run");
    return out;
}

}  // namespace q3::test
