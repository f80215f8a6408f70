// Which skies each PVS cluster can possibly see. A sun ray that reaches a sky surface passes in
// a straight line from the sample's cluster to the cluster in front of that surface, so the
// surface's cluster is in the sample's PVS; suns whose sky is in no visible cluster are culled
// before any ray is traced.
#pragma once

#include <cstdint>
#include <vector>

#include "bspfile.h"

namespace q3::light {

class BspTree;

class SkyVisibility {
public:
    // Nothing culled (no tree, not vised, or a sky surface no leaf references, e.g. on a brush entity).
    SkyVisibility() = default;
    // `surfaceSkyIndex[s]` per BSP surface: -2 = not a sky, -1 = sky without an index, >= 0 its index.
    SkyVisibility(const bsp::Bsp& bsp, const BspTree& tree, const std::vector<int>& surfaceSkyIndex);

    // Whether a sun lighting through sky `skyIndex` (-1 = any sky) may reach a sample in `cluster`
    // (-1 = unknown: always true).
    bool maySeeSky(int cluster, int skyIndex) const {
        if (!enabled_ || cluster < 0 || static_cast<size_t>(cluster) >= visibleSkies_.size()) return true;
        const uint64_t mask = visibleSkies_[static_cast<size_t>(cluster)];
        return skyIndex < 0 || skyIndex >= 32 ? mask != 0 : (mask >> skyIndex & 1u) != 0;
    }
    bool enabled() const { return enabled_; }

private:
    bool enabled_ = false;
    std::vector<uint64_t> visibleSkies_;  // per cluster: bit k = sky index k, bit 32 = a sky without index
};

}  // namespace q3::light
