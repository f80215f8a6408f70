#include "brush_filter.h"

#include <algorithm>

#include "shader_info.h"

namespace q3::bspstage {
namespace {

// How far a brush must reach past a plane to count as being on that side (q3map2 uses 0.1 where
// it names PLANESIDE_EPSILON).
constexpr double kPlaneSideEpsilon = 0.1;
constexpr double kMinimumVolume = 1.0;

DBounds fragmentBounds(const BrushFragment& b) {
    DBounds bounds;
    for (const auto& s : b.sides) bounds.add(windingBounds(s.winding));
    return bounds;
}

bool boundsValid(const BrushFragment& b) {
    DBounds world;
    world.add(DVec3::splat(-kMaxWorldCoord));
    world.add(DVec3::splat(kMaxWorldCoord));
    const DBounds bounds = fragmentBounds(b);
    return !bounds.empty() && world.surroundsStrictly(bounds);
}

// Which side holds the point farthest from the plane.
bool mostlyOnBack(const BrushFragment& b, const DPlane& plane) {
    double best = 0;
    bool back = false;
    for (const auto& s : b.sides) {
        for (const DVec3& p : s.winding) {
            const double d = plane.distanceTo(p);
            if (d > best) {
                best = d;
                back = false;
            }
            if (-d > best) {
                best = -d;
                back = true;
            }
        }
    }
    return back;
}

struct Filter {
    Tree& tree;
    const PlaneSet& planes;
    const std::vector<Brush>& brushes;

    // An areaportal brush fragment marks the portals of its leaf that lie on its areaportal side.
    void markAreaportalPortals(int leaf, const Brush& brush) {
        auto side = std::find_if(brush.sides.begin(), brush.sides.end(),
                                 [](const BrushSide& s) { return (s.compileFlags & compileflags::AreaPortal) != 0; });
        if (side == brush.sides.end() || side->winding.empty()) return;
        const DVec3 normal = planes[side->planeNum].normal();
        tree.forEachPortal(leaf, [&](int p) {
            Portal& portal = tree.portal(p);
            if (portal.onNode < 0) return;
            const int nodePlane = tree.node(portal.onNode).planeNum;
            if ((nodePlane | 1) != (side->planeNum | 1)) return;
            const Winding w = nodePlane == side->planeNum ? portal.winding : reverseWinding(portal.winding);
            if (coplanarWindingsIntersect(w, side->winding, normal)) portal.compileFlags |= compileflags::AreaPortal;
        });
    }

    int filter(BrushFragment fragment, int brushIndex, int nodeIndex) {
        if (fragment.empty()) return 0;
        TreeNode& node = tree.node(nodeIndex);
        if (node.isLeaf()) {
            node.brushes.push_back(brushIndex);
            const Brush& brush = brushes[size_t(brushIndex)];
            if (!brush.detail) {
                if (brush.opaque)
                    node.opaque = true;
                else if (brush.compileFlags & compileflags::AreaPortal)
                    markAreaportalPortals(nodeIndex, brush);
            }
            return 1;
        }
        const int planeNum = node.planeNum;
        const int front = node.children[0], back = node.children[1];
        auto [f, b] = splitBrushFragment(std::move(fragment), planeNum, planes);
        return filter(std::move(f), brushIndex, front) + filter(std::move(b), brushIndex, back);
    }
};

int filterBrushes(const std::vector<Brush>& brushes, Tree& tree, const PlaneSet& planes, bool detail) {
    Filter filter{tree, planes, brushes};
    int references = 0;
    for (size_t i = 0; i < brushes.size(); ++i)
        if (brushes[i].detail == detail) references += filter.filter(fragmentOf(brushes[i]), int(i), tree.head);
    return references;
}

}  // namespace

BrushFragment fragmentOf(const Brush& brush) {
    BrushFragment f;
    for (const BrushSide& s : brush.sides) f.sides.push_back({s.planeNum, s.winding});
    return f;
}

double fragmentVolume(const BrushFragment& brush, const PlaneSet& planes) {
    auto first = std::find_if(brush.sides.begin(), brush.sides.end(), [](const auto& s) { return !s.winding.empty(); });
    if (first == brush.sides.end()) return 0;
    const DVec3 corner = first->winding[0];
    double volume = 0;
    for (auto it = first + 1; it != brush.sides.end(); ++it)
        if (!it->winding.empty()) volume += -planes[it->planeNum].plane.distanceTo(corner) * windingArea(it->winding);
    return volume / 3;
}

std::pair<BrushFragment, BrushFragment> splitBrushFragment(BrushFragment brush, int planeNum,
                                                           const PlaneSet& planes) {
    const DPlane& plane = planes[planeNum].plane;
    double frontMost = 0, backMost = 0;
    for (const auto& s : brush.sides) {
        for (const DVec3& p : s.winding) {
            const double d = plane.distanceTo(p);
            frontMost = std::max(frontMost, d);
            backMost = std::min(backMost, d);
        }
    }
    if (frontMost < kPlaneSideEpsilon) return {BrushFragment{}, std::move(brush)};
    if (backMost > -kPlaneSideEpsilon) return {std::move(brush), BrushFragment{}};

    Winding mid = baseWindingForPlane(plane);
    for (const auto& s : brush.sides) {
        chopWindingInPlace(mid, planes[s.planeNum ^ 1].plane, 0);
        if (mid.empty()) break;
    }
    if (mid.empty() || windingIsTiny(mid)) {
        if (mostlyOnBack(brush, plane)) return {BrushFragment{}, std::move(brush)};
        return {std::move(brush), BrushFragment{}};
    }

    BrushFragment pieces[2];
    for (const auto& s : brush.sides) {
        if (s.winding.empty()) continue;
        auto [front, back] = clipWindingStrict(s.winding, plane, 0);
        if (!front.empty()) pieces[0].sides.push_back({s.planeNum, std::move(front)});
        if (!back.empty()) pieces[1].sides.push_back({s.planeNum, std::move(back)});
    }
    for (BrushFragment& piece : pieces)
        if (piece.sides.size() < 3 || !boundsValid(piece)) piece.sides.clear();
    if (pieces[0].empty() || pieces[1].empty()) {
        if (!pieces[0].empty()) return {std::move(brush), BrushFragment{}};
        if (!pieces[1].empty()) return {BrushFragment{}, std::move(brush)};
        return {};
    }
    // Each piece is closed by the cut, facing away from it.
    pieces[0].sides.push_back({planeNum ^ 1, mid});
    pieces[1].sides.push_back({planeNum, std::move(mid)});
    for (BrushFragment& piece : pieces)
        if (fragmentVolume(piece, planes) < kMinimumVolume) piece.sides.clear();
    return {std::move(pieces[0]), std::move(pieces[1])};
}

int filterStructuralBrushesIntoTree(const std::vector<Brush>& brushes, Tree& tree, const PlaneSet& planes) {
    return filterBrushes(brushes, tree, planes, false);
}

int filterDetailBrushesIntoTree(const std::vector<Brush>& brushes, Tree& tree, const PlaneSet& planes) {
    return filterBrushes(brushes, tree, planes, true);
}

}  // namespace q3::bspstage
