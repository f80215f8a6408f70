// Visible hulls (q3map2 surface.cpp ClipSidesIntoTree): each brush side's winding is pushed down
// the tree, and the convex hull of the pieces that land in open leaves becomes the side's visible
// hull. The second tree is built from these hulls only, so faces outside the map or buried in
// other brushes no longer split it.
#pragma once

#include <vector>

#include "bsp_brushes.h"
#include "bsp_tree.h"
#include "plane_set.h"

namespace q3::bspstage {

// Sets visibleHull for every side of `brushes` with a winding.
void clipSidesIntoTree(std::vector<Brush>& brushes, const Tree& tree, const PlaneSet& planes);

}  // namespace q3::bspstage
