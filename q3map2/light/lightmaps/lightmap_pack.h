// Packing of finished lightmaps (RGB bytes) into pages: solid lightmaps stored as one texel,
// identical lightmaps collapsed, first-fit placement in q3map2's order, then the BSP surfaces' and
// draw vertices' lightmap fields rewritten to match, and lump 14 or external lm_NNNN.tga pages.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "bspfile.h"
#include "color_pipeline.h"

namespace q3::light {

struct PackOptions {
    int pageSize = 128;       // -lightmapsize (power of two >= 2)
    int gamePageSize = 128;   // the game's lump-14 page size
    bool external = false;    // -external: pages go to maps/<map>/lm_NNNN.tga
    bool collapse = true;     // false with -nocollapse (also disables solid lightmaps)
    // Whether identical lightmaps may share texels. False with -deluxe: q3map2 then merges no twins
    // (a twin's directions would be lost) but still stores a solid lightmap as one texel.
    bool twins = true;
    bool fastAllocate = true; // false with -slowallocate: test every position of every page
    // How blocks that carry their light (LightmapBlock::light) turn it into bytes after collapsing:
    // colorToBytes(max(light, minLight), block brightness, color), as q3map2 stores its luxels.
    ColorOptions color;
    Vec3 minLight;
};

// One raw lightmap after ColorToBytes, ready to be placed.
struct LightmapBlock {
    int width = 0, height = 0;
    std::vector<Rgb8> texels;    // width * height, row-major
    std::vector<Rgb8> directionTexels;  // -deluxe: the light direction of every texel; empty = none
    std::vector<uint8_t> used;   // per texel: 0 = carries nothing (may overlap other blocks); empty = all used
    // The light of every texel before its conversion to bytes (q3map2's BSP luxels), minimum light
    // not applied. When every block carries it, solid lightmaps and twins are found on it with
    // q3map2's tolerances (which are in light units, not bytes: -compensate and -gamma change how
    // many bytes they span), and merged twins are converted again (PackOptions::color).
    std::vector<Vec3> light;
    float brightness = 1;        // q3map_lightmapBrightness of the shader: blocks of different ones never collapse
    std::string sortKey;         // shader name of the first surface (the order without shaderNames)
    // Shader names of the surfaces drawn with this lightmap, sorted (q3map2 CompareRawLightmap
    // compares them in turn); empty: sortKey alone.
    std::vector<std::string> shaderNames;
    // Sum of q3map2's four style slots of the raw lightmap (255 for an empty one): lightmaps with
    // fewer styles come first.
    int styleSum = 3 * 255;
    std::vector<int> surfaces;   // BSP surfaces drawn with this lightmap
    // Per surface (same order), per draw vertex: lightmap coordinate in block texel units
    // (0..width, 0..height), as RawLightmap::vertexCoords.
    std::vector<std::vector<std::array<float, 2>>> vertexCoords;
};

struct BlockPlacement {
    int page = -1;          // output page index
    int x = 0, y = 0;       // texel position in the page
    int width = 0, height = 0;  // texels occupied (1 x 1 when solid)
    bool solid = false;
    int twinOf = -1;        // block whose texels this one reuses (collapse), -1 = own texels
};

struct PackedLightmaps {
    int pageSize = 128;
    bool external = false;                    // pages are TGA files, lump 14 stays empty
    bool customSize = false;                  // pageSize != game size without -external
    std::vector<std::vector<uint8_t>> pages;  // RGB bytes, pageSize * pageSize * 3 each
    std::vector<std::vector<uint8_t>> pageUsed;  // per page texel: 1 = written
    std::vector<BlockPlacement> placements;   // per input block

    // BSP lightmapNum of a surface drawn from `page`: the page index for lump-14 and -external pages,
    // -3 for custom-size pages that need a generated shader.
    int lightmapNumForPage(int page) const;
    // Lump 14: the pages back to back (empty for external or custom-size pages).
    std::vector<uint8_t> lump14() const;
    // External and custom-size pages are written as maps/<map>/lm_NNNN.tga (writeExternalLightmaps).
    bool needsExternalFiles() const { return external || customSize; }
};

// True when the block is stored as a single texel: all used texels equal, or at most 2 x 2.
bool blockIsSolid(const LightmapBlock& block);
// q3map2 CompareBSPLuxels on bytes: same size and, over texels used by both, no channel differs by
// more than 3 and the mean difference stays within the luxel tolerance.
bool blocksMatch(const LightmapBlock& a, const LightmapBlock& b);

// Places every block, in q3map2's order: std::sort of the block indices by shader names, style
// sum and area, larger first (its ties fall as libstdc++'s introsort leaves them, which is
// deterministic), then first fit page by page as FindOutLightmaps.
PackedLightmaps packLightmaps(std::span<const LightmapBlock> blocks, const PackOptions& options);

// -fill: grows the written texels of every page into the unused ones, pass after pass, each unused
// texel with a written 4-neighbour (wrapping around the page edges) taking their mean (truncated),
// until nothing changes (q3map2 FillOutLightmap; helps JPEG/PNG compression of external pages).
void fillUnusedTexels(PackedLightmaps& packed);
// -fillpink: every unused texel becomes (255, 0, 255).
void fillUnusedTexelsPink(PackedLightmaps& packed);

// Rewrites lightmapNum/X/Y/Width/Height of every surface of every block and the lightmap st of its
// draw vertices ((x + s) / pageSize; solid blocks use the texel centre), and sets bsp.lightmaps to
// lump14(). Surfaces not in any block are left alone.
void applyPackedLightmaps(bsp::Bsp& bsp, std::span<const LightmapBlock> blocks, const PackedLightmaps& packed);

// 24-bit uncompressed TGA of one page, stored bottom-up as q3map2's WriteTGA24(..., flip) does.
std::vector<uint8_t> encodeLightmapTga(std::span<const uint8_t> rgb, int width, int height);
// Writes every page as <dir>/lm_NNNN.tga (atomic writes, creating `dir`) and removes stale
// lm_NNNN.tga files numbered after the last page, as q3map2 does. Returns the paths written.
std::vector<std::filesystem::path> writeExternalLightmaps(const PackedLightmaps& packed, const std::filesystem::path& dir);
std::string externalLightmapName(int index);  // "lm_0007.tga"

}  // namespace q3::light
