// What the finished portals of earlier waves of the full vis tell about pairs of clusters, for the
// walks of later waves. A line of sight runs both ways, so:
//  - cluster A sees X once a finished portal of A sees X, or a finished portal of X sees A;
//  - once every portal of X is finished, X sees nothing but what its portals see: a cluster A
//    missing from that row cannot see X either.
// A walk from a portal of A then marks the first kind from the start and never looks for the
// second, and only works on the pairs still open.
#pragma once

#include "portal_bits.h"
#include "vis_graph.h"

#include <vector>

namespace q3::vis {

class ClusterKnowledge {
public:
    // `results`: per portal, the clusters it sees, read once all portals of a cluster are done.
    ClusterKnowledge(const VisGraph& graph, const BitMatrix& results);

    // The cluster whose portal list holds `portal`, or -1 when none or several do (-hint lets
    // a leaf merged away merge again, and its old portal list with it).
    int home(int portal) const { return home_[static_cast<size_t>(portal)]; }

    // Records a finished portal (its row of `results`). Calls in a fixed order give the same
    // knowledge at any thread count.
    void learn(int portal);

    // The clusters `cluster` is known to see.
    const uint64_t* seen(int cluster) const { return seen_.row(static_cast<size_t>(cluster)); }
    // The clusters `cluster` may still see: all but those known hidden from it.
    const uint64_t* possible(int cluster) const { return possible_.row(static_cast<size_t>(cluster)); }

private:
    const VisGraph& graph_;
    const BitMatrix& results_;
    std::vector<std::vector<int>> holders_;  // per portal: the clusters (not merged away) listing it
    std::vector<int> home_;
    BitMatrix seen_;
    BitMatrix possible_;
    std::vector<int> portalsLeft_;  // per cluster: portals not finished yet
};

}  // namespace q3::vis
