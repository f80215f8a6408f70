// -debugportals (q3map2 surface.cpp MakeDebugPortalSurfs): every passable portal of the world
// tree becomes a face with the "debugportals" shader, coloured by its place in its leaf's portal
// list, so that the tree can be looked at in the game.
#pragma once

#include <vector>

#include "bsp_tree.h"
#include "draw_surface.h"
#include "plane_set.h"
#include "shader_info.h"

namespace q3::bspstage {

// One face per passable portal, from its front leaf, open leaves in depth-first order.
std::vector<DrawSurface> debugPortalSurfaces(const Tree& tree, PlaneSet& planes, const ShaderTable& shaders);

}  // namespace q3::bspstage
