#include "leaf_merge.h"

#include <cmath>

namespace q3::vis {

namespace {

constexpr float kConvexEpsilon = 0.2f;
constexpr float kEdgeEpsilon = 0.1f;
constexpr float kContinuousEpsilon = 0.005f;

// Some point of one winding lies in front of the other's plane: the union would not be convex.
bool planesConcave(const VisPortal& a, const VisPortal& b) {
    for (Vec3 p : a.winding.view())
        if (b.plane.distanceTo(p) > kConvexEpsilon) return true;
    for (Vec3 p : b.winding.view())
        if (a.plane.distanceTo(p) > kConvexEpsilon) return true;
    return false;
}

// The portals and solid faces of a leaf, as the convexity test sees them (removed ones included,
// as in q3map2).
template <class Visit>
bool forEachBoundary(const VisGraph& graph, int leaf, Visit visit) {
    for (int f : graph.leafFaces[static_cast<size_t>(leaf)])
        if (!visit(graph.faces[static_cast<size_t>(f)])) return false;
    for (int p : graph.leafs[static_cast<size_t>(leaf)].portals)
        if (!visit(graph.portals[static_cast<size_t>(p)])) return false;
    return true;
}

bool tryMergeLeaves(VisGraph& graph, int l1, int l2) {
    const bool convex = forEachBoundary(graph, l1, [&](const VisPortal& p1) {
        if (p1.leaf == l2) return true;
        return forEachBoundary(graph, l2, [&](const VisPortal& p2) { return p2.leaf == l1 || !planesConcave(p1, p2); });
    });
    if (!convex) return false;
    // Portals between the two disappear; the rest of l1's move to l2 (solid faces likewise).
    std::vector<int> joined;
    for (int p : graph.leafs[static_cast<size_t>(l1)].portals) {
        if (graph.portals[static_cast<size_t>(p)].leaf == l2)
            graph.portals[static_cast<size_t>(p)].removed = true;
        else
            joined.push_back(p);
    }
    for (int p : graph.leafs[static_cast<size_t>(l2)].portals) {
        if (graph.portals[static_cast<size_t>(p)].leaf == l1)
            graph.portals[static_cast<size_t>(p)].removed = true;
        else
            joined.push_back(p);
    }
    graph.leafs[static_cast<size_t>(l2)].portals = std::move(joined);
    std::vector<int>& faces2 = graph.leafFaces[static_cast<size_t>(l2)];
    const std::vector<int>& faces1 = graph.leafFaces[static_cast<size_t>(l1)];
    std::vector<int> faces(faces1.begin(), faces1.end());
    faces.insert(faces.end(), faces2.begin(), faces2.end());
    faces2 = std::move(faces);
    graph.leafs[static_cast<size_t>(l1)].merged = l2;
    return true;
}

void updatePortalLeafs(VisGraph& graph) {
    for (VisPortal& p : graph.portals)
        if (!p.removed) p.leaf = mergedLeaf(graph, p.leaf);
}

bool near(Vec3 a, Vec3 b) {
    return std::fabs(a.x - b.x) <= kEdgeEpsilon && std::fabs(a.y - b.y) <= kEdgeEpsilon &&
           std::fabs(a.z - b.z) <= kEdgeEpsilon;
}

Vec3 normalized(Vec3 v) {
    const float len = length(v);
    return len == 0 ? v : v / len;
}

}  // namespace

bool mergeWindings(const Winding& a, const Winding& b, Vec3 planeNormal, Winding& merged) {
    const int na = a.count, nb = b.count;
    // A shared edge, walked in opposite directions by the two windings.
    int i = 0, j = 0;
    bool found = false;
    for (i = 0; i < na && !found; ++i)
        for (j = 0; j < nb; ++j)
            if (near(a.points[i], b.points[(j + 1) % nb]) && near(a.points[(i + 1) % na], b.points[j])) {
                found = true;
                break;
            }
    if (!found) return false;
    --i;  // undo the outer loop's step past the match
    const Vec3 p1 = a.points[i], p2 = a.points[(i + 1) % na];
    // Convex at both ends of the shared edge; a point exactly in line is dropped.
    Vec3 edgeNormal = normalized(cross(planeNormal, p1 - a.points[(i + na - 1) % na]));
    float d = dot(b.points[(j + 2) % nb] - p1, edgeNormal);
    if (d > kContinuousEpsilon) return false;
    const bool keepFirst = d < -kContinuousEpsilon;
    edgeNormal = normalized(cross(planeNormal, a.points[(i + 2) % na] - p2));
    d = dot(b.points[(j + nb - 1) % nb] - p2, edgeNormal);
    if (d > kContinuousEpsilon) return false;
    const bool keepSecond = d < -kContinuousEpsilon;
    if (na + nb - 2 > kMaxWindingPoints) return false;

    merged.count = 0;
    for (int k = (i + 1) % na; k != i; k = (k + 1) % na) {
        if (k == (i + 1) % na && !keepSecond) continue;
        merged.points[merged.count++] = a.points[k];
    }
    for (int l = (j + 1) % nb; l != j; l = (l + 1) % nb) {
        if (l == (j + 1) % nb && !keepFirst) continue;
        merged.points[merged.count++] = b.points[l];
    }
    return true;
}

int mergeLeaves(VisGraph& graph, bool hintSwitch) {
    int total = 0;
    int merges = 0;
    do {
        merges = 0;
        for (int i = 0; i < graph.clusterCount; ++i) {
            if (graph.leafs[static_cast<size_t>(i)].merged >= 0 && !hintSwitch) continue;
            const std::vector<int> portals = graph.leafs[static_cast<size_t>(i)].portals;
            for (int pnum : portals) {
                const VisPortal& p = graph.portals[static_cast<size_t>(pnum)];
                // Never through hint portals; a leaf never merges with itself.
                if (p.removed || p.hint || p.leaf == i) continue;
                if (tryMergeLeaves(graph, i, p.leaf)) {
                    updatePortalLeafs(graph);
                    ++merges;
                    break;
                }
            }
        }
        total += merges;
    } while (merges);
    return total;
}

PortalMergeCount mergeLeafPortals(VisGraph& graph) {
    PortalMergeCount count;
    for (int i = 0; i < graph.clusterCount; ++i) {
        const VisLeaf& leaf = graph.leafs[static_cast<size_t>(i)];
        if (leaf.merged >= 0) continue;
        bool mergedOne = false;
        for (size_t j = 0; j < leaf.portals.size() && !mergedOne; ++j) {
            VisPortal& p1 = graph.portals[static_cast<size_t>(leaf.portals[j])];
            if (p1.removed) continue;
            for (size_t k = j + 1; k < leaf.portals.size(); ++k) {
                VisPortal& p2 = graph.portals[static_cast<size_t>(leaf.portals[k])];
                if (p2.removed || p1.leaf != p2.leaf) continue;
                Winding merged;
                if (!mergeWindings(p1.winding, p2.winding, p1.plane.normal, merged)) continue;
                p1.winding = merged;
                if (p1.hint && p2.hint) ++count.hintPortals;
                p1.hint = p1.hint || p2.hint;
                boundingSphere(p1.winding, p1.origin, p1.radius);
                p2.removed = true;
                ++count.portals;
                mergedOne = true;
                break;
            }
        }
        if (mergedOne) --i;  // the same leaf again, until nothing merges
    }
    return count;
}

}  // namespace q3::vis
