#include "sh_legacy_grid.h"

#include <cmath>

#include "sh.h"

namespace q3::sh {

void decodeLegacyDirection(const uint8_t point[kLegacyPointBytes], float direction[3]) {
    const double step = 2.0 * kPi / 256.0;
    const double lat = point[7] * step;
    const double lng = point[6] * step;
    direction[0] = float(std::cos(lat) * std::sin(lng));
    direction[1] = float(std::sin(lat) * std::sin(lng));
    direction[2] = float(std::cos(lng));
}

GridPointSH legacyPointToSH(const uint8_t point[kLegacyPointBytes]) {
    float dir[3];
    decodeLegacyDirection(point, dir);
    SH9Color sh;
    addAmbient(sh, {point[0] / 255.0, point[1] / 255.0, point[2] / 255.0});
    addDirectionalIrradiance(sh, {dir[0], dir[1], dir[2]}, {point[3] / 255.0, point[4] / 255.0, point[5] / 255.0});
    return toGridPoint(sh);
}

std::string legacyGridPlacement(const float worldMins[3], const float worldMaxs[3], const float gridSize[3],
                                float origin[3], int32_t bounds[3]) {
    for (int axis = 0; axis < 3; ++axis) {
        const float size = gridSize[axis];
        if (!std::isfinite(size) || !(size > 0)) return "legacy grid size is not positive";
        origin[axis] = size * std::ceil(worldMins[axis] / size);
        const float maxs = size * std::floor(worldMaxs[axis] / size);
        const double count = std::floor((double(maxs) - origin[axis]) / size) + 1.0;
        if (!std::isfinite(origin[axis]) || !(count >= 1) || count > 1e6)
            return "legacy grid has no points along axis " + std::to_string(axis) + " (world too small for gridsize)";
        bounds[axis] = int32_t(count);
    }
    return {};
}

std::string decodeLegacyGrid(const ByteRange& lump, const float worldMins[3], const float worldMaxs[3],
                             const float gridSize[3], GridSH& out, std::vector<uint8_t>& usable) {
    GridSH grid;
    if (std::string err = legacyGridPlacement(worldMins, worldMaxs, gridSize, grid.mins, grid.bounds); !err.empty())
        return err;
    for (int axis = 0; axis < 3; ++axis) grid.size[axis] = gridSize[axis];
    const uint64_t numPoints = uint64_t(grid.bounds[0]) * uint64_t(grid.bounds[1]) * uint64_t(grid.bounds[2]);
    if (numPoints * kLegacyPointBytes != lump.size)
        return "legacy light grid mismatch: lump 15 is " + std::to_string(lump.size) + " bytes, the world bounds need " +
               std::to_string(numPoints) + " points of 8 bytes";
    grid.points.resize(size_t(numPoints));
    usable.assign(size_t(numPoints), 0);
    for (size_t i = 0; i < numPoints; ++i) {
        const uint8_t* point = lump.data + kLegacyPointBytes * i;
        grid.points[i] = legacyPointToSH(point);
        usable[i] = (point[0] | point[1] | point[2]) != 0;
    }
    out = std::move(grid);
    return {};
}

}  // namespace q3::sh
