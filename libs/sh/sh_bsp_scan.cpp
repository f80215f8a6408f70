// BSP directory scanning for the grid runtime. Sizes are compared in 64-bit arithmetic so no
// offset or length taken from the file can wrap around.
#include "sh_bsp_scan.h"

#include <cmath>
#include <cstdlib>
#include <cstring>

namespace q3::sh {
namespace {

uint32_t readU32(const uint8_t* p) {
    return uint32_t(p[0]) | (uint32_t(p[1]) << 8) | (uint32_t(p[2]) << 16) | (uint32_t(p[3]) << 24);
}
float readF32(const uint8_t* p) {
    const uint32_t u = readU32(p);
    float v;
    std::memcpy(&v, &u, sizeof v);
    return v;
}

bool rangeInside(uint64_t offset, uint64_t length, uint64_t fileSize) {
    return offset <= fileSize && length <= fileSize - offset;
}

char lowerAscii(char c) { return (c >= 'A' && c <= 'Z') ? char(c - 'A' + 'a') : c; }

bool equalsIgnoreCase(const std::string& a, const char* b) {
    const size_t n = std::strlen(b);
    if (a.size() != n) return false;
    for (size_t i = 0; i < n; ++i)
        if (lowerAscii(a[i]) != lowerAscii(b[i])) return false;
    return true;
}

// Reads the next quoted string or brace of entity text; returns false at the end.
bool nextEntityToken(const char* text, size_t size, size_t& pos, std::string& token, bool& quoted) {
    while (pos < size && (text[pos] == ' ' || text[pos] == '\t' || text[pos] == '\n' || text[pos] == '\r'))
        ++pos;
    if (pos >= size || text[pos] == '\0') return false;
    token.clear();
    if (text[pos] == '"') {
        quoted = true;
        ++pos;
        while (pos < size && text[pos] != '"' && text[pos] != '\0') token += text[pos++];
        if (pos < size && text[pos] == '"') ++pos;
        return true;
    }
    quoted = false;
    if (text[pos] == '{' || text[pos] == '}') {
        token = text[pos++];
        return true;
    }
    while (pos < size && text[pos] != ' ' && text[pos] != '\t' && text[pos] != '\n' && text[pos] != '\r' &&
           text[pos] != '\0' && text[pos] != '"' && text[pos] != '{' && text[pos] != '}')
        token += text[pos++];
    return true;
}

// The header does not store its entry count. `count` entries are plausible when the header fits,
// no non-empty lump starts inside it, and the entries past the 17 of v46 lie inside the file.
bool entryCountFits(const uint8_t* bsp, size_t size, int count) {
    const size_t header = 8 + 8 * size_t(count);
    if (size < header) return false;
    for (int i = 0; i < count; ++i) {
        const uint32_t offset = readU32(bsp + 8 + 8 * i);
        const uint32_t length = readU32(bsp + 12 + 8 * i);
        if (length != 0 && offset < header) return false;
        if (i >= 17 && !rangeInside(offset, length, size)) return false;
    }
    return true;
}

}  // namespace

std::string readBspDirectory(const uint8_t* bsp, size_t size, BspDirectory& out) {
    out = BspDirectory{};
    if (bsp == nullptr || size < 8) return "not a BSP: shorter than 8 bytes";
    if (std::memcmp(bsp, "IBSP", 4) != 0) return "not an IBSP file (bad ident)";
    const uint32_t version = readU32(bsp + 4);
    if (version != 46 && version != 47) return "unsupported IBSP version " + std::to_string(version);
    out.version = int(version);
    if (size < 8 + 8 * size_t(17)) return "BSP header truncated: " + std::to_string(size) + " bytes";
    int count = 17;
    if (version == 47) {
        for (int candidate : {19, 18}) {
            if (entryCountFits(bsp, size, candidate)) {
                count = candidate;
                break;
            }
        }
    }
    out.lumpCount = count;
    out.endOfLumps = 8 + 8 * size_t(count);  // a BSPX trailer never starts inside the header
    for (int i = 0; i < count; ++i) {
        const uint32_t offset = readU32(bsp + 8 + 8 * i);
        const uint32_t length = readU32(bsp + 12 + 8 * i);
        if (length == 0) continue;
        if (offset > uint32_t(INT32_MAX) || length > uint32_t(INT32_MAX) || !rangeInside(offset, length, size))
            return "BSP lump " + std::to_string(i) + " (offset " + std::to_string(offset) + ", length " +
                   std::to_string(length) + ") lies outside the file of " + std::to_string(size) + " bytes";
        out.lumps[i] = {bsp + offset, length};
        if (size_t(offset) + length > out.endOfLumps) out.endOfLumps = size_t(offset) + length;
    }
    return {};
}

std::string findBspxLump(const uint8_t* bsp, size_t size, const BspDirectory& dir, const char* name,
                         ByteRange& out, bool& found) {
    found = false;
    out = {};
    const uint64_t start = (uint64_t(dir.endOfLumps) + 3) & ~uint64_t(3);
    if (!rangeInside(start, 8, size) || std::memcmp(bsp + start, "BSPX", 4) != 0) return {};
    const uint64_t count = readU32(bsp + start + 4);
    if (!rangeInside(start + 8, count * 32, size))
        return "BSPX directory of " + std::to_string(count) + " entries runs past the end of the file";
    for (uint64_t e = 0; e < count; ++e) {
        const uint8_t* entry = bsp + start + 8 + 32 * e;
        char entryName[25] = {};
        std::memcpy(entryName, entry, 24);
        if (std::strcmp(entryName, name) != 0) continue;
        const uint32_t offset = readU32(entry + 24);
        const uint32_t length = readU32(entry + 28);
        if (!rangeInside(offset, length, size))
            return std::string("BSPX lump ") + name + " (offset " + std::to_string(offset) + ", length " +
                   std::to_string(length) + ") lies outside the file of " + std::to_string(size) + " bytes";
        out = {bsp + offset, length};
        found = true;
        return {};
    }
    return {};
}

std::string readWorldBounds(const BspDirectory& dir, float mins[3], float maxs[3]) {
    const ByteRange& models = dir.lumps[kLumpModels];
    if (models.size < 40) return "BSP has no world model (lump 7 shorter than one 40-byte model)";
    for (int axis = 0; axis < 3; ++axis) {
        mins[axis] = readF32(models.data + 4 * axis);
        maxs[axis] = readF32(models.data + 12 + 4 * axis);
        if (!std::isfinite(mins[axis]) || !std::isfinite(maxs[axis]) || mins[axis] > maxs[axis])
            return "BSP world model bounds are not finite and ordered";
    }
    return {};
}

std::string readWorldGridSize(const ByteRange& entities, float gridSize[3]) {
    gridSize[0] = 64;
    gridSize[1] = 64;
    gridSize[2] = 128;
    const char* text = reinterpret_cast<const char*>(entities.data);
    size_t pos = 0;
    std::string token, key;
    bool quoted = false;
    if (!nextEntityToken(text, entities.size, pos, token, quoted) || quoted || token != "{") return {};
    while (nextEntityToken(text, entities.size, pos, key, quoted)) {
        if (!quoted) return {};  // "}" ends worldspawn; anything else is not a key we can read
        if (!nextEntityToken(text, entities.size, pos, token, quoted) || !quoted)
            return "worldspawn key \"" + key + "\" has no value";
        if (!equalsIgnoreCase(key, "gridsize")) continue;
        const char* cursor = token.c_str();
        for (int axis = 0; axis < 3; ++axis) {
            char* end = nullptr;
            const double value = std::strtod(cursor, &end);
            if (end == cursor || !std::isfinite(value) || value <= 0 || value > 1e9)
                return "worldspawn gridsize \"" + token + "\" is not three positive numbers";
            gridSize[axis] = float(value);
            cursor = end;
        }
    }
    return {};
}

}  // namespace q3::sh
