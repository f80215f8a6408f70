// Figures -info reports about the light grids: the legacy grid size engines expect, and
// statistics of an SH grid. Pure functions.
#pragma once

#include "sh_grid_lump.h"

#include <cstdint>
#include <string_view>

namespace q3::info {

// The legacy grid engines derive from model 0's bounds and worldspawn "gridsize"
// (ioquake3 R_LoadLightGrid): origin = size*ceil(mins/size), bounds = (size*floor(maxs/size) - origin)/size + 1.
struct LegacyGridLayout {
    float cellSize[3] = {64, 64, 128};
    float origin[3] = {0, 0, 0};
    int32_t bounds[3] = {0, 0, 0};
    int64_t points = 0;
};

LegacyGridLayout legacyGridLayout(const float worldMins[3], const float worldMaxs[3], const float cellSize[3]);

// Reads worldspawn "gridsize" ("x y z"); absent or malformed components keep 64 64 128, as engines do.
void parseGridSize(std::string_view value, float cellSize[3]);

struct ShGridStats {
    int64_t points = 0;
    float coeff0Min = 0, coeff0Max = 0;
    double coeff0Mean = 0;  // over every point and channel
    int64_t allZeroPoints = 0;  // all 27 floats exactly zero
};

ShGridStats shGridStats(const sh::GridSH& grid);

}  // namespace q3::info
