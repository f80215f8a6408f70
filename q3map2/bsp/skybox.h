// _skybox (q3map2 portals.cpp FloodEntities, surface.cpp MakeSkyboxSurface): the surfaces of a room
// holding a _skybox entity are copied into the sky, scaled by its _scale (64) and turned by its
// angles around it, and drawn in every leaf that draws sky: a 3D sky for the price of a small room.
#pragma once

#include <optional>
#include <vector>

#include "bsp_brushes.h"
#include "draw_surface.h"
#include "model_transform.h"

namespace q3::bspstage {

// The transform of the last _skybox point entity; nullopt when the map has none.
std::optional<ModelTransform> skyboxTransform(const std::vector<BspEntity>& entities);

// The copy of a written surface that is drawn in the sky: vertices moved, no plane normal (so that
// back-face culling of the moved copy does not go wrong), its parent the original's BSP surface.
DrawSurface skyboxCopy(const DrawSurface& ds, const ModelTransform& transform);

}  // namespace q3::bspstage
