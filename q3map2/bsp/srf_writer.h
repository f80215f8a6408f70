// The .srf file -bsp writes beside the BSP (q3map2 surface_extra.cpp WriteSurfaceExtraFile): a
// "default" block, then one block per BSP surface in order with its shader and the values that
// differ from the default (entity, shadow flags, sample size, ambient colour, longest curve, lightmap
// axis).
// -light reads it (q3map2/light/srf_file.h).
#pragma once

#include <span>
#include <string>
#include <vector>

#include "bsp_brushes.h"
#include "draw_surface.h"

namespace q3::bspstage {

// `surfaces` in BSP surface order; `map` names their shaders; `entityParams` (per .map entity, the
// worldspawn first) gives the ambient colours: the worldspawn's in the default block, another
// entity's on its surfaces when it is set and differs.
std::string surfaceExtraText(const std::vector<const DrawSurface*>& surfaces, int defaultSampleSize,
                             const LoadedMap& map, std::span<const EntitySurfaceParams> entityParams);

}  // namespace q3::bspstage
