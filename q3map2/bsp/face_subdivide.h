// Faces of shaders with tessSize cut on that grid (q3map2 surface.cpp SubdivideFaceSurfaces): each
// face spanning more than one grid cell on an axis is cut at the first grid line above its minimum,
// recursively, and its pieces replace it at the end of the list. Sky faces are never cut.
#pragma once

#include <vector>

#include "draw_surface.h"
#include "face_surfaces.h"

namespace q3::bspstage {

// Cuts the faces of `entity` among `surfaces`; a cut face is left empty (kind Bad) for
// tidySurfaces to drop, its pieces appended.
void subdivideFaceSurfaces(std::vector<DrawSurface>& surfaces, const BspEntity& entity, const FaceContext& context,
                           const std::vector<EntitySurfaceParams>& paramsByMapEntity);

// Drops surfaces left without vertices (flares and shader-only surfaces excepted), keeping order.
int tidySurfaces(std::vector<DrawSurface>& surfaces);

}  // namespace q3::bspstage
