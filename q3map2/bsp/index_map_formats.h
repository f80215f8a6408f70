// The 8-bit palette images q3map2 takes as index maps besides TGA (Load256Image: PCX and BMP),
// read as it reads them: each pixel is its palette index (the palette is never looked at), rows in
// the order q3map2 lays them out.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

namespace q3::bspstage {

struct PaletteIndexes {
    int width = 0;
    int height = 0;
    std::vector<uint8_t> pixels;  // width * height palette indexes
};

// PCX version 5, RLE, 8 bits per pixel, under 640x480 (q3map2 LoadPCX); rows top to bottom. Width
// and height come from xmax and ymax alone. Throws ImageError naming `name` when malformed.
PaletteIndexes decodePcxIndexes(std::span<const uint8_t> bytes, std::string_view name);

// BMP with one plane of 8 bits (q3map2 LoadBMP): the pixel rows as one block from the data offset
// (no row padding), in file order for a bottom-up file (the picture's bottom row first, as q3map2
// reads them) and reversed for a top-down one. Throws ImageError naming `name` when malformed.
PaletteIndexes decodeBmpIndexes(std::span<const uint8_t> bytes, std::string_view name);

}  // namespace q3::bspstage
