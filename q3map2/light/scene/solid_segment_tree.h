// A compact copy of a BSP's node tree for q3map2's segment walk (TraceLine_r: front to back, 0.1-unit
// on-plane epsilon) against one kind of solid leaf. Only the subtrees that hold both stopping and
// open leaves are copied; every other child becomes an "all open" or "all solid" mark, so a walk
// ends as soon as it knows the answer. Which leaves stop a walk, and which branches count as open
// whatever they hold, is the caller's rule: structural solid for point-light rays (bsp_tree.h),
// q3map2's sun-ray rule for sun rays (sky_ray_solid.h).
#pragma once

#include <cmath>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "bspfile.h"
#include "convex_cell.h"
#include "vec3.h"

namespace q3::light {

// Depth bound of the compact walks: their stacks are fixed arrays of this size.
constexpr int kMaxCompactDepth = 256;

// The nodes of `bsp` breadth first from the root when they form a proper tree (every reference in
// range, every node reached once, no path deeper than kMaxCompactDepth); empty otherwise, and for
// a BSP without nodes.
std::vector<int32_t> properTreeOrder(const bsp::Bsp& bsp);

// CompactNode::axis for a plane normal: 0..2 when it is exactly +1 on that axis and 0 elsewhere,
// 3..5 for -1, 6 for any other.
int32_t axialPlaneCode(const float normal[3]);

// A node with its plane inline, 32 bytes. Walks keep a point as the doubles {x, y, z, -x, -y, -z}:
// `axis` 0..5 marks a plane whose normal is exactly +1 (0..2) or -1 (3..5) on one axis and 0
// elsewhere, whose distance is then p[axis] - dist, bit-identical to the full dot product in
// double (the other products are zeros and the sums exact); 6 marks any other plane.
struct CompactNode {
    double dist;
    float normal[3];
    int32_t axis;
    int32_t children[2];
};

// A point as the compact walks read it: coordinates and their negations, exact in double.
struct WalkPoint {
    double v[6];
    explicit WalkPoint(Vec3 p) : v{p.x, p.y, p.z, -double(p.x), -double(p.y), -double(p.z)} {}
};

// The node plane's distance, equal to the full dot product in double (see CompactNode::axis).
inline double nodeDistance(const CompactNode& n, const WalkPoint& p) {
    if (n.axis < 6) return p.v[n.axis] - n.dist;
    return double(n.normal[0]) * p.v[0] + double(n.normal[1]) * p.v[1] + double(n.normal[2]) * p.v[2] - n.dist;
}

// One step of q3map2's TraceLine at a node: a segment whose ends lie at `front` and `back` from the
// plane stays on one side within TRACE_ON_EPSILON (`split` false, `side` 0 front, 1 back), or is
// split at `frac`, its start's side (`side`) walked first.
struct SegmentStep {
    bool split = false;
    int side = 0;
    float frac = 0;
};
// The side a segment stays on without a split (0 front, 1 back), -1 when it is split.
inline int unsplitSide(double front, double back) {
    constexpr double kOnEpsilon = 0.1;  // TRACE_ON_EPSILON
    if (front >= -kOnEpsilon && back >= -kOnEpsilon) return 0;
    if (front < kOnEpsilon && back < kOnEpsilon) return 1;
    return -1;
}
inline SegmentStep segmentStep(double front, double back) {
    if (const int side = unsplitSide(front, back); side >= 0) return {false, side, 0};
    return {true, front < 0 ? 1 : 0, float(front / (front - back))};
}

// A depth-first copy (front child first, so a walk mostly moves forward in memory) of the nodes of
// `bsp` reached from the root through children that `keep` accepts; a child it refuses becomes
// `leafRef(child)`. The tree must be proper (properTreeOrder not empty).
std::vector<CompactNode> compactCopy(const bsp::Bsp& bsp, const std::function<bool(int32_t child)>& keep,
                                     const std::function<int32_t(int32_t child)>& leafRef);

// Whether both ends are finite and within 1e30 on every axis: every split point of such a walk
// stays finite, where the axial shortcut and the full dot product agree (0 * inf would not).
inline bool withinWalkRange(Vec3 from, Vec3 to) {
    constexpr float kMaxCoord = 1e30f;
    return std::fabs(from.x) <= kMaxCoord && std::fabs(from.y) <= kMaxCoord && std::fabs(from.z) <= kMaxCoord &&
           std::fabs(to.x) <= kMaxCoord && std::fabs(to.y) <= kMaxCoord && std::fabs(to.z) <= kMaxCoord;
}

// What one walk of the convex hull of many segments' ends tells their own walks: none of them can
// reach a stopping leaf (`clear`), or else each may begin at node `start`, above which every node
// sends all of them the same way (nullopt: from the root, as without a hull).
struct HullVerdict {
    bool clear = false;
    std::optional<int32_t> start;
    // The longest path from `start` (or the root) down to a mark, in nodes: segments walked in a
    // low subtree meet few nodes.
    int32_t height = 0;
};

class SolidSegmentTree {
public:
    SolidSegmentTree() = default;
    // `stopsAt[leaf]` nonzero: a walk that reaches the leaf stops there (leaves past the array
    // stop too). `openBranch[node]` nonzero (may be empty): the walk skips the whole branch as open.
    // Not usable() when the node tree is not a proper tree (see properTreeOrder).
    SolidSegmentTree(const bsp::Bsp& bsp, std::span<const uint8_t> stopsAt, std::span<const uint8_t> openBranch = {});

    bool usable() const { return usable_; }
    // Whether the walk of the segment reaches a stopping leaf. Requires usable() and
    // withinWalkRange (callers take the plain walk otherwise).
    bool crosses(Vec3 from, Vec3 to) const { return entry(from, to).has_value(); }
    // Where the walk (near side first) first reaches a stopping leaf: the start of the segment's part
    // in it, the point the plain recursive walk returns. Same requirements as crosses().
    std::optional<Vec3> entry(Vec3 from, Vec3 to) const { return entryFrom(root_, from, to); }
    // Where walks of segments that stay within `radius` of `center` part: every node above it sends
    // all of them to the same side. Walks from there (entryFrom) end where walks from the root do.
    int32_t sharedStart(Vec3 center, float radius) const;
    // entry() begun at `node` (root or a sharedStart() whose ball holds the segment).
    std::optional<Vec3> entryFrom(int32_t node, Vec3 from, Vec3 to) const;
    // `clear` when no segment between two points of the convex hull of `points` can reach a stopping
    // leaf as crosses() walks it (margins cover the rounding of the walk's split points), so a
    // batch of rays inside that hull needs no walk of its own; not clear when some may, when the
    // tree is not usable, or when the answer would take more than a bounded number of nodes. When
    // not clear, where the segments' walks may begin.
    HullVerdict hullWalk(std::span<const Vec3> points) const;
    // For every stopping subtree, its cell within the box lo..hi grown by `relax`: the part of the
    // box on its side of each plane above it, every plane moved `relax` away from that side. A
    // walk's part that reaches the subtree lies on its side of each plane above it but for the
    // on-plane epsilon (0.1) and the rounding of split points, so with `relax` above both, a
    // segment inside the box whose walk reaches solid meets one of these cells. Empty when nothing
    // stops a walk (or the tree is not usable); the whole box when the root does.
    std::vector<ConvexCell> stoppingCells(DVec3 lo, DVec3 hi, double relax) const;

private:
    // Children that are not copied nodes: the walk knows the answer there.
    static constexpr int32_t kOpenSubtree = -1, kSolidSubtree = -2;

    bool usable_ = false;
    std::vector<CompactNode> nodes_;  // depth first, front child first; empty: root_ is a mark
    std::vector<int32_t> heights_;    // per node, HullVerdict::height of a walk begun there
    int32_t root_ = kOpenSubtree;
};

}  // namespace q3::light
