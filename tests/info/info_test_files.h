// Byte-level BSP helpers for the -info tests, written independently of libs/bspfile so that the
// tests check the program against the file format, not against itself.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace q3::test {

using Bytes = std::vector<uint8_t>;

constexpr int kQ3Lumps = 17;

struct LumpEntry {
    int32_t offset = 0, length = 0;
};

Bytes readBytes(const std::filesystem::path& path);
void writeBytes(const std::filesystem::path& path, const Bytes& bytes);

int32_t get32(const Bytes& b, size_t at);
float getFloat(const Bytes& b, size_t at);
void put32(Bytes& b, size_t at, int32_t v);
void putFloat(Bytes& b, size_t at, float v);

// Entry `lump` of the header directory (lumps 0..16 exist in every IBSP header).
LumpEntry lumpEntry(const Bytes& file, int lump);
void setLumpEntry(Bytes& file, int lump, LumpEntry entry);
Bytes lumpData(const Bytes& file, int lump);
// End of the last lump of a 17-entry header, rounded up to 4.
size_t endOfLumps(const Bytes& file);

// A version 47 file with 19 entries: lumps 0..16 of `v46`, lump 17 empty, lump 18 = `sh`.
Bytes withShLump(const Bytes& v46, const Bytes& sh);
// `v46` cut at the end of its lumps, then a BSPX trailer with one lump.
Bytes withBspxLump(const Bytes& v46, const std::string& name, const Bytes& data);

// An SH grid lump: 40-byte header and bx*by*bz points of 27 floats; `coeff0[i]` fills point i's
// coefficient 0 (R, G, B), every other coefficient of a point is coeff0 * 0.1.
Bytes shGridLump(const float mins[3], const float size[3], const int32_t bounds[3],
                 const std::vector<std::array<float, 3>>& coeff0);

struct RunResult {
    int exitCode = -1;
    std::string out, err;
};
// Runs the q3map2 of this build with the given arguments (each quoted), stdout and stderr apart;
// the captured streams go through files in `scratch`.
RunResult runQ3map2(const std::vector<std::string>& args, const std::filesystem::path& scratch);

}  // namespace q3::test
