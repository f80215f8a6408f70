// Brushes pushed down the tree (q3map2 brush.cpp FilterBrushIntoTree_r / SplitBrush): every leaf
// lists the brushes with a fragment in it; a structural opaque brush makes its leaves opaque, and an
// areaportal brush flags the coplanar portals of its leaves.
#pragma once

#include <vector>

#include "bsp_brushes.h"
#include "bsp_tree.h"
#include "plane_set.h"

namespace q3::bspstage {

// A piece of a brush while it is split down the tree: its sides' planes and windings.
struct BrushFragment {
    struct Side {
        int planeNum = -1;
        Winding winding;
    };
    std::vector<Side> sides;
    bool empty() const { return sides.empty(); }
};

BrushFragment fragmentOf(const Brush& brush);
// Cuts the fragment by a map plane into (front, back). A side gets nothing when the brush does not
// reach more than 0.1 past the plane, when the cut would be tiny, or when a piece has volume < 1.
std::pair<BrushFragment, BrushFragment> splitBrushFragment(BrushFragment brush, int planeNum,
                                                           const PlaneSet& planes);
double fragmentVolume(const BrushFragment& brush, const PlaneSet& planes);

// Filters every non-detail brush of `brushes` into the tree; returns the number of leaf references.
int filterStructuralBrushesIntoTree(const std::vector<Brush>& brushes, Tree& tree, const PlaneSet& planes);
// The same for detail brushes (they only add leaf references).
int filterDetailBrushesIntoTree(const std::vector<Brush>& brushes, Tree& tree, const PlaneSet& planes);

}  // namespace q3::bspstage
