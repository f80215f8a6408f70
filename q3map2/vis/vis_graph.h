// The portal graph -vis works on: each portal of the .prt becomes two one-way portals, one
// living in each of its clusters and leading into the other, as q3map2's LoadPortals builds them.
#pragma once

#include "portal_file.h"
#include "vis_geometry.h"

#include <vector>

namespace q3::vis {

struct VisPortal {
    // The fields every test reads come first: the winding behind them is most of the size.
    Plane plane;       // normal points into `leaf`
    int leaf = 0;      // the cluster this portal leads into
    int owner = 0;     // the cluster this portal lives in
    Vec3 origin;       // bounding sphere, for quick plane tests
    float radius = 0;
    bool hint = false;
    bool sky = false;
    bool removed = false;  // merged away (-merge, -mergeportals)
    Winding winding;
};

struct VisLeaf {
    std::vector<int> portals;  // indices of the portals living in this cluster
    int merged = -1;           // the leaf this one was merged into (-merge), or -1
};

struct VisGraph {
    int clusterCount = 0;
    std::vector<VisPortal> portals;  // 2 per file portal: 2i in cluster A, 2i+1 in cluster B
    std::vector<VisLeaf> leafs;
    // The solid faces of each cluster (normals out of it), only for -merge's convexity test.
    std::vector<VisPortal> faces;
    std::vector<std::vector<int>> leafFaces;
};

// Portal 2i (in cluster A, into B) takes its hint flag from the file; portal 2i+1 takes it from
// `hintSwitch` (q3map2's -hint) instead, whatever the file says.
VisGraph buildVisGraph(const PortalFile& file, bool hintSwitch);

// The leaf a (possibly merged) leaf ended up in.
int mergedLeaf(const VisGraph& graph, int leaf);

}  // namespace q3::vis
