// Points inside solid: a texel whose surface point lies in a solid leaf or inside an opaque brush
// faces a wall flush against it, so no player ever sees it.
#include "light_compare_internal.h"

namespace q3::conformance::detail {
namespace {

constexpr int kContentsSolid = 1;

float planeDistance(const bsp::Plane& p, Vec3 point) {
    return p.normal[0] * point.x + p.normal[1] * point.y + p.normal[2] * point.z - p.dist;
}

}  // namespace

SolidTest::SolidTest(const bsp::Bsp& bsp) : bsp_(bsp) {}

bool SolidTest::inSolid(Vec3 point) const {
    if (bsp_.nodes.empty()) return false;
    int node = 0;
    for (size_t steps = 0; node >= 0; ++steps) {
        if (size_t(node) >= bsp_.nodes.size() || steps > bsp_.nodes.size()) return false;  // malformed tree
        const bsp::Node& n = bsp_.nodes[size_t(node)];
        if (n.planeNum < 0 || size_t(n.planeNum) >= bsp_.planes.size()) return false;
        node = n.children[planeDistance(bsp_.planes[size_t(n.planeNum)], point) >= 0 ? 0 : 1];
    }
    const size_t leafNum = size_t(-(node + 1));
    if (leafNum >= bsp_.leafs.size()) return false;
    const bsp::Leaf& leaf = bsp_.leafs[leafNum];
    if (leaf.cluster < 0) return true;
    // Detail brushes leave their leaf's cluster valid: test the opaque ones of the leaf.
    for (int i = 0; i < leaf.numLeafBrushes; ++i) {
        const int64_t lb = int64_t(leaf.firstLeafBrush) + i;
        if (lb < 0 || size_t(lb) >= bsp_.leafBrushes.size()) continue;
        const int b = bsp_.leafBrushes[size_t(lb)];
        if (b < 0 || size_t(b) >= bsp_.brushes.size()) continue;
        const bsp::Brush& brush = bsp_.brushes[size_t(b)];
        if (brush.shaderNum < 0 || size_t(brush.shaderNum) >= bsp_.shaders.size() ||
            !(bsp_.shaders[size_t(brush.shaderNum)].contentFlags & kContentsSolid))
            continue;
        bool inside = brush.numSides > 0;
        for (int s = 0; s < brush.numSides && inside; ++s) {
            const int64_t side = int64_t(brush.firstSide) + s;
            if (side < 0 || size_t(side) >= bsp_.brushSides.size()) { inside = false; break; }
            const int plane = bsp_.brushSides[size_t(side)].planeNum;
            if (plane < 0 || size_t(plane) >= bsp_.planes.size()) { inside = false; break; }
            inside = planeDistance(bsp_.planes[size_t(plane)], point) <= 0;
        }
        if (inside) return true;
    }
    return false;
}

}  // namespace q3::conformance::detail
