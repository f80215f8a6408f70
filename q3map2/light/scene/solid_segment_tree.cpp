#include "solid_segment_tree.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace q3::light {

std::vector<int32_t> properTreeOrder(const bsp::Bsp& bsp) {
    const std::vector<bsp::Node>& nodes = bsp.nodes;
    const size_t numLeafs = bsp.leafs.size();
    if (nodes.empty() || nodes.size() > size_t(INT32_MAX) || numLeafs > size_t(INT32_MAX)) return {};
    std::vector<int32_t> order{0};
    std::vector<int32_t> depth(nodes.size(), -1);
    depth[0] = 0;
    for (size_t i = 0; i < order.size(); ++i) {
        const bsp::Node& n = nodes[size_t(order[i])];
        if (n.planeNum < 0 || size_t(n.planeNum) >= bsp.planes.size()) return {};
        for (const int32_t child : n.children) {
            if (child < 0) {
                if (size_t(-(int64_t(child) + 1)) >= numLeafs) return {};
                continue;
            }
            if (size_t(child) >= nodes.size() || depth[size_t(child)] >= 0) return {};
            depth[size_t(child)] = depth[size_t(order[i])] + 1;
            if (depth[size_t(child)] >= kMaxCompactDepth) return {};
            order.push_back(child);
        }
    }
    return order;
}

int32_t axialPlaneCode(const float normal[3]) {
    for (int k = 0; k < 3; ++k) {
        const bool rest = normal[(k + 1) % 3] == 0.0f && normal[(k + 2) % 3] == 0.0f;
        if (rest && normal[k] == 1.0f) return k;
        if (rest && normal[k] == -1.0f) return k + 3;
    }
    return 6;
}

std::vector<CompactNode> compactCopy(const bsp::Bsp& bsp, const std::function<bool(int32_t child)>& keep,
                                     const std::function<int32_t(int32_t child)>& leafRef) {
    std::vector<CompactNode> out;
    std::vector<int32_t> newIndex(bsp.nodes.size(), -1);
    std::vector<int32_t> stack{0};
    while (!stack.empty()) {
        const int32_t index = stack.back();
        stack.pop_back();
        newIndex[size_t(index)] = int32_t(out.size());
        const bsp::Node& n = bsp.nodes[size_t(index)];
        const bsp::Plane& plane = bsp.planes[size_t(n.planeNum)];
        out.push_back(CompactNode{plane.dist, {plane.normal[0], plane.normal[1], plane.normal[2]},
                                  axialPlaneCode(plane.normal), {n.children[0], n.children[1]}});
        for (int side = 1; side >= 0; --side)
            if (keep(n.children[side])) stack.push_back(n.children[side]);
    }
    for (CompactNode& c : out)
        for (int32_t& child : c.children) child = keep(child) ? newIndex[size_t(child)] : leafRef(child);
    return out;
}

SolidSegmentTree::SolidSegmentTree(const bsp::Bsp& bsp, std::span<const uint8_t> stopsAt,
                                   std::span<const uint8_t> openBranch) {
    const std::vector<int32_t> order = properTreeOrder(bsp);
    if (order.empty()) return;
    usable_ = true;
    // What each subtree holds, children before parents (they follow their parent in `order`).
    constexpr uint8_t kHasOpen = 1, kHasSolid = 2, kMixed = 3;
    std::vector<uint8_t> kinds(bsp.nodes.size(), 0);
    auto childKind = [&](int32_t child) -> uint8_t {
        if (child >= 0) return kinds[size_t(child)];
        const size_t leaf = size_t(-(int64_t(child) + 1));
        return leaf >= stopsAt.size() || stopsAt[leaf] ? kHasSolid : kHasOpen;
    };
    for (size_t i = order.size(); i-- > 0;) {
        const size_t node = size_t(order[i]);
        const bsp::Node& n = bsp.nodes[node];
        kinds[node] = node < openBranch.size() && openBranch[node] ? kHasOpen
                                                                   : childKind(n.children[0]) | childKind(n.children[1]);
    }
    root_ = kinds[0] == kHasSolid ? kSolidSubtree : kinds[0] == kHasOpen ? kOpenSubtree : 0;
    if (kinds[0] == kMixed)
        nodes_ = compactCopy(
            bsp, [&](int32_t child) { return child >= 0 && kinds[size_t(child)] == kMixed; },
            [&](int32_t child) { return childKind(child) == kHasSolid ? kSolidSubtree : kOpenSubtree; });
    // Children follow their parents in the depth-first copy.
    heights_.assign(nodes_.size(), 1);
    for (size_t i = nodes_.size(); i-- > 0;)
        for (const int32_t child : nodes_[i].children)
            if (child >= 0) heights_[i] = std::max(heights_[i], heights_[size_t(child)] + 1);
}

int32_t SolidSegmentTree::sharedStart(Vec3 center, float radius) const {
    // A node's step keeps both ends on one side when both lie beyond the on-plane epsilon on it
    // (segmentStep): a ball whose centre lies farther than its radius plus that epsilon qualifies.
    constexpr double kOnEpsilon = 0.1;  // as segmentStep
    const double reach = double(radius) + kOnEpsilon;
    const WalkPoint c(center);
    int32_t node = root_;
    while (node >= 0) {
        const CompactNode& n = nodes_[size_t(node)];
        const double d = nodeDistance(n, c);
        if (d > reach)
            node = n.children[0];
        else if (d < -reach)
            node = n.children[1];
        else
            break;
    }
    return node;
}

std::optional<Vec3> SolidSegmentTree::entryFrom(int32_t root, Vec3 from, Vec3 to) const {
    // Far sides still to walk. A push happens at most once per node of the current path, so the
    // validated depth bounds the stack. The near side of every split is walked first and keeps the
    // part's start, so the first stopping leaf reached is where the segment enters one, and a whole
    // stopping subtree (a mark) is entered at the start of the part that reaches it.
    // Plain floats, not Vec3: the array must not be zero-filled on every call.
    struct Pending {
        int32_t node;
        float start[3], end[3];
    };
    Pending stack[kMaxCompactDepth];
    int top = 0;
    int32_t node = root;
    Vec3 start = from, end = to;
    WalkPoint s(start), e(end);
    while (true) {
        if (node < 0) {
            if (node == kSolidSubtree) return start;
            if (top == 0) return std::nullopt;
            const Pending& next = stack[--top];
            node = next.node;
            start = Vec3::fromArray(next.start);
            end = Vec3::fromArray(next.end);
            s = WalkPoint(start);
            e = WalkPoint(end);
            continue;
        }
        const CompactNode& n = nodes_[size_t(node)];
        // segmentStep, with the unsplit sides decided before the split is made (most nodes).
        const double front = nodeDistance(n, s), back = nodeDistance(n, e);
        if (const int side = unsplitSide(front, back); side >= 0) {
            node = n.children[side];
            continue;
        }
        const SegmentStep step = segmentStep(front, back);
        const Vec3 mid = start + (end - start) * step.frac;
        stack[top++] = Pending{n.children[1 - step.side], {mid.x, mid.y, mid.z}, {end.x, end.y, end.z}};
        node = n.children[step.side];
        end = mid;
        e = WalkPoint(mid);
    }
}

HullVerdict SolidSegmentTree::hullWalk(std::span<const Vec3> points) const {
    if (!usable_ || points.empty()) return {};
    if (root_ == kOpenSubtree) return {true, std::nullopt};
    if (root_ == kSolidSubtree) return {false, root_};
    // The points' box gives an axial plane's distances at once; others take every point.
    double boxLo[3], boxHi[3];
    for (int k = 0; k < 3; ++k) boxLo[k] = boxHi[k] = points[0][k];
    for (const Vec3 p : points) {
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return {};
        for (int k = 0; k < 3; ++k) {
            boxLo[k] = std::min(boxLo[k], double(p[k]));
            boxHi[k] = std::max(boxHi[k], double(p[k]));
        }
    }
    double extent = 0;
    for (int k = 0; k < 3; ++k) extent = std::max({extent, std::fabs(boxLo[k]), std::fabs(boxHi[k])});
    if (extent > 1e30) return {};
    // A walk splits its segment at float midpoints, each of which may stray from the hull by under
    // 1e-6 of the extent (a few roundings of float coordinates): the margin covers chains of such
    // splits far longer than real paths take. It stays below the 0.1 on-plane epsilon within 9000
    // units, so ray starts lying on a wall still walk only its open side, as their segments do.
    const double margin = 0.01 + 1e-5 * extent;
    constexpr double kOnEpsilon = 0.1;  // as segmentStep
    constexpr int kNodeBudget = 192;
    int32_t stack[kMaxCompactDepth];
    int top = 0, visited = 0;
    int32_t node = root_;
    // The first node that sends the hull both ways: every node above it sends each segment the way
    // it sends the hull, unsplit (no split point has been made yet, so the margin is not needed
    // there but harmless), and walks begun at it end where walks from the root do.
    std::optional<int32_t> firstFork;
    auto unclear = [&](int32_t from) { return HullVerdict{false, from, from >= 0 ? heights_[size_t(from)] : 0}; };
    while (true) {
        if (node == kSolidSubtree || ++visited > kNodeBudget) return unclear(firstFork ? *firstFork : node);
        if (node < 0) {
            if (top == 0) return {true, std::nullopt};
            node = stack[--top];
            continue;
        }
        const CompactNode& n = nodes_[size_t(node)];
        double lo, hi;
        if (n.axis < 3) {
            lo = boxLo[n.axis] - n.dist;
            hi = boxHi[n.axis] - n.dist;
        } else if (n.axis < 6) {
            lo = -boxHi[n.axis - 3] - n.dist;
            hi = -boxLo[n.axis - 3] - n.dist;
        } else {
            // The box's nearest and farthest corners first; only a box the plane cuts needs the points.
            lo = hi = -n.dist;
            for (int k = 0; k < 3; ++k) {
                const double w = n.normal[k];
                lo += w * (w >= 0 ? boxLo[k] : boxHi[k]);
                hi += w * (w >= 0 ? boxHi[k] : boxLo[k]);
            }
            if (lo >= -kOnEpsilon + margin || hi < -kOnEpsilon - margin) {
                node = n.children[lo >= -kOnEpsilon + margin ? 0 : 1];
                continue;
            }
            lo = std::numeric_limits<double>::infinity();
            hi = -lo;
            for (const Vec3 p : points) {
                const double d =
                    double(n.normal[0]) * p.x + double(n.normal[1]) * p.y + double(n.normal[2]) * p.z - n.dist;
                lo = std::min(lo, d);
                hi = std::max(hi, d);
            }
        }
        // A segment goes front when both ends lie at -0.1 or more, back when that fails and both
        // lie below 0.1: the whole hull goes back only when it lies below -0.1.
        if (lo >= -kOnEpsilon + margin) {
            node = n.children[0];
        } else if (hi < -kOnEpsilon - margin) {
            node = n.children[1];
        } else {
            // Both sides; the pending side waits on a stack no deeper than the path.
            if (!firstFork) firstFork = node;
            if (top == kMaxCompactDepth) return unclear(*firstFork);
            stack[top++] = n.children[1];
            node = n.children[0];
        }
    }
}

std::vector<ConvexCell> SolidSegmentTree::stoppingCells(DVec3 lo, DVec3 hi, double relax) const {
    std::vector<ConvexCell> out;
    if (!usable_ || root_ == kOpenSubtree) return out;
    const ConvexCell box = ConvexCell::box(lo, hi);
    if (root_ == kSolidSubtree) {
        if (!box.empty()) out.push_back(box);
        return out;
    }
    // Depth first, front child first; a cut that leaves the cell whole keeps it as it is.
    struct Pending {
        int32_t node;
        ConvexCell cell;
    };
    std::vector<Pending> stack;
    stack.push_back({root_, box});
    while (!stack.empty()) {
        Pending p = std::move(stack.back());
        stack.pop_back();
        const CompactNode& n = nodes_[size_t(p.node)];
        const DVec3 normal{n.normal[0], n.normal[1], n.normal[2]};
        // Front keeps dot(normal, x) - dist >= -relax, back keeps dot(normal, x) - dist <= relax.
        const DVec3 keepNormal[2] = {-normal, normal};
        const double keepDist[2] = {relax - n.dist, n.dist + relax};
        for (int side = 1; side >= 0; --side) {
            const int32_t child = n.children[side];
            if (child == kOpenSubtree) continue;
            ConvexCell cell = p.cell.inside(keepNormal[side], keepDist[side])
                                  ? p.cell
                                  : p.cell.clipped(keepNormal[side], keepDist[side]);
            if (cell.empty()) continue;
            if (child == kSolidSubtree)
                out.push_back(std::move(cell));
            else
                stack.push_back({child, std::move(cell)});
        }
    }
    return out;
}

}  // namespace q3::light
