// IBSP reading and writing: header layout detection (17/18/19 entries), lump extraction, lump 18
// (SH grid) and the BSPX trailer, and the deterministic writer.
#include "bspfile_internal.h"

#include "file_io.h"
#include "sh_grid_lump.h"

#include <algorithm>
#include <climits>

namespace q3::bsp {

namespace {

using detail::fail;
using detail::failLump;
using detail::headerBytes;

struct LumpEntry {
    int64_t offset = 0;
    int64_t length = 0;
};

LumpEntry entryAt(std::span<const uint8_t> file, int index) {
    const uint8_t* p = file.data() + headerBytes(index);
    return {detail::loadI32(p), detail::loadI32(p + 4)};
}

// Entry counts a version may have, largest first.
std::vector<int> candidateEntryCounts(int32_t version) {
    if (version == kVersionQ3) return {18, 17};
    // Quake Live writes 18 entries and the SH grid 19; RTCW/ET maps from id-lineage tools also
    // carry version 47 with the plain 17-entry layout.
    if (version == kVersionQL) return {19, 18, 17};
    return {19, 18, 17};  // forced unknown version
}

// The header does not say how many entries it has. A count is plausible when no non-empty lump
// starts inside the header it implies, and the entries beyond the smallest layout describe real
// ranges of the file (a 17-entry file may have lump data or q3map2's banner text where an 18th
// entry would be).
bool entryCountFits(std::span<const uint8_t> file, int count, int smallest) {
    const size_t header = headerBytes(count);
    if (file.size() < header) return false;
    for (int i = 0; i < count; ++i) {
        const LumpEntry e = entryAt(file, i);
        if (e.length > 0 && e.offset < static_cast<int64_t>(header)) return false;
        if (i >= smallest) {
            if (e.offset < 0 || e.length < 0) return false;
            if (e.offset + e.length > static_cast<int64_t>(file.size())) return false;
        }
    }
    return true;
}

int detectEntryCount(std::span<const uint8_t> file, int32_t version) {
    const std::vector<int> candidates = candidateEntryCounts(version);
    for (int count : candidates)
        if (entryCountFits(file, count, candidates.back())) return count;
    return candidates.back();  // lump checks will say what is wrong
}

std::string printableIdent(const uint8_t* p) {
    std::string out;
    for (int i = 0; i < 4; ++i) {
        const char c = static_cast<char>(p[i]);
        if (c >= 0x20 && c < 0x7f) {
            out += c;
        } else {
            static constexpr char kHex[] = "0123456789abcdef";
            out += "\\x";
            out += kHex[p[i] >> 4];
            out += kHex[p[i] & 15];
        }
    }
    return out;
}

template <typename T>
std::vector<T> recordsOf(std::span<const uint8_t> data, int lump, const std::string& name) {
    if (data.size() % sizeof(T) != 0)
        failLump(name, lump, "length " + std::to_string(data.size()) + " is not a multiple of the record size " +
                                 std::to_string(sizeof(T)));
    return detail::recordsFrom<T>(data.data(), data.size());
}

std::vector<uint8_t> rawOf(std::span<const uint8_t> data) { return std::vector<uint8_t>(data.begin(), data.end()); }

// `range` lies inside `file`: its bytes are moved to the front, the rest dropped, and the buffer
// becomes `target` (its capacity stays that of the file: the other lumps' few megabytes).
void adoptFileBuffer(std::vector<uint8_t>& file, std::span<const uint8_t> range, std::vector<uint8_t>& target) {
    const size_t offset = static_cast<size_t>(range.data() - file.data());
    std::memmove(file.data(), file.data() + offset, range.size());
    file.resize(range.size());
    target = std::move(file);
}

// parseBsp, and readBsp with `file` (the buffer `bytes` views): the SH grid, the one lump that can
// be large (up to 1 GiB, as lump 18 or in the BSPX trailer), then takes over the file's buffer
// instead of being copied beside it.
Bsp parseFrom(std::span<const uint8_t> bytes, const std::string& name, const ReadOptions& options,
              std::vector<uint8_t>* file) {
    const size_t size = bytes.size();
    if (size < 8)
        fail(name, "header", "truncated: file is " + std::to_string(size) + " bytes, a BSP header needs at least 144");
    if (std::memcmp(bytes.data(), kIdent, 4) != 0)
        fail(name, "header", "not an IBSP file (ident \"" + printableIdent(bytes.data()) + "\")");

    Bsp bsp;
    bsp.version = detail::loadI32(bytes.data() + 4);
    if (bsp.version != kVersionQ3 && bsp.version != kVersionQL && !options.force)
        fail(name, "header", "unsupported version " + std::to_string(bsp.version) +
                                 " (expected 46 or 47; -force reads it anyway)");

    const int smallest = candidateEntryCounts(bsp.version).back();
    if (size < headerBytes(smallest))
        fail(name, "header", "truncated: file is " + std::to_string(size) + " bytes, a version " +
                                 std::to_string(bsp.version) + " header needs " +
                                 std::to_string(headerBytes(smallest)));
    bsp.headerLumps = detectEntryCount(bytes, bsp.version);
    const size_t header = headerBytes(bsp.headerLumps);

    // Locate every lump and reject ranges outside the file before touching any data.
    std::span<const uint8_t> data[kMaxLumps];
    size_t endOfLumps = header;
    for (int i = 0; i < bsp.headerLumps; ++i) {
        const LumpEntry e = entryAt(bytes, i);
        if (e.length < 0) failLump(name, i, "negative length " + std::to_string(e.length));
        if (e.offset < 0) failLump(name, i, "negative offset " + std::to_string(e.offset));
        if (e.offset + e.length > static_cast<int64_t>(size))
            failLump(name, i, "offset " + std::to_string(e.offset) + " + length " + std::to_string(e.length) +
                                  " extends past the end of the file (" + std::to_string(size) + " bytes)");
        if (e.length == 0) continue;
        if (e.offset < static_cast<int64_t>(header))
            failLump(name, i, "data at offset " + std::to_string(e.offset) + " overlaps the " +
                                  std::to_string(header) + "-byte header");
        data[i] = bytes.subspan(static_cast<size_t>(e.offset), static_cast<size_t>(e.length));
        endOfLumps = std::max(endOfLumps, static_cast<size_t>(e.offset + e.length));
    }

    bsp.entities.assign(data[LUMP_ENTITIES].begin(), data[LUMP_ENTITIES].end());
    bsp.shaders = recordsOf<Shader>(data[LUMP_SHADERS], LUMP_SHADERS, name);
    bsp.planes = recordsOf<Plane>(data[LUMP_PLANES], LUMP_PLANES, name);
    bsp.nodes = recordsOf<Node>(data[LUMP_NODES], LUMP_NODES, name);
    bsp.leafs = recordsOf<Leaf>(data[LUMP_LEAFS], LUMP_LEAFS, name);
    bsp.leafSurfaces = recordsOf<int32_t>(data[LUMP_LEAFSURFACES], LUMP_LEAFSURFACES, name);
    bsp.leafBrushes = recordsOf<int32_t>(data[LUMP_LEAFBRUSHES], LUMP_LEAFBRUSHES, name);
    bsp.models = recordsOf<Model>(data[LUMP_MODELS], LUMP_MODELS, name);
    bsp.brushes = recordsOf<Brush>(data[LUMP_BRUSHES], LUMP_BRUSHES, name);
    bsp.brushSides = recordsOf<BrushSide>(data[LUMP_BRUSHSIDES], LUMP_BRUSHSIDES, name);
    bsp.drawVerts = recordsOf<DrawVert>(data[LUMP_DRAWVERTS], LUMP_DRAWVERTS, name);
    bsp.drawIndexes = recordsOf<int32_t>(data[LUMP_DRAWINDEXES], LUMP_DRAWINDEXES, name);
    bsp.fogs = recordsOf<Fog>(data[LUMP_FOGS], LUMP_FOGS, name);
    bsp.surfaces = recordsOf<Surface>(data[LUMP_SURFACES], LUMP_SURFACES, name);
    bsp.lightmaps = rawOf(data[LUMP_LIGHTMAPS]);
    bsp.lightGrid = recordsOf<GridPoint>(data[LUMP_LIGHTGRID], LUMP_LIGHTGRID, name);
    bsp.visibility = rawOf(data[LUMP_VISIBILITY]);
    bsp.lump17 = rawOf(data[LUMP_ADVERTISEMENTS]);
    const std::span<const uint8_t> shLump = data[LUMP_LIGHTGRID_SH];
    if (!file) bsp.shGrid = rawOf(shLump);

    // A BSPX trailer starts at the end of the last lump rounded up to 4 bytes; anything else found
    // there is not ours to interpret and is ignored, as the engines do.
    detail::UncopiedLump bspxSh{sh::kBspxLumpName};
    const bool adoptBspx = file && shLump.empty();  // lump 18 takes the buffer when there is one
    const size_t trailer = detail::alignUp4(endOfLumps);
    if (trailer + 4 <= size && std::memcmp(bytes.data() + trailer, "BSPX", 4) == 0)
        bsp.bspx = detail::parseBspxTrailer(bytes, trailer, name, adoptBspx ? &bspxSh : nullptr);
    if (file && !shLump.empty()) adoptFileBuffer(*file, shLump, bsp.shGrid);
    else if (adoptBspx && bspxSh.index != SIZE_MAX) adoptFileBuffer(*file, bspxSh.range, bsp.bspx[bspxSh.index].data);

    if (options.validate) validateBsp(bsp, name);
    return bsp;
}

}  // namespace

Bsp parseBsp(std::span<const uint8_t> bytes, const std::string& name, const ReadOptions& options) {
    return parseFrom(bytes, name, options, nullptr);
}

Bsp readBsp(const std::filesystem::path& path, const ReadOptions& options) {
    std::vector<uint8_t> bytes = readFileBytes(path);
    return parseFrom(bytes, path.string(), options, &bytes);
}

namespace {

class VectorSink : public detail::ByteSink {
public:
    void append(std::span<const uint8_t> bytes) override {
        bytes_.insert(bytes_.end(), bytes.begin(), bytes.end());
        size_ += bytes.size();
    }
    std::vector<uint8_t> take() { return std::move(bytes_); }

private:
    std::vector<uint8_t> bytes_;
};

class FileSink : public detail::ByteSink {
public:
    explicit FileSink(AtomicFileWriter& file) : file_(file) {}
    void append(std::span<const uint8_t> bytes) override {
        file_.write(bytes.data(), bytes.size());
        size_ += bytes.size();
    }

private:
    AtomicFileWriter& file_;
};

// Header (ident, version, lump directory), lumps in order each padded to 4 bytes, BSPX trailer.
void serializeInto(const Bsp& bsp, const std::string& name, detail::ByteSink& out) {
    if (bsp.headerLumps < 17 || bsp.headerLumps > kMaxLumps)
        fail(name, "header", "cannot write " + std::to_string(bsp.headerLumps) + " lump entries (17, 18 or 19)");
    for (int lump = bsp.headerLumps; lump < kMaxLumps; ++lump) {
        const size_t bytes = lumpView(bsp, lump).size();
        if (bytes > 0)
            failLump(name, lump, std::to_string(bytes) + " bytes but the header has only " +
                                     std::to_string(bsp.headerLumps) + " entries");
    }
    // Offsets first, so that the header is written before the lumps and nothing is held twice.
    std::vector<uint8_t> header(headerBytes(bsp.headerLumps), 0);
    std::memcpy(header.data(), kIdent, 4);
    std::memcpy(header.data() + 4, &bsp.version, 4);
    size_t cursor = header.size();
    for (int lump = 0; lump < bsp.headerLumps; ++lump) {
        const size_t bytes = lumpView(bsp, lump).size();
        int32_t entry[2] = {0, 0};  // an empty lump is written as offset 0, length 0
        if (bytes > 0) {
            if (cursor + bytes > static_cast<size_t>(INT32_MAX))
                failLump(name, lump, "file would exceed 2 GiB, the limit of 32-bit lump offsets");
            entry[0] = static_cast<int32_t>(cursor);
            entry[1] = static_cast<int32_t>(bytes);
            cursor = detail::alignUp4(cursor + bytes);
        }
        std::memcpy(header.data() + headerBytes(lump), entry, sizeof entry);
    }
    out.append(header);
    for (int lump = 0; lump < bsp.headerLumps; ++lump) {
        const std::span<const uint8_t> payload = lumpView(bsp, lump);
        if (payload.empty()) continue;
        out.append(payload);
        out.pad4();
    }
    if (!bsp.bspx.empty()) detail::appendBspxTrailer(out, bsp.bspx, name);
}

}  // namespace

std::vector<uint8_t> serializeBsp(const Bsp& bsp, const std::string& name) {
    VectorSink sink;
    serializeInto(bsp, name, sink);
    return sink.take();
}

void writeBsp(const std::filesystem::path& path, const Bsp& bsp) {
    AtomicFileWriter file(path);
    FileSink sink(file);
    serializeInto(bsp, path.string(), sink);
    file.commit();
}

}  // namespace q3::bsp
