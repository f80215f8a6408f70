#include "engine_grid_count.h"

#include <cmath>
#include <cstdio>
#include <strings.h>

namespace q3::enginetest {

namespace {
// sscanf stores each component it converts and stops at the first one it cannot.
void scanGridSize(const std::string& value, std::array<float, 3>& size) {
    std::sscanf(value.c_str(), "%f %f %f", &size[0], &size[1], &size[2]);
}
}  // namespace

std::array<float, 3> engineGridSize(const std::string& value) {
    std::array<float, 3> size = {64, 64, 128};
    scanGridSize(value, size);
    return size;
}

EngineGrid engineGridFor(const std::array<float, 3>& mins, const std::array<float, 3>& maxs,
                         const std::array<float, 3>& size) {
    EngineGrid grid;
    grid.size = size;
    for (int i = 0; i < 3; ++i) {
        // vec3_t (float) variables: a float quotient, ceil/floor in double, stored back as float.
        grid.origin[i] = float(size[i] * std::ceil(double(mins[i] / size[i])));
        const float last = float(size[i] * std::floor(double(maxs[i] / size[i])));
        grid.bounds[i] = int((last - grid.origin[i]) / size[i] + 1);
    }
    return grid;
}

EngineGrid engineGridOf(const bsp::Bsp& bsp, const std::string& name) {
    if (bsp.models.empty()) throw bsp::BspError(name + ": models: no world model, so no light grid bounds");
    std::array<float, 3> size = {64, 64, 128};
    const std::vector<bsp::Entity> entities = bsp::parseEntities(bsp.entities, name);
    // Only the first entity (worldspawn) is read; every "gridsize" key there is scanned in turn.
    if (!entities.empty())
        for (const auto& [key, value] : entities.front().pairs)
            if (strcasecmp(key.c_str(), "gridsize") == 0) scanGridSize(value, size);
    const bsp::Model& world = bsp.models.front();
    return engineGridFor({world.mins[0], world.mins[1], world.mins[2]},
                         {world.maxs[0], world.maxs[1], world.maxs[2]}, size);
}

}  // namespace q3::enginetest
