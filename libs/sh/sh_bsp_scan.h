// Bounds-checked reading of the parts of a Quake 3 BSP image the grid runtime needs: the lump
// directory (v46 with 17 entries, v47 with 18 or 19), the BSPX trailer, model 0 bounds and the
// worldspawn "gridsize". Every function returns an empty string on success, else one line.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace q3::sh {

constexpr int kLumpEntities = 0;
constexpr int kLumpShaders = 1;
constexpr int kLumpPlanes = 2;
constexpr int kLumpNodes = 3;
constexpr int kLumpLeafs = 4;
constexpr int kLumpLeafBrushes = 6;
constexpr int kLumpModels = 7;
constexpr int kLumpBrushes = 8;
constexpr int kLumpBrushSides = 9;
constexpr int kLumpLightGrid = 15;
constexpr int kLumpVisibility = 16;
constexpr int kLumpLightGridSH = 18;
constexpr int kMaxLumps = 19;

struct ByteRange {
    const uint8_t* data = nullptr;
    size_t size = 0;
    bool empty() const { return size == 0; }
};

struct BspDirectory {
    int version = 0;
    int lumpCount = 0;              // 17, 18 or 19
    ByteRange lumps[kMaxLumps];     // entries past lumpCount stay empty
    size_t endOfLumps = 0;          // end of the last non-empty lump (at least the header)
};

// Reads the header: ident "IBSP", version 46 (17 entries) or 47 (19, 18 or 17 entries: the SH
// layout, Quake Live, id-lineage tools), every lump inside the file. A v47 file has N entries when
// no non-empty lump starts inside the N-entry header and entries 17.. lie inside the file.
std::string readBspDirectory(const uint8_t* bsp, size_t size, BspDirectory& out);

// Finds a named lump of the BSPX trailer ("BSPX", uint32 count, {char name[24]; uint32 ofs, len}),
// which starts at endOfLumps rounded up to 4. `found` is false when there is no trailer or no such
// entry; an entry pointing outside the file is an error.
std::string findBspxLump(const uint8_t* bsp, size_t size, const BspDirectory& dir, const char* name,
                         ByteRange& out, bool& found);

// mins/maxs of model 0 (lump 7, first 24 bytes), checked finite and ordered.
std::string readWorldBounds(const BspDirectory& dir, float mins[3], float maxs[3]);

// The worldspawn (first entity) key "gridsize" as three positive numbers; "64 64 128" when absent.
std::string readWorldGridSize(const ByteRange& entities, float gridSize[3]);

}  // namespace q3::sh
