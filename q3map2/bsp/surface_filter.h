// Which leaves draw a surface (q3map2 surface.cpp FilterDrawsurfsIntoTree's filtering): faces by
// clipping their winding down the tree, patches by the convex hull of points that bound every
// level of detail, triangle surfaces by each triangle and each vertex, flares by their origin.
// Only open (non-opaque) leaves take references.
#pragma once

#include "bsp_tree.h"
#include "draw_surface.h"
#include "plane_set.h"

namespace q3::bspstage {

// Adds `outputNum` to the drawSurfaces of every open leaf the surface touches (once per leaf);
// returns the number of references added. A surface with none is not written. A leaf reached marks
// a sky shader's surface on it (TreeNode::sky), and a _skybox leaf marks the surface (skybox).
int filterSurfaceIntoTree(DrawSurface& ds, Tree& tree, const PlaneSet& planes, int outputNum);

// A _skybox copy's references: every open leaf that draws sky, whose bounds grow to hold the copy.
int addSkyboxReferences(DrawSurface& ds, Tree& tree, int outputNum);

}  // namespace q3::bspstage
