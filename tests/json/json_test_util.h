#pragma once

#include "bspfile.h"
#include "json_stage.h"
#include "log.h"
#include "sh_grid_lump.h"

#include <filesystem>
#include <string>

namespace q3::test {

// A small but complete BSP (one model, two triangles, a lightmap page, a legacy grid).
bsp::Bsp smallBsp();
// An SH grid of bx*by*bz points with distinct coefficients.
sh::GridSH smallShGrid(int bx, int by, int bz);
// Writes `bsp` to dir/maps/NAME.bsp, returns that path.
std::filesystem::path writeMap(const std::filesystem::path& dir, const std::string& name, const bsp::Bsp& bsp);
// Unpacks `bsp` to `folder` and packs it again, returning the serialised result.
std::vector<uint8_t> unpackThenPack(const bsp::Bsp& bsp, const std::filesystem::path& folder,
                                    json::JsonOptions options = {});
void replaceInFile(const std::filesystem::path& file, const std::string& from, const std::string& to);

}  // namespace q3::test
