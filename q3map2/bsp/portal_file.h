// Clusters and the PRT1 portal file -vis reads (q3map2 prtfile.cpp).
#pragma once

#include <string>

#include "bsp_tree.h"

namespace q3::bspstage {

struct ClusterCounts {
    int clusters = 0;    // "visclusters"
    int portals = 0;     // passable portals between different clusters ("visportals")
    int solidFaces = 0;  // non-passable portal sides of open leaves between different clusters
};

// Numbers the clusters depth-first (front child first): a subtree without structural splits is
// one cluster, otherwise every open leaf is its own cluster; opaque leaves get -1. Then counts
// what the portal file will hold.
ClusterCounts numberClusters(Tree& tree);

// The PRT1 text, byte for byte as q3map2 writes it: "PRT1", cluster, portal and solid face counts,
// then one line per portal ("<points> <clusterA> <clusterB> <flags> (x y z ) ..."), then one line
// per solid face ("<points> <cluster> (x y z ) ..."). Numbers within 0.001 of an integer are
// written as integers, others with %f.
std::string portalFileText(const Tree& tree, const ClusterCounts& counts);

}  // namespace q3::bspstage
