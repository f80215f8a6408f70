#include "vis_graph.h"

#include <algorithm>

namespace q3::vis {

namespace {

Winding toWinding(const std::vector<Vec3>& points) {
    Winding w;
    w.count = static_cast<int>(points.size());
    std::copy(points.begin(), points.end(), w.points.begin());
    return w;
}

// The plane of the first three points; a file whose first three points are collinear still
// gets a usable plane from the whole winding (Newell's normal).
Plane windingPlane(const Winding& w) {
    Plane plane;
    if (planeFromPoints(plane, w.points[0], w.points[1], w.points[2])) return plane;
    Vec3 normal;
    for (int i = 0; i < w.count; ++i) {
        const Vec3 a = w.points[i], b = w.points[(i + 1) % w.count];
        normal += Vec3{(a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y)};
    }
    // Newell's normal follows the winding's turn, the opposite of planeFromPoints' convention.
    normal = -normal;
    const float len = length(normal);
    if (len == 0) return {{0, 0, 1}, w.points[0].z};
    normal = normal / len;
    return {normal, dot(w.points[0], normal)};
}

void setSphere(VisPortal& p) { boundingSphere(p.winding, p.origin, p.radius); }

}  // namespace

VisGraph buildVisGraph(const PortalFile& file, bool hintSwitch) {
    VisGraph graph;
    graph.clusterCount = file.clusterCount;
    graph.leafs.resize(static_cast<size_t>(file.clusterCount));
    graph.portals.resize(file.portals.size() * 2);
    for (size_t i = 0; i < file.portals.size(); ++i) {
        const FilePortal& fp = file.portals[i];
        VisPortal& forward = graph.portals[2 * i];
        forward.winding = toWinding(fp.points);
        const Plane plane = windingPlane(forward.winding);
        forward.plane = plane.flipped();
        forward.leaf = fp.clusters[1];
        forward.owner = fp.clusters[0];
        forward.hint = (fp.flags & kPortalFlagHint) != 0;
        forward.sky = (fp.flags & kPortalFlagSky) != 0;
        setSphere(forward);
        graph.leafs[static_cast<size_t>(fp.clusters[0])].portals.push_back(static_cast<int>(2 * i));

        VisPortal& backward = graph.portals[2 * i + 1];
        backward.winding.count = forward.winding.count;
        std::reverse_copy(forward.winding.points.begin(), forward.winding.points.begin() + forward.winding.count,
                          backward.winding.points.begin());
        backward.plane = plane;
        backward.leaf = fp.clusters[0];
        backward.owner = fp.clusters[1];
        backward.hint = hintSwitch;  // q3map2 ignores the file's flag for this direction
        backward.sky = false;        // ... and never marks it sky
        setSphere(backward);
        graph.leafs[static_cast<size_t>(fp.clusters[1])].portals.push_back(static_cast<int>(2 * i + 1));
    }
    graph.leafFaces.resize(static_cast<size_t>(file.clusterCount));
    graph.faces.resize(file.faces.size());
    for (size_t i = 0; i < file.faces.size(); ++i) {
        VisPortal& face = graph.faces[i];
        face.winding = toWinding(file.faces[i].points);
        face.plane = windingPlane(face.winding).flipped();  // normal out of the cluster
        face.leaf = -1;
        face.owner = file.faces[i].cluster;
        setSphere(face);
        graph.leafFaces[static_cast<size_t>(face.owner)].push_back(static_cast<int>(i));
    }
    return graph;
}

int mergedLeaf(const VisGraph& graph, int leaf) {
    // Merges only ever point at a leaf that is not merged itself, so the chain is short; the
    // bound only guards against a graph edited by hand.
    for (int steps = 0; graph.leafs[static_cast<size_t>(leaf)].merged >= 0 && steps <= graph.clusterCount; ++steps)
        leaf = graph.leafs[static_cast<size_t>(leaf)].merged;
    return leaf;
}

}  // namespace q3::vis
