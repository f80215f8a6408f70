#include "flow_beam.h"

#include <algorithm>
#include <limits>

namespace q3::vis {

void buildBeam(const Winding& source, const Winding& pass, Beam& beam) {
    beam.count = 0;
    for (int edge = 0; edge < source.count; ++edge)
        if (findSeparator(source, pass, edge, false, beam.planes[static_cast<size_t>(beam.count)])) ++beam.count;
    for (int edge = 0; edge < pass.count; ++edge)
        if (findSeparator(pass, source, edge, true, beam.planes[static_cast<size_t>(beam.count)])) ++beam.count;
}

std::vector<Box> clusterPortalBounds(const VisGraph& graph) {
    std::vector<Box> boxes(graph.leafs.size());
    for (size_t l = 0; l < graph.leafs.size(); ++l) {
        constexpr float kHuge = std::numeric_limits<float>::max();
        Vec3 lo = Vec3::splat(kHuge), hi = Vec3::splat(-kHuge);
        for (int pnum : graph.leafs[l].portals)
            for (Vec3 p : graph.portals[static_cast<size_t>(pnum)].winding.view())
                for (int j = 0; j < 3; ++j) {
                    lo[j] = std::min(lo[j], p[j]);
                    hi[j] = std::max(hi[j], p[j]);
                }
        // A cluster without portals is never reached; any box will do.
        if (lo.x > hi.x) lo = hi = Vec3{};
        boxes[l] = {(lo + hi) * 0.5f, (hi - lo) * 0.5f};
    }
    return boxes;
}

}  // namespace q3::vis
