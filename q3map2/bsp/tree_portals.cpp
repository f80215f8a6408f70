#include "tree_portals.h"

#include <stdexcept>

#include "log.h"
#include "shader_info.h"

namespace q3::bspstage {
namespace {

// Padding around the tree bounds so that no leaf has zero volume.
constexpr double kSideSpace = 8;
// Epsilons for clipping a node's plane by its ancestors and for splitting portals.
constexpr double kBaseWindingEpsilon = 0.001;
constexpr double kSplitWindingEpsilon = 0.001;

struct PortalBuilder {
    Tree& tree;
    const PlaneSet& planes;
    PortalCounts counts;

    void addPortalToNodes(int p, int front, int back) {
        Portal& portal = tree.portal(p);
        if (portal.nodes[0] != -1 || portal.nodes[1] != -1) throw std::logic_error("portal already linked");
        portal.nodes[0] = front;
        portal.next[0] = tree.node(front).firstPortal;
        tree.node(front).firstPortal = p;
        portal.nodes[1] = back;
        portal.next[1] = tree.node(back).firstPortal;
        tree.node(back).firstPortal = p;
    }

    void removePortalFromNode(int p, int nodeIndex) {
        int previous = -1, previousSide = 0;
        for (int t = tree.node(nodeIndex).firstPortal; t != p;) {
            if (t == -1) throw std::logic_error("portal not in leaf");
            previousSide = tree.portal(t).sideOf(nodeIndex);
            previous = t;
            t = tree.portal(t).next[previousSide];
        }
        Portal& portal = tree.portal(p);
        const int side = portal.sideOf(nodeIndex);
        (previous == -1 ? tree.node(nodeIndex).firstPortal : tree.portal(previous).next[previousSide]) = portal.next[side];
        portal.nodes[side] = -1;
        portal.next[side] = -1;
    }

    int newPortal(Portal p) {
        tree.portals.push_back(std::move(p));
        return int(tree.portals.size()) - 1;
    }

    void makeHeadnodePortals() {
        DBounds bounds = tree.bounds;
        bounds.mins -= DVec3::splat(kSideSpace);
        bounds.maxs += DVec3::splat(kSideSpace);
        if (bounds.empty()) throw CompileError("Backwards tree volume");
        TreeNode outside;
        outside.cluster = 0;  // q3map2's outside node is zero-initialised; cluster tests compare with it
        tree.nodes.push_back(outside);
        tree.outside = int(tree.nodes.size()) - 1;
        int sides[6];
        for (int i = 0; i < 3; ++i) {
            for (int j = 0; j < 2; ++j) {
                Portal p;
                p.plane = j ? DPlane{DVec3::axis(i, -1), -bounds.maxs[i]} : DPlane{DVec3::axis(i), bounds.mins[i]};
                p.winding = baseWindingForPlane(p.plane);
                sides[j * 3 + i] = newPortal(std::move(p));
                addPortalToNodes(sides[j * 3 + i], tree.head, tree.outside);
            }
        }
        for (int i = 0; i < 6; ++i)
            for (int j = 0; j < 6; ++j)
                if (j != i) chopWindingInPlace(tree.portal(sides[i]).winding, tree.portal(sides[j]).plane, kOnEpsilon);
    }

    Winding baseWindingForNode(int nodeIndex) const {
        Winding w = baseWindingForPlane(planes[tree.node(nodeIndex).planeNum].plane);
        for (int child = nodeIndex, n = tree.node(nodeIndex).parent; n != -1 && !w.empty();) {
            const DPlane& plane = planes[tree.node(n).planeNum].plane;
            chopWindingInPlace(w, tree.node(n).children[0] == child ? plane : plane.flipped(), kBaseWindingEpsilon);
            child = n;
            n = tree.node(n).parent;
        }
        return w;
    }

    void makeNodePortal(int nodeIndex) {
        Winding w = baseWindingForNode(nodeIndex);
        for (int p = tree.node(nodeIndex).firstPortal; p != -1 && !w.empty();) {
            const Portal& portal = tree.portal(p);
            const int side = portal.sideOf(nodeIndex);
            chopWindingInPlace(w, side == 0 ? portal.plane : portal.plane.flipped(), kClipEpsilon);
            p = portal.next[side];
        }
        if (w.empty()) return;
        if (windingIsTiny(w)) {
            ++counts.tinyPortals;
            return;
        }
        const TreeNode& node = tree.node(nodeIndex);
        Portal p;
        p.plane = planes[node.planeNum].plane;
        p.onNode = nodeIndex;
        p.winding = std::move(w);
        p.compileFlags = node.compileFlags;
        const int front = node.children[0], back = node.children[1];
        addPortalToNodes(newPortal(std::move(p)), front, back);
    }

    // A piece of a split portal too small to keep is dropped; both leaves remember it.
    bool dropIfTiny(Winding& w, int child, int other) {
        if (w.empty() || !windingIsTiny(w)) return false;
        ++tree.node(child).tinyPortals;
        ++tree.node(other).tinyPortals;
        ++counts.tinyPortals;
        w.clear();
        return true;
    }

    void splitNodePortals(int nodeIndex) {
        const DPlane plane = planes[tree.node(nodeIndex).planeNum].plane;
        const int front = tree.node(nodeIndex).children[0], back = tree.node(nodeIndex).children[1];
        for (int p = tree.node(nodeIndex).firstPortal; p != -1;) {
            const int side = tree.portal(p).sideOf(nodeIndex);
            const int next = tree.portal(p).next[side];
            const int other = tree.portal(p).nodes[side ^ 1];
            removePortalFromNode(p, tree.portal(p).nodes[0]);
            removePortalFromNode(p, tree.portal(p).nodes[1]);

            auto [frontWinding, backWinding] = clipWinding(tree.portal(p).winding, plane, kSplitWindingEpsilon);
            dropIfTiny(frontWinding, front, other);
            dropIfTiny(backWinding, back, other);
            if (frontWinding.empty() && backWinding.empty()) {
                p = next;
                continue;
            }
            if (frontWinding.empty() || backWinding.empty()) {
                const int child = frontWinding.empty() ? back : front;
                if (side == 0)
                    addPortalToNodes(p, child, other);
                else
                    addPortalToNodes(p, other, child);
                p = next;
                continue;
            }
            Portal copy = tree.portal(p);
            copy.nodes[0] = copy.nodes[1] = copy.next[0] = copy.next[1] = -1;
            copy.winding = std::move(backWinding);
            tree.portal(p).winding = std::move(frontWinding);
            const int split = newPortal(std::move(copy));
            if (side == 0) {
                addPortalToNodes(p, front, other);
                addPortalToNodes(split, back, other);
            } else {
                addPortalToNodes(p, other, front);
                addPortalToNodes(split, other, back);
            }
            p = next;
        }
        tree.node(nodeIndex).firstPortal = -1;
    }

    void calcNodeBounds(int nodeIndex) {
        DBounds b;
        tree.forEachPortal(nodeIndex, [&](int p) { b.add(windingBounds(tree.portal(p).winding)); });
        tree.node(nodeIndex).bounds = b;
    }

    void makePortals(int nodeIndex) {
        calcNodeBounds(nodeIndex);
        if (tree.node(nodeIndex).isLeaf()) return;
        makeNodePortal(nodeIndex);
        splitNodePortals(nodeIndex);
        makePortals(tree.node(nodeIndex).children[0]);
        makePortals(tree.node(nodeIndex).children[1]);
    }
};

}  // namespace

PortalCounts makeTreePortals(Tree& tree, const PlaneSet& planes) {
    PortalBuilder builder{tree, planes, {}};
    builder.makeHeadnodePortals();
    builder.makePortals(tree.head);
    return builder.counts;
}

bool portalPassable(const Tree& tree, const Portal& portal) {
    if (portal.onNode < 0) return false;
    if (portal.compileFlags & compileflags::AntiPortal) return false;
    return !tree.node(portal.nodes[0]).opaque && !tree.node(portal.nodes[1]).opaque;
}

}  // namespace q3::bspstage
