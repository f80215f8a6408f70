// The world's BSP tree while -bsp builds it: nodes split by map planes, leaves, and the portals
// between leaves (q3map2 node_t / portal_t / tree_t), all addressed by index.
#pragma once

#include <cstdint>
#include <vector>

#include "dvec3.h"
#include "winding.h"

namespace q3::bspstage {

inline constexpr int kLeafPlane = -1;  // planeNum of a leaf

struct TreeNode {
    int planeNum = kLeafPlane;  // always the even plane of a pair for decision nodes
    int parent = -1;
    int children[2] = {-1, -1};  // front, back
    DBounds bounds;              // split volume while building; the portals' extent afterwards
    uint32_t compileFlags = 0;   // of the face whose plane split here (hint, antiportal, ...)
    bool hasStructuralChildren = false;
    bool opaque = false;         // filled by a structural opaque brush, or outside the map
    int occupied = 0;            // flood step from the nearest entity; 0 = never reached
    int occupant = -1;           // entity whose flood started in this leaf
    bool skybox = false;         // reached from a _skybox entity, or in its area: its surfaces get sky copies
    bool sky = false;            // draws a sky surface: sky copies of the _skybox room are drawn here
    int cluster = -1;
    int area = -1;
    int firstPortal = -1;        // head of this node's portal list
    int tinyPortals = 0;
    std::vector<int> brushes;    // brushes (entity list indices) with a fragment in this leaf
    std::vector<int> drawSurfaces;  // BSP surfaces drawn in this leaf, in the order they were added

    bool isLeaf() const { return planeNum == kLeafPlane; }
};

struct Portal {
    DPlane plane;
    int onNode = -1;          // node whose plane made it; -1 for the six outside portals
    int nodes[2] = {-1, -1};  // front and back node
    int next[2] = {-1, -1};   // next portal in the list of nodes[0] / nodes[1]
    Winding winding;
    uint32_t compileFlags = 0;

    int sideOf(int node) const { return nodes[0] == node ? 0 : 1; }
    int otherNode(int node) const { return nodes[0] == node ? nodes[1] : nodes[0]; }
    int nextOf(int node) const { return next[sideOf(node)]; }
};

struct Tree {
    std::vector<TreeNode> nodes;
    std::vector<Portal> portals;  // includes portals no longer linked to any node
    int head = -1;
    int outside = -1;  // the node standing for everything outside the padded tree bounds
    DBounds bounds;    // of the faces the tree was built from

    TreeNode& node(int i) { return nodes[size_t(i)]; }
    const TreeNode& node(int i) const { return nodes[size_t(i)]; }
    Portal& portal(int i) { return portals[size_t(i)]; }
    const Portal& portal(int i) const { return portals[size_t(i)]; }

    // Calls f(portalIndex) for each portal of `node`, in list order.
    template <class F>
    void forEachPortal(int nodeIndex, F&& f) const {
        for (int p = node(nodeIndex).firstPortal; p != -1;) {
            const int next = portal(p).nextOf(nodeIndex);
            f(p);
            p = next;
        }
    }
    // Leaves in depth-first order, front child first.
    template <class F>
    void forEachLeaf(F&& f) const {
        std::vector<int> stack{head};
        while (!stack.empty()) {
            const int n = stack.back();
            stack.pop_back();
            if (node(n).isLeaf()) {
                f(n);
                continue;
            }
            stack.push_back(node(n).children[1]);
            stack.push_back(node(n).children[0]);
        }
    }
    int leafCount() const;
};

}  // namespace q3::bspstage
