// Per-cluster sky visibility from the PVS (see sky_visibility.h).
#include "sky_visibility.h"

#include "bsp_tree.h"

namespace q3::light {
namespace {

constexpr uint64_t kUnindexedSky = uint64_t{1} << 32;

uint64_t skyBit(int skyIndex) {
    return skyIndex >= 0 && skyIndex < 32 ? uint64_t{1} << skyIndex : kUnindexedSky;
}

}  // namespace

SkyVisibility::SkyVisibility(const bsp::Bsp& bsp, const BspTree& tree, const std::vector<int>& surfaceSkyIndex) {
    const int numClusters = tree.numClusters();
    if (numClusters <= 0 || bsp.visibility.size() <= 8 || bsp.nodes.empty()) return;

    // Skies in front of which each cluster lies.
    std::vector<uint64_t> ownSkies(static_cast<size_t>(numClusters), 0);
    std::vector<uint8_t> referenced(surfaceSkyIndex.size(), 0);
    for (const bsp::Leaf& leaf : bsp.leafs) {
        for (int i = 0; i < leaf.numLeafSurfaces; ++i) {
            const size_t ls = static_cast<size_t>(leaf.firstLeafSurface + i);
            if (ls >= bsp.leafSurfaces.size()) continue;
            const int s = bsp.leafSurfaces[ls];
            if (s < 0 || static_cast<size_t>(s) >= surfaceSkyIndex.size() || surfaceSkyIndex[s] < -1) continue;
            referenced[static_cast<size_t>(s)] = 1;
            if (leaf.cluster >= 0 && leaf.cluster < numClusters)
                ownSkies[static_cast<size_t>(leaf.cluster)] |= skyBit(surfaceSkyIndex[s]);
        }
    }
    for (size_t s = 0; s < surfaceSkyIndex.size(); ++s)
        if (surfaceSkyIndex[s] >= -1 && !referenced[s]) return;  // a sky outside the world's leafs

    visibleSkies_.assign(static_cast<size_t>(numClusters), 0);
    for (int c = 0; c < numClusters; ++c)
        for (int v = 0; v < numClusters; ++v)
            if (ownSkies[static_cast<size_t>(v)] && tree.clusterVisible(c, v))
                visibleSkies_[static_cast<size_t>(c)] |= ownSkies[static_cast<size_t>(v)];
    enabled_ = true;
}

}  // namespace q3::light
