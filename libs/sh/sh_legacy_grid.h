// The legacy Quake 3 light grid (lump 15: 8 bytes per point, ambient RGB, directed RGB, lat/long)
// turned into SH points, so an engine samples either grid the same way.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "sh_bsp_scan.h"
#include "sh_grid_lump.h"

namespace q3::sh {

constexpr size_t kLegacyPointBytes = 8;

// The engine's decoding of the direction bytes (toward the light): lat = byte 7, long = byte 6,
// 256 steps per turn: (cos lat sin lng, sin lat sin lng, cos lng).
void decodeLegacyDirection(const uint8_t point[kLegacyPointBytes], float direction[3]);

// One legacy point as SH irradiance (bytes / 255): the ambient as a uniform term plus the
// directed colour as a directional contribution from the decoded direction, so that the SH
// evaluates to about ambient + directed * max(0, n.dir).
GridPointSH legacyPointToSH(const uint8_t point[kLegacyPointBytes]);

// Grid placement with the engine's rule: origin = size*ceil(mins/size), maxs = size*floor(maxs/size),
// bounds = (maxs - origin)/size + 1 per axis.
std::string legacyGridPlacement(const float worldMins[3], const float worldMaxs[3], const float gridSize[3],
                                float origin[3], int32_t bounds[3]);

// Decodes lump 15 laid out by legacyGridPlacement. `usable[i]` is 0 for points whose ambient bytes
// are all zero (in solid): engines leave them out of the interpolation, as the legacy renderer does.
std::string decodeLegacyGrid(const ByteRange& lump, const float worldMins[3], const float worldMaxs[3],
                             const float gridSize[3], GridSH& out, std::vector<uint8_t>& usable);

}  // namespace q3::sh
