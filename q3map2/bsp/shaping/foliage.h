// q3map_foliage (q3map2 surface_foliage.cpp Foliage): every triangle of a triangle or meta surface
// (or of a patch, tessellated the older way: see foliage.cpp) whose shader asks for foliage is halved along its longest edge until no edge is longer than the
// density; each piece facing upwards (plane normal z >= 0.5), with enough vertex alpha (average at
// least 0.75, or inverted, or ignored) and a roll of the dice under odds x alpha, places one copy
// of the model at its centre. The copies of one foliage directive are one Foliage surface: the
// model's vertices (scaled, at the origin) followed by one vertex per copy (its position and the
// averaged normal), which an engine instances. The dice are the -bsp stage's shared rand() sequence.
#pragma once

#include <vector>

#include "draw_surface.h"
#include "libc_random.h"
#include "model_surfaces.h"

namespace q3 {
class Log;
}

namespace q3::bspstage {

inline constexpr int kMaxFoliageInstances = 8192;  // per directive and surface (q3map2 MAX_FOLIAGE_INSTANCES)

struct FoliageInputs {
    const ModelInputs& models;
    LoadedMap& map;
    LibcRandom& random;
    int mapEntityNum = 0;  // the model being compiled
};

// Appends the Foliage surfaces of `source` (none unless its shader has q3map_foliage).
void addFoliage(const DrawSurface& source, FoliageInputs& in, std::vector<DrawSurface>& out, Log& log);

}  // namespace q3::bspstage
