#include "visible_hull.h"

namespace q3::bspstage {
namespace {

void clipSideIntoTree(const Winding& w, BrushSide& side, int nodeIndex, const Tree& tree, const PlaneSet& planes) {
    if (w.empty()) return;
    const TreeNode& node = tree.node(nodeIndex);
    if (!node.isLeaf()) {
        // A side on the node's plane goes to the side its own plane faces.
        if (side.planeNum == node.planeNum) return clipSideIntoTree(w, side, node.children[0], tree, planes);
        if (side.planeNum == (node.planeNum ^ 1)) return clipSideIntoTree(w, side, node.children[1], tree, planes);
        // Whole windings go down unclipped; only crossing ones are split (no copies on the way).
        switch (windingOnPlaneSide(w, planes[node.planeNum].plane)) {
        case PlaneSide::Front: return clipSideIntoTree(w, side, node.children[0], tree, planes);
        case PlaneSide::Back: return clipSideIntoTree(w, side, node.children[1], tree, planes);
        case PlaneSide::On:
            // Lies on a plane it does not share: keep it on both sides rather than lose it.
            clipSideIntoTree(w, side, node.children[0], tree, planes);
            clipSideIntoTree(w, side, node.children[1], tree, planes);
            return;
        case PlaneSide::Cross: {
            auto [front, back] = clipWindingStrict(w, planes[node.planeNum].plane, kOnEpsilon);
            clipSideIntoTree(front, side, node.children[0], tree, planes);
            clipSideIntoTree(back, side, node.children[1], tree, planes);
            return;
        }
        }
        return;
    }
    if (!node.opaque) addWindingToConvexHull(w, side.visibleHull, planes[side.planeNum].normal());
}

}  // namespace

void clipSidesIntoTree(std::vector<Brush>& brushes, const Tree& tree, const PlaneSet& planes) {
    for (Brush& b : brushes) {
        for (BrushSide& side : b.sides) {
            if (side.winding.empty()) continue;
            side.visibleHull.clear();
            clipSideIntoTree(side.winding, side, tree.head, tree, planes);
        }
    }
}

}  // namespace q3::bspstage
