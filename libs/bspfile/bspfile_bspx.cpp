// The BSPX trailer: "BSPX", uint32 count, then count x {char name[24]; uint32 offset, length}, found
// at the end of the last lump rounded up to 4 bytes. Offsets are from the start of the file.
#include "bspfile_internal.h"

#include <algorithm>

namespace q3::bsp {

namespace {

constexpr size_t kNameBytes = 24;
constexpr size_t kEntryBytes = kNameBytes + 8;
constexpr size_t kTrailerHeaderBytes = 8;

}  // namespace

const BspxLump* Bsp::findBspx(std::string_view name) const {
    for (const BspxLump& lump : bspx)
        if (lump.name == name) return &lump;
    return nullptr;
}

void Bsp::setBspx(std::string name, std::vector<uint8_t> data) {
    for (BspxLump& lump : bspx) {
        if (lump.name == name) {
            lump.data = std::move(data);
            return;
        }
    }
    bspx.push_back({std::move(name), std::move(data)});
}

bool Bsp::removeBspx(std::string_view name) {
    auto it = std::find_if(bspx.begin(), bspx.end(), [&](const BspxLump& l) { return l.name == name; });
    if (it == bspx.end()) return false;
    bspx.erase(it);
    return true;
}

namespace detail {

std::vector<BspxLump> parseBspxTrailer(std::span<const uint8_t> file, size_t start, const std::string& name,
                                       UncopiedLump* uncopied) {
    const size_t size = file.size();
    if (start + kTrailerHeaderBytes > size)
        fail(name, "bspx", "trailer header truncated at offset " + std::to_string(start));
    const uint64_t count = loadU32(file.data() + start + 4);
    const uint64_t room = (size - start - kTrailerHeaderBytes) / kEntryBytes;
    if (count > room)
        fail(name, "bspx", "directory claims " + std::to_string(count) + " entries but only " +
                               std::to_string(room) + " fit in the file");
    std::vector<BspxLump> lumps;
    lumps.reserve(static_cast<size_t>(count));
    for (uint64_t i = 0; i < count; ++i) {
        const uint8_t* entry = file.data() + start + kTrailerHeaderBytes + i * kEntryBytes;
        const char* text = reinterpret_cast<const char*>(entry);
        const size_t nameLength = std::find(text, text + kNameBytes, '\0') - text;
        const std::string where = "entry " + std::to_string(i);
        if (nameLength == kNameBytes) fail(name, "bspx", where + ": name is not NUL-terminated within 24 bytes");
        if (nameLength == 0) fail(name, "bspx", where + ": empty name");
        BspxLump lump;
        lump.name.assign(text, nameLength);
        const uint64_t offset = loadU32(entry + kNameBytes);
        const uint64_t length = loadU32(entry + kNameBytes + 4);
        if (length > 0) {
            if (offset > size || length > size - offset)
                fail(name, "bspx", "lump \"" + lump.name + "\" (offset " + std::to_string(offset) + ", length " +
                                       std::to_string(length) + ") extends past the end of the file (" +
                                       std::to_string(size) + " bytes)");
            if (uncopied && uncopied->index == SIZE_MAX && lump.name == uncopied->name) {
                uncopied->range = file.subspan(static_cast<size_t>(offset), static_cast<size_t>(length));
                uncopied->index = lumps.size();
            } else {
                lump.data.assign(file.begin() + static_cast<ptrdiff_t>(offset),
                                 file.begin() + static_cast<ptrdiff_t>(offset + length));
            }
        }
        lumps.push_back(std::move(lump));
    }
    return lumps;
}

void appendBspxTrailer(ByteSink& out, const std::vector<BspxLump>& lumps, const std::string& name) {
    out.pad4();
    const uint64_t directoryStart = out.size();
    const uint64_t dataStart = directoryStart + kTrailerHeaderBytes + lumps.size() * kEntryBytes;

    // Lay the data out first so the directory can be written in one pass.
    std::vector<std::pair<uint64_t, uint64_t>> placement;
    uint64_t cursor = dataStart;
    for (const BspxLump& lump : lumps) {
        if (lump.name.empty()) fail(name, "bspx", "a lump has an empty name");
        if (lump.name.size() >= kNameBytes)
            fail(name, "bspx", "lump name \"" + lump.name + "\" is longer than 23 characters");
        if (lump.name.find('\0') != std::string::npos)
            fail(name, "bspx", "lump name contains a NUL byte");
        if (lump.data.empty()) {
            placement.emplace_back(0, 0);
            continue;
        }
        placement.emplace_back(cursor, lump.data.size());
        cursor = alignUp4(cursor + lump.data.size());
    }
    if (cursor > UINT32_MAX) fail(name, "bspx", "trailer would extend past 4 GiB");

    std::vector<uint8_t> directory = {'B', 'S', 'P', 'X'};
    appendU32(directory, static_cast<uint32_t>(lumps.size()));
    for (size_t i = 0; i < lumps.size(); ++i) {
        char field[kNameBytes] = {};
        std::memcpy(field, lumps[i].name.data(), lumps[i].name.size());
        directory.insert(directory.end(), field, field + kNameBytes);
        appendU32(directory, static_cast<uint32_t>(placement[i].first));
        appendU32(directory, static_cast<uint32_t>(placement[i].second));
    }
    out.append(directory);
    for (const BspxLump& lump : lumps) {
        out.append(lump.data);
        out.pad4();
    }
}

}  // namespace detail
}  // namespace q3::bsp
