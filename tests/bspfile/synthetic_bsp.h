// Small, fully consistent BSPs built in memory, and an independent reader of raw header entries so
// tests can check file images without going through the library's own parser.
#pragma once

#include "bspfile.h"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace q3::bsp::test {

// A one-room world: 2 shaders, 6 planes, 1 node, 2 leafs, a 6-sided brush with a fog, a planar
// quad and a 3x3 patch, one lightmap page, a 2x2x2 light grid, 1-cluster visibility, 2 entities.
Bsp makeSyntheticBsp();

// A valid SH grid lump image of bx*by*bz points with distinct coefficients.
std::vector<uint8_t> makeShGridLump(int bx, int by, int bz);

struct RawEntry {
    int32_t offset = 0;
    int32_t length = 0;
};
// Reads `count` header entries straight from the bytes.
std::vector<RawEntry> rawEntries(std::span<const uint8_t> file, int count);
// The bytes a header entry points at (empty for length 0).
std::vector<uint8_t> rawLump(std::span<const uint8_t> file, const RawEntry& entry);
// Overwrites header entry `lump` of a file image.
void setRawEntry(std::vector<uint8_t>& file, int lump, int32_t offset, int32_t length);
void storeI32(std::vector<uint8_t>& file, size_t at, int32_t value);
void storeU32(std::vector<uint8_t>& file, size_t at, uint32_t value);

// Builds a file image the way other compilers lay files out, independently of serializeBsp:
// `entries` header slots, then `gap` (e.g. q3map2's banner text), then the lumps in `order`,
// 4-byte aligned. Empty lumps get `emptyOffset` (q3map2 stores the current file position there,
// id's tools 0): pass -1 for "current position".
std::vector<uint8_t> buildRawImage(int32_t version, int entries, const std::vector<std::vector<uint8_t>>& lumps,
                                   const std::string& gap, const std::vector<int>& order, int32_t emptyOffset);

}  // namespace q3::bsp::test
