// From portal visibility to the BSP's visibility lump (q3map2's ClusterMerge): the row of a
// cluster holds the cluster itself, the clusters its portals lead into, and the clusters every
// portal seen through them leads into. Leaves merged by -merge see what their merged leaf sees.
// The passes hand over, per portal, the set of clusters it sees (its own destination included).
#pragma once

#include "portal_bits.h"
#include "vis_graph.h"

#include <cstdint>
#include <span>
#include <vector>

namespace q3::vis {

// Bytes per cluster row as q3map2 lays it out: a multiple of 8.
inline int32_t visRowBytes(int clusterCount) { return ((clusterCount + 63) & ~63) >> 3; }

// Per portal: the cluster it leads into and those of every portal its row of `portalBits` holds.
BitMatrix portalClusterSets(const VisGraph& graph, const BitMatrix& portalBits);

// int32 clusterCount, int32 bytesPerCluster, then the uncompressed rows (bit j of row i at byte
// i * bytesPerCluster + j / 8, bit j % 8). `clusterSets`: per portal, the clusters it sees.
std::vector<uint8_t> buildVisibilityLump(const VisGraph& graph, const BitMatrix& clusterSets);

struct VisSummary {
    int clusters = 0;
    double averageVisible = 0;  // clusters seen per cluster, itself included
    int minVisible = 0, maxVisible = 0;
    std::vector<int> histogram;  // histogram[v] = clusters that see exactly v clusters
};

// Reads back a lump in the layout above; throws std::runtime_error when it does not hold one.
VisSummary summarizeVisibility(std::span<const uint8_t> lump);

}  // namespace q3::vis
