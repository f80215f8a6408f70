// The legacy light grid as an engine lays it out when it loads a map: ioquake3's R_LoadEntities
// (worldspawn "gridsize", default 64 64 128) and R_LoadLightGrid (bounds from model 0). The engine
// throws the whole grid away ("light grid mismatch") unless lump 15 holds exactly this many points.
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "bspfile.h"

namespace q3::enginetest {

struct EngineGrid {
    std::array<float, 3> size{};    // cell size the engine reads from the entity lump
    std::array<float, 3> origin{};  // first point: size * ceil(mins / size)
    std::array<int, 3> bounds{};    // points per axis
    int64_t numPoints() const { return int64_t(bounds[0]) * bounds[1] * bounds[2]; }
};

// Parses a "gridsize" value as the engine does (sscanf "%f %f %f": components it cannot read keep
// the default 64 64 128).
std::array<float, 3> engineGridSize(const std::string& value);

// The grid for model 0's bounds and a cell size, in the engine's float arithmetic.
EngineGrid engineGridFor(const std::array<float, 3>& mins, const std::array<float, 3>& maxs,
                         const std::array<float, 3>& size);

// The grid the engine derives from a whole map: worldspawn's gridsize and model 0's bounds.
// Throws bsp::BspError (naming `name`) when the map has no model.
EngineGrid engineGridOf(const bsp::Bsp& bsp, const std::string& name);

}  // namespace q3::enginetest
