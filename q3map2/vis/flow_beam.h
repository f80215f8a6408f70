// The beam of one step of the full vis: every line from the source winding through the pass
// winding stays in front of the separating planes between the two (q3map2's ClipToSeperators
// planes), whatever portals it crosses next. The flow clips the next portals by these planes,
// and drops from the chain's "might see" set the clusters wholly behind one of them: no line of
// the chain can reach those, however deep the chain goes on.
#pragma once

#include "vis_geometry.h"
#include "vis_graph.h"

#include <array>
#include <cmath>
#include <vector>

namespace q3::vis {

struct Beam {
    // Separators of source edges with pass points, then of pass edges with source points
    // (flipped), each with the source behind and the pass in front.
    std::array<Plane, 2 * kMaxSeparators> planes;
    int count = 0;
};

void buildBeam(const Winding& source, const Winding& pass, Beam& beam);

// An axis-aligned box as centre and half extents, for plane tests.
struct Box {
    Vec3 centre;
    Vec3 half;
};

// Wholly behind `plane`, by more than the on-plane epsilon.
inline bool boxBehind(const Plane& plane, const Box& box) {
    const float reach = std::abs(plane.normal.x) * box.half.x + std::abs(plane.normal.y) * box.half.y +
                        std::abs(plane.normal.z) * box.half.z;
    return plane.distanceTo(box.centre) + reach < -kOnEpsilon;
}

// Per cluster: the box around the windings of its portals. A line can only enter the cluster
// through one of them, so a plane with the box behind it shuts the whole cluster out.
std::vector<Box> clusterPortalBounds(const VisGraph& graph);

}  // namespace q3::vis
