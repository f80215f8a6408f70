// Lightmap pages as pictures: q3map2's -export (every lump-14 page to <map>/lightmap_NNNN.tga) and
// -import (edited pages read back into the BSP, as TGA or PNG), and a PNG atlas of all packed
// pages (-lightmapatlas FILE.png) to look at what was baked.
//
// Exported pictures keep q3map2's orientation: page row 0 is the bottom row of the picture, so
// files interchange with q3map2's own -export/-import.
#pragma once

#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "bspfile.h"
#include "common_options.h"
#include "image.h"
#include "log.h"
#include "option_table.h"

namespace q3::light {

struct LightContext;
struct PackedLightmaps;

inline constexpr int kGameLightmapSize = 128;  // side of a lump-14 page in Quake III

// "lightmap_0007.tga" (extension "tga" or "png").
std::string exportedLightmapName(int index, const std::string& extension = "tga");
// Where q3map2 puts exported pages: the BSP path without its extension (maps/foo.bsp -> maps/foo).
std::filesystem::path lightmapExportDir(const std::filesystem::path& bspPath);

// The lump-14 pages of a BSP (RGB, size x size each). Throws BspError (naming `fileName`) when the
// lump is not a whole number of pages.
std::vector<std::span<const uint8_t>> lumpPages(const bsp::Bsp& bsp, const std::string& fileName,
                                                int size = kGameLightmapSize);

// One RGB page as a picture in export orientation (page row 0 at the bottom), opaque.
Image pagePicture(std::span<const uint8_t> rgb, int size);
// The page bytes of an export-orientation picture (alpha dropped). Throws ImageError naming
// `name` when the picture is not size x size.
std::vector<uint8_t> pageFromPicture(const Image& picture, int size, const std::string& name);

// Writes every lump-14 page as <dir>/lightmap_NNNN.tga (atomically, creating dir). Returns the paths.
std::vector<std::filesystem::path> exportLightmapPages(const bsp::Bsp& bsp, const std::filesystem::path& dir,
                                                       const std::string& fileName);
// Replaces every lump-14 page for which <dir>/lightmap_NNNN.tga (or, when absent, .png) exists; a
// page with no picture keeps its bytes and is reported as a warning. Returns the pages replaced.
// Throws ImageError for an unreadable picture or one of the wrong size.
int importLightmapPages(bsp::Bsp& bsp, const std::filesystem::path& dir, const std::string& fileName, Log& log);

// All pages side by side in a grid of ceil(sqrt(n)) columns, each drawn with row 0 at the top (as a
// renderer maps it), unused cells black.
Image lightmapAtlas(std::span<const std::vector<uint8_t>> pages, int pageSize);

// After packing, within -light: -export writes the lump pages next to the BSP; -lightmapatlas
// writes the packed pages (lump or external) as one PNG.
void exportPackedLightmaps(const LightContext& ctx, const PackedLightmaps& packed, Log& log);

// The -export and -import stages on common.mapPath (extension forced to .bsp). -import rewrites the
// BSP atomically. Return the exit code; bad input throws the project's one-line exceptions.
int runExportStage(const CommonOptions& common, Log& log);
int runImportStage(const CommonOptions& common, Log& log);

// -export and -import take no options of their own (the parser refuses any).
struct PictureStageOptions {};
const cli::OptionTable<PictureStageOptions>& pictureStageOptionTable();

}  // namespace q3::light
