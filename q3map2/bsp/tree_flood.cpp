#include "tree_flood.h"

#include <cstdio>

#include "log.h"
#include "script.h"
#include "shader_info.h"
#include "tree_portals.h"

namespace q3::bspstage {
namespace {

int leafAt(const Tree& tree, const PlaneSet& planes, const DVec3& point) {
    int n = tree.head;
    while (!tree.node(n).isLeaf()) {
        const DPlane& plane = planes[tree.node(n).planeNum].plane;
        n = tree.node(n).children[plane.distanceTo(point) >= 0 ? 0 : 1];
    }
    return n;
}

// Breadth-first, remembering each leaf's step count; leaves reached earlier by a longer path are
// revisited so that the leak line is as short as possible. A _skybox entity's flood marks every
// node it reaches, solid ones and ones it does not go on from included, as q3map2's does.
int floodFrom(Tree& tree, int start, bool skybox) {
    int flooded = 0;
    int step = 1;
    std::vector<int> current{start}, next;
    while (!current.empty()) {
        for (int n : current) {
            TreeNode& node = tree.node(n);
            if (skybox) node.skybox = true;
            if (node.opaque || (node.occupied && node.occupied <= step)) continue;
            if (!node.occupied) ++flooded;
            node.occupied = step;
            tree.forEachPortal(n, [&](int p) { next.push_back(tree.portal(p).otherNode(n)); });
        }
        current.swap(next);
        next.clear();
        ++step;
    }
    return flooded;
}

std::string formatPoint(const DVec3& p) {
    char line[128];
    std::snprintf(line, sizeof line, "%f %f %f\n", float(p.x), float(p.y), float(p.z));
    return line;
}

}  // namespace

FloodResult floodEntities(Tree& tree, const std::vector<BspEntity>& entities, const PlaneSet& planes, Log& log,
                          FloodCounts* counts) {
    tree.node(tree.outside).occupied = 0;
    bool inside = false;
    int flooded = 0;
    for (size_t i = 1; i < entities.size(); ++i) {
        const BspEntity& e = entities[i];
        if (!e.isPointEntity()) continue;  // brush entities may move into the map: never flood from them
        DVec3 origin = roundToFloat(e.origin);
        origin.z += 1;  // off the floor
        const int leaf = leafAt(tree, planes, origin);
        if (tree.node(leaf).opaque) {
            log.warning("Entity " + std::to_string(e.mapEntityNum) + " (" + e.classname + "): Entity in solid");
            continue;
        }
        const bool skybox = equalsNoCase(e.classname, "_skybox");
        tree.node(leaf).occupant = int(i);
        tree.node(leaf).skybox = skybox;  // any entity's own leaf takes its entity's say
        flooded += floodFrom(tree, leaf, skybox);
        inside = true;
    }
    if (counts) counts->floodedLeafs = flooded;
    if (!inside) return FloodResult::Empty;
    if (tree.node(tree.outside).occupied) return FloodResult::Leaked;
    return FloodResult::Good;
}

FillCounts fillOutside(Tree& tree) {
    FillCounts counts;
    tree.forEachLeaf([&](int n) {
        TreeNode& node = tree.node(n);
        if (node.occupied) {
            ++counts.inside;
        } else if (node.opaque) {
            ++counts.solid;
        } else {
            node.opaque = true;
            ++counts.filled;
        }
    });
    return counts;
}

std::string leakLineText(const Tree& tree, const std::vector<BspEntity>& entities, int* leakingEntity) {
    if (!tree.node(tree.outside).occupied) return {};
    std::string text;
    int n = tree.outside;
    while (tree.node(n).occupied > 1) {
        int best = tree.node(n).occupied, bestPortal = -1, bestNode = -1;
        tree.forEachPortal(n, [&](int p) {
            const int other = tree.portal(p).otherNode(n);
            const int occupied = tree.node(other).occupied;
            if (occupied && occupied < best) {
                best = occupied;
                bestPortal = p;
                bestNode = other;
            }
        });
        if (bestPortal < 0) break;  // cannot happen for a flooded leaf; guards against a loop
        n = bestNode;
        text += formatPoint(windingCenter(tree.portal(bestPortal).winding));
    }
    const int occupant = tree.node(n).occupant;
    if (occupant >= 0) text += formatPoint(entities[size_t(occupant)].origin);
    if (leakingEntity) *leakingEntity = occupant;
    return text;
}

int floodAreas(Tree& tree) {
    int areas = 0;
    int skyboxArea = -1;  // the last area numbered with a _skybox leaf in it
    tree.forEachLeaf([&](int start) {
        if (tree.node(start).opaque || tree.node(start).area != -1) return;
        std::vector<int> stack{start};
        while (!stack.empty()) {
            const int n = stack.back();
            stack.pop_back();
            TreeNode& node = tree.node(n);
            if (node.area != -1 || node.cluster == -1) continue;
            node.area = areas;
            if (node.skybox) skyboxArea = areas;
            tree.forEachPortal(n, [&](int p) {
                const Portal& portal = tree.portal(p);
                if (portal.compileFlags & compileflags::AreaPortal) return;  // areaportals separate areas
                if (!portalPassable(tree, portal)) return;
                stack.push_back(portal.otherNode(n));
            });
        }
        ++areas;
    });
    if (skyboxArea >= 0)
        tree.forEachLeaf([&](int n) {
            TreeNode& node = tree.node(n);
            if (!node.opaque && node.area == skyboxArea) node.skybox = true;
        });
    return areas;
}

}  // namespace q3::bspstage
