// Portals: the polygons that join neighbouring leaves of the tree (q3map2 portals.cpp
// MakeTreePortals), plus the six outside portals that join the tree to its outside node.
#pragma once

#include "bsp_tree.h"
#include "plane_set.h"

namespace q3::bspstage {

struct PortalCounts {
    int tinyPortals = 0;  // discarded: fewer than three edges longer than 0.2
};

// Creates the outside node and every portal; node bounds become the extent of their portals.
PortalCounts makeTreePortals(Tree& tree, const PlaneSet& planes);

// True when something can move through the portal: both leaves open, not the outside box, and not
// an antiportal.
bool portalPassable(const Tree& tree, const Portal& portal);

}  // namespace q3::bspstage
