#include "segment_clearance.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace q3::vis::test {

namespace {
constexpr int32_t kContentsSolid = 1;
}

SolidWorld::SolidWorld(const bsp::Bsp& bsp) : bsp_(bsp) {
    if (bsp.models.empty() || bsp.nodes.empty()) throw std::runtime_error("BSP without a world model or nodes");
    const bsp::Model& world = bsp.models[0];
    mins = Vec3::fromArray(world.mins);
    maxs = Vec3::fromArray(world.maxs);
    for (int b = world.firstBrush; b < world.firstBrush + world.numBrushes; ++b) {
        const bsp::Brush& brush = bsp.brushes[static_cast<size_t>(b)];
        if (!(bsp.shaders[static_cast<size_t>(brush.shaderNum)].contentFlags & kContentsSolid)) continue;
        SolidBrush solid;
        for (int s = brush.firstSide; s < brush.firstSide + brush.numSides; ++s) {
            const bsp::Plane& plane = bsp.planes[static_cast<size_t>(bsp.brushSides[static_cast<size_t>(s)].planeNum)];
            solid.sides.push_back({Vec3::fromArray(plane.normal), plane.dist});
        }
        brushes_.push_back(std::move(solid));
    }
}

int SolidWorld::clusterAt(Vec3 p) const {
    int node = 0;
    while (node >= 0) {
        const bsp::Node& n = bsp_.nodes[static_cast<size_t>(node)];
        const bsp::Plane& plane = bsp_.planes[static_cast<size_t>(n.planeNum)];
        node = n.children[dot(Vec3::fromArray(plane.normal), p) - plane.dist >= 0 ? 0 : 1];
    }
    return bsp_.leafs[static_cast<size_t>(-(node + 1))].cluster;
}

bool SolidWorld::segmentClear(Vec3 a, Vec3 b, float margin) const {
    for (const SolidBrush& brush : brushes_) {
        // Clip the segment to the brush grown by `margin`: it hits when a part is left.
        double enter = 0, exit = 1;
        bool missed = false;
        for (const HalfSpace& side : brush.sides) {
            const double da = static_cast<double>(dot(side.normal, a)) - side.dist - margin;
            const double db = static_cast<double>(dot(side.normal, b)) - side.dist - margin;
            if (da > 0 && db > 0) {
                missed = true;
                break;
            }
            if (da <= 0 && db <= 0) continue;
            const double t = da / (da - db);
            if (da > 0)
                enter = std::max(enter, t);
            else
                exit = std::min(exit, t);
            if (enter > exit) {
                missed = true;
                break;
            }
        }
        if (!missed) return false;
    }
    return true;
}

bool lumpSees(const std::vector<uint8_t>& lump, int from, int to) {
    int32_t rowBytes = 0;
    std::memcpy(&rowBytes, lump.data() + 4, 4);
    return (lump[8 + static_cast<size_t>(from) * static_cast<size_t>(rowBytes) + static_cast<size_t>(to >> 3)] >>
            (to & 7)) & 1;
}

}  // namespace q3::vis::test
