// Structural solid as q3map2's sun rays meet it (see sky_ray_solid.h).
#include "sky_ray_solid.h"

namespace q3::light {
namespace {

constexpr double kOnEpsilon = 0.1;  // TRACE_ON_EPSILON
constexpr int kMaxDepth = 4096;     // hostile trees

double distanceTo(const bsp::Plane& plane, Vec3 p) {
    return double(plane.normal[0]) * p.x + double(plane.normal[1]) * p.y + double(plane.normal[2]) * p.z -
           double(plane.dist);
}

}  // namespace

SkyRaySolid::SkyRaySolid(const bsp::Bsp& bsp, const TraceLeafContents& contents) : bsp_(bsp) {
    const size_t numLeafs = bsp.leafs.size();
    leafStops_.assign(numLeafs, 0);
    for (size_t l = 0; l < numLeafs; ++l) {
        const bool subdivided = l < contents.subdivided.size() && contents.subdivided[l];
        leafStops_[l] = bsp.leafs[l].cluster == -1 && !subdivided ? 1 : 0;
    }
    // A node holds pieces when a leaf below it does: children are visited before their parent
    // by walking the nodes in reverse depth-first order.
    nodeHoldsPieces_.assign(bsp.nodes.size(), 0);
    std::vector<int32_t> order, stack{0};
    std::vector<uint8_t> seen(bsp.nodes.size(), 0);
    while (!stack.empty() && !bsp.nodes.empty()) {
        const int32_t node = stack.back();
        stack.pop_back();
        if (node < 0 || size_t(node) >= bsp.nodes.size() || seen[size_t(node)]) continue;
        seen[size_t(node)] = 1;
        order.push_back(node);
        for (int32_t child : bsp.nodes[size_t(node)].children) stack.push_back(child);
    }
    for (auto it = order.rbegin(); it != order.rend(); ++it) {
        uint8_t holds = 0;
        for (int32_t child : bsp.nodes[size_t(*it)].children) {
            if (child >= 0)
                holds |= size_t(child) < nodeHoldsPieces_.size() ? nodeHoldsPieces_[size_t(child)] : 0;
            else if (size_t(-(child + 1)) < contents.holdsPieces.size())
                holds |= contents.holdsPieces[size_t(-(child + 1))];
        }
        nodeHoldsPieces_[size_t(*it)] = holds;
    }
    std::vector<uint8_t> openBranch(nodeHoldsPieces_.size());
    for (size_t n = 0; n < openBranch.size(); ++n) openBranch[n] = nodeHoldsPieces_[n] ? 0 : 1;
    compact_ = SolidSegmentTree(bsp, leafStops_, openBranch);
}

bool SkyRaySolid::stops(Vec3 from, Vec3 to) const {
    if (bsp_.nodes.empty()) return false;
    if (!compact_.usable() || !withinWalkRange(from, to)) return stopsByPlainWalk(from, to);
    return compact_.crosses(from, to);
}

HullVerdict SkyRaySolid::hullWalk(std::span<const Vec3> points) const {
    if (bsp_.nodes.empty()) return {true, std::nullopt};
    return compact_.hullWalk(points);
}

bool SkyRaySolid::stopsFrom(const HullVerdict& hull, Vec3 from, Vec3 to) const {
    if (!hull.start || bsp_.nodes.empty() || !compact_.usable() || !withinWalkRange(from, to))
        return stops(from, to);
    return compact_.entryFrom(*hull.start, from, to).has_value();
}

bool SkyRaySolid::stopsByPlainWalk(Vec3 from, Vec3 to) const {
    if (bsp_.nodes.empty()) return false;
    return stopsBelow(0, from, to, 0);
}

bool SkyRaySolid::stopsBelow(int32_t node, Vec3 start, Vec3 end, int depth) const {
    // The near side first; recursion only where the segment is split.
    while (true) {
        if (node < 0) {
            const size_t leaf = size_t(-(node + 1));
            return leaf >= leafStops_.size() || leafStops_[leaf] != 0;
        }
        if (size_t(node) >= bsp_.nodes.size() || depth > kMaxDepth) return false;
        if (!nodeHoldsPieces_[size_t(node)]) return false;  // testAll skips the branch
        const bsp::Node& n = bsp_.nodes[size_t(node)];
        if (n.planeNum < 0 || size_t(n.planeNum) >= bsp_.planes.size()) return false;
        const bsp::Plane& plane = bsp_.planes[size_t(n.planeNum)];
        const double front = distanceTo(plane, start), back = distanceTo(plane, end);
        ++depth;
        if (front >= -kOnEpsilon && back >= -kOnEpsilon) {
            node = n.children[0];
            continue;
        }
        if (front < kOnEpsilon && back < kOnEpsilon) {
            node = n.children[1];
            continue;
        }
        const int side = front < 0 ? 1 : 0;
        const Vec3 mid = start + (end - start) * float(front / (front - back));
        if (stopsBelow(n.children[side], start, mid, depth)) return true;
        node = n.children[1 - side];
        start = mid;
    }
}

}  // namespace q3::light
