// -merge / -mergeportals / -hint (q3map2's MergeLeaves and MergeLeafPortals): fewer, larger
// clusters and portals before the flow, trading vis accuracy for speed. Clusters are merged when
// their union stays convex (every portal and solid face of one has the other's within 0.2 units
// behind its plane); never through hint portals. Coplanar portals between the same two clusters
// that share an edge and stay convex become one.
#pragma once

#include "vis_graph.h"

namespace q3::vis {

// Returns the number of merges. `hintSwitch` is q3map2's -hint: leaves already merged are tried
// again (its "merge all non-hint portals").
int mergeLeaves(VisGraph& graph, bool hintSwitch);

struct PortalMergeCount {
    int portals = 0;
    int hintPortals = 0;  // merges of two hint portals
};
PortalMergeCount mergeLeafPortals(VisGraph& graph);

// The winding of two coplanar windings sharing an edge when their union is convex, else false.
bool mergeWindings(const Winding& a, const Winding& b, Vec3 planeNormal, Winding& merged);

}  // namespace q3::vis
