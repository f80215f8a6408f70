#include "portal_file.h"

#include <cmath>
#include <cstdio>

#include "shader_info.h"
#include "tree_portals.h"

namespace q3::bspstage {
namespace {

constexpr double kIntegerTolerance = 0.001;
// The portal's own plane and the plane vis derives from its first three points may disagree near
// an axis changeover; beyond this the clusters are written the other way round.
constexpr double kSameFacing = 0.99;
constexpr int kHintFlag = 1;
constexpr int kSkyFlag = 2;

void numberLeafs(Tree& tree, int nodeIndex, int cluster, int& next) {
    TreeNode& node = tree.node(nodeIndex);
    if (!node.isLeaf()) {
        node.cluster = -99;
        if (!node.hasStructuralChildren && cluster < 0) cluster = next++;
        const int front = node.children[0], back = node.children[1];
        numberLeafs(tree, front, cluster, next);
        numberLeafs(tree, back, cluster, next);
        return;
    }
    node.area = -1;
    if (node.opaque) {
        node.cluster = -1;
        return;
    }
    node.cluster = cluster < 0 ? next++ : cluster;
}

// Portals that differ in cluster, seen from each open leaf: `passable` picks vis portals or solid
// faces.
template <class F>
void forEachClusterBoundary(const Tree& tree, bool passable, F&& f) {
    tree.forEachLeaf([&](int leaf) {
        if (tree.node(leaf).opaque) return;
        tree.forEachPortal(leaf, [&](int p) {
            const Portal& portal = tree.portal(p);
            if (portalPassable(tree, portal) != passable) return;
            if (tree.node(portal.nodes[0]).cluster == tree.node(portal.nodes[1]).cluster) return;
            f(leaf, portal);
        });
    });
}

void appendNumber(std::string& out, double value) {
    const float v = float(value);
    char text[64];
    if (std::fabs(v - std::rint(v)) < kIntegerTolerance)
        std::snprintf(text, sizeof text, "%li ", std::lrint(v));
    else
        std::snprintf(text, sizeof text, "%f ", double(v));
    out += text;
}

void appendPoint(std::string& out, const DVec3& p) {
    out += '(';
    appendNumber(out, p.x);
    appendNumber(out, p.y);
    appendNumber(out, p.z);
    out += ") ";
}

}  // namespace

ClusterCounts numberClusters(Tree& tree) {
    ClusterCounts counts;
    numberLeafs(tree, tree.head, -1, counts.clusters);
    forEachClusterBoundary(tree, true, [&](int leaf, const Portal& p) {
        if (p.nodes[0] == leaf) ++counts.portals;
    });
    forEachClusterBoundary(tree, false, [&](int, const Portal&) { ++counts.solidFaces; });
    return counts;
}

std::string portalFileText(const Tree& tree, const ClusterCounts& counts) {
    std::string out = "PRT1\n" + std::to_string(counts.clusters) + "\n" + std::to_string(counts.portals) + "\n" +
                      std::to_string(counts.solidFaces) + "\n";
    forEachClusterBoundary(tree, true, [&](int leaf, const Portal& p) {
        if (p.nodes[0] != leaf) return;  // written once, from the front leaf
        const int front = tree.node(p.nodes[0]).cluster, back = tree.node(p.nodes[1]).cluster;
        const bool backwards = dot(p.plane.normal, windingPlane(p.winding).normal) < kSameFacing;
        int flags = 0;
        if (p.compileFlags & compileflags::Hint) flags |= kHintFlag;
        if (p.compileFlags & compileflags::Sky) flags |= kSkyFlag;
        char head[64];
        std::snprintf(head, sizeof head, "%zu %i %i %d ", p.winding.size(), backwards ? back : front,
                      backwards ? front : back, flags);
        out += head;
        for (const DVec3& point : p.winding) appendPoint(out, point);
        out += '\n';
    });
    forEachClusterBoundary(tree, false, [&](int leaf, const Portal& p) {
        const bool fromFront = p.nodes[0] == leaf;
        char head[32];
        std::snprintf(head, sizeof head, "%zu %i ", p.winding.size(), tree.node(leaf).cluster);
        out += head;
        // Seen from the back leaf the polygon is written reversed, so it faces into its cluster.
        if (fromFront)
            for (const DVec3& point : p.winding) appendPoint(out, point);
        else
            for (auto it = p.winding.rbegin(); it != p.winding.rend(); ++it) appendPoint(out, *it);
        out += '\n';
    });
    return out;
}

}  // namespace q3::bspstage
