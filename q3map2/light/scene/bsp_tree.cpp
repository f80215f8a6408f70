#include "bsp_tree.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <tuple>

namespace q3::light {

// CompactNode::axis for a plane normal: 0..2 when it is exactly +1 on that axis and 0 elsewhere,
// 3..5 for -1, 6 for any other.
static int32_t axialPlaneCode(const float normal[3]) {
    for (int k = 0; k < 3; ++k) {
        const bool rest = normal[(k + 1) % 3] == 0.0f && normal[(k + 2) % 3] == 0.0f;
        if (rest && normal[k] == 1.0f) return k;
        if (rest && normal[k] == -1.0f) return k + 3;
    }
    return 6;
}

bool shaderIsTranslucent(const bsp::Shader& shader) {
    using namespace contents;
    // The content flags the C_TRANSLUCENT surfaceparms of q3map2's quake3 game table set.
    constexpr int32_t kTranslucentContents = kLava | kSlime | kWater | kAreaPortal | kPlayerClip | kMonsterClip |
                                             kClusterPortal | kDoNotEnter | kBotClip | kOrigin | kTranslucent |
                                             kTrigger | kNoDrop;
    constexpr int32_t kTranslucentSurface = kSurfLightFilter | kSurfAlphaShadow;
    return (shader.contentFlags & kTranslucentContents) != 0 || (shader.surfaceFlags & kTranslucentSurface) != 0;
}

BspTree::BspTree(const bsp::Bsp& bsp, std::span<const uint8_t> translucentShaders, bool compactWalks) : bsp_(bsp) {
    opaque_.assign(bsp.brushes.size(), 0);
    if (!bsp.models.empty()) {
        // Only world brushes block light in q3map2's point-in-solid test.
        const bsp::Model& world = bsp.models[0];
        for (int i = 0; i < world.numBrushes; ++i) {
            const int b = world.firstBrush + i;
            if (b < 0 || b >= int(bsp.brushes.size())) continue;
            const bsp::Brush& brush = bsp.brushes[b];
            bool translucent = false;
            for (int s = 0; s < brush.numSides && !translucent; ++s) {
                const int sideIndex = brush.firstSide + s;
                if (sideIndex < 0 || sideIndex >= int(bsp.brushSides.size())) continue;
                const int shader = bsp.brushSides[sideIndex].shaderNum;
                if (shader < 0 || shader >= int(bsp.shaders.size())) continue;
                translucent = size_t(shader) < translucentShaders.size() ? translucentShaders[shader] != 0
                                                                          : shaderIsTranslucent(bsp.shaders[shader]);
            }
            opaque_[b] = translucent ? 0 : 1;
        }
    }
    if (bsp.visibility.size() >= 8) {
        int32_t header[2];
        std::memcpy(header, bsp.visibility.data(), sizeof(header));
        numClusters_ = header[0];
        bytesPerCluster_ = header[1];
    }
    if (compactWalks) buildCompactTree();
    buildLeafSolids();
}

void BspTree::buildLeafSolids() {
    const size_t numLeafs = bsp_.leafs.size();
    leafSolidStart_.assign(numLeafs + 1, 0);
    for (size_t l = 0; l < numLeafs; ++l) {
        leafSolidStart_[l] = uint32_t(leafSolids_.size());
        const bsp::Leaf& leaf = bsp_.leafs[l];
        if (leaf.cluster < 0) continue;  // clusterInLeaf answers -1 at once
        for (int i = 0; i < leaf.numLeafBrushes; ++i) {
            const int lb = leaf.firstLeafBrush + i;
            if (lb < 0 || lb >= int(bsp_.leafBrushes.size())) continue;
            const int b = bsp_.leafBrushes[lb];
            if (!brushIsOpaque(b)) continue;
            const bsp::Brush& brush = bsp_.brushes[b];
            LeafSolid solid{b, uint32_t(solidPlanes_.size()), 0};
            // Axial sides first: they are the brush's box, which most points lie outside of, and
            // each takes one subtraction (the order of the tests does not change their answer).
            for (const bool axial : {true, false})
                for (int k = 0; k < brush.numSides; ++k) {
                    const bsp::Plane& plane = bsp_.planes[bsp_.brushSides[brush.firstSide + k].planeNum];
                    const int32_t axis = axialPlaneCode(plane.normal);
                    if ((axis < 6) == axial)
                        solidPlanes_.push_back({{plane.normal[0], plane.normal[1], plane.normal[2]}, plane.dist, axis});
                }
            solid.numPlanes = uint32_t(solidPlanes_.size()) - solid.firstPlane;
            leafSolids_.push_back(solid);
        }
    }
    leafSolidStart_[numLeafs] = uint32_t(leafSolids_.size());
}

// One step of q3map2's TraceLine at a node: a segment whose ends lie at `front` and `back` from the
// plane stays on one side within TRACE_ON_EPSILON (`split` false, `side` 0 front, 1 back), or is
// split at `frac`, its start's side (`side`) walked first.
struct SegmentStep {
    bool split = false;
    int side = 0;
    float frac = 0;
};

static SegmentStep segmentStep(double front, double back) {
    constexpr double kOnEpsilon = 0.1;  // TRACE_ON_EPSILON
    if (front >= -kOnEpsilon && back >= -kOnEpsilon) return {false, 0, 0};
    if (front < kOnEpsilon && back < kOnEpsilon) return {false, 1, 0};
    return {true, front < 0 ? 1 : 0, float(front / (front - back))};
}

static double planeDistance(const bsp::Plane& plane, Vec3 p) {
    return double(plane.normal[0]) * p.x + double(plane.normal[1]) * p.y + double(plane.normal[2]) * p.z -
           double(plane.dist);
}

// A point as the compact walks read it: coordinates and their negations, exact in double.
struct WalkPoint {
    double v[6];
    explicit WalkPoint(Vec3 p) : v{p.x, p.y, p.z, -double(p.x), -double(p.y), -double(p.z)} {}
};

// The same value as planeDistance for the node's plane (see CompactNode::axis).
template <class Node>
static inline double nodeDistance(const Node& n, const WalkPoint& p) {
    if (n.axis < 6) return p.v[n.axis] - n.dist;
    return double(n.normal[0]) * p.v[0] + double(n.normal[1]) * p.v[1] + double(n.normal[2]) * p.v[2] - n.dist;
}

void BspTree::buildCompactTree() {
    const std::vector<bsp::Node>& nodes = bsp_.nodes;
    const size_t numLeafs = bsp_.leafs.size();
    if (nodes.empty() || nodes.size() > size_t(INT32_MAX) || numLeafs > size_t(INT32_MAX)) return;
    // The compact walks rely on a proper tree: every reference in range, every node reached once
    // from the root (no cycles, no shared subtrees) and paths short enough for fixed stacks.
    // Anything else keeps the reference walks.
    std::vector<int32_t> order{0};  // breadth first from the root
    std::vector<int32_t> depth(nodes.size(), -1);
    depth[0] = 0;
    for (size_t i = 0; i < order.size(); ++i) {
        const bsp::Node& n = nodes[size_t(order[i])];
        if (n.planeNum < 0 || size_t(n.planeNum) >= bsp_.planes.size()) return;
        for (const int32_t child : n.children) {
            if (child < 0) {
                if (size_t(-(int64_t(child) + 1)) >= numLeafs) return;
                continue;
            }
            if (size_t(child) >= nodes.size() || depth[size_t(child)] >= 0) return;
            depth[size_t(child)] = depth[size_t(order[i])] + 1;
            if (depth[size_t(child)] >= kMaxCompactDepth) return;
            order.push_back(child);
        }
    }

    leafCluster_.resize(numLeafs);
    for (size_t i = 0; i < numLeafs; ++i) leafCluster_[i] = bsp_.leafs[i].cluster;
    // What each subtree holds, children before parents (they follow their parent in `order`); the
    // segment walk's solid test is a leaf outside every cluster.
    constexpr uint8_t kHasOpen = 1, kHasSolid = 2, kMixed = 3;
    std::vector<uint8_t> kinds(nodes.size(), 0);
    auto childKind = [&](int32_t child) -> uint8_t {
        if (child >= 0) return kinds[size_t(child)];
        return leafCluster_[size_t(-(int64_t(child) + 1))] == -1 ? kHasSolid : kHasOpen;
    };
    for (size_t i = order.size(); i-- > 0;) {
        const bsp::Node& n = nodes[size_t(order[i])];
        kinds[size_t(order[i])] = childKind(n.children[0]) | childKind(n.children[1]);
    }

    // Depth-first copies of the tree from the root: all of it for point walks, only the mixed
    // subtrees for segment walks. `keep` says which child nodes are copied; `leafRef` what a child
    // that is not copied becomes.
    auto copyTree = [&](std::vector<CompactNode>& out, auto keep, auto leafRef) {
        std::vector<int32_t> newIndex(nodes.size(), -1);
        std::vector<int32_t> stack{0};
        while (!stack.empty()) {
            const int32_t index = stack.back();
            stack.pop_back();
            newIndex[size_t(index)] = int32_t(out.size());
            const bsp::Node& n = nodes[size_t(index)];
            const bsp::Plane& plane = bsp_.planes[size_t(n.planeNum)];
            CompactNode c{plane.dist, {plane.normal[0], plane.normal[1], plane.normal[2]}, axialPlaneCode(plane.normal),
                          {n.children[0], n.children[1]}};
            out.push_back(c);
            for (int side = 1; side >= 0; --side)
                if (keep(n.children[side])) stack.push_back(n.children[side]);
        }
        for (CompactNode& c : out)
            for (int32_t& child : c.children) child = keep(child) ? newIndex[size_t(child)] : leafRef(child);
    };
    copyTree(compact_, [](int32_t child) { return child >= 0; }, [](int32_t child) { return child; });
    const uint8_t rootKind = kinds[0];
    segmentRoot_ = rootKind == kHasSolid ? kSolidSubtree : rootKind == kHasOpen ? kOpenSubtree : 0;
    if (rootKind == kMixed) {
        copyTree(
            segmentTree_, [&](int32_t child) { return child >= 0 && kinds[size_t(child)] == kMixed; },
            [&](int32_t child) { return childKind(child) == kHasSolid ? kSolidSubtree : kOpenSubtree; });
    }
}

bool BspTree::segmentCrossesSolid(Vec3 from, Vec3 to) const {
    if (bsp_.nodes.empty()) return false;
    // Bounded coordinates keep every midpoint finite, where the axial shortcut and the full dot
    // product agree (0 * inf would not); anything else takes the reference walk.
    constexpr float kMaxCoord = 1e30f;
    const bool bounded = std::fabs(from.x) <= kMaxCoord && std::fabs(from.y) <= kMaxCoord &&
                         std::fabs(from.z) <= kMaxCoord && std::fabs(to.x) <= kMaxCoord &&
                         std::fabs(to.y) <= kMaxCoord && std::fabs(to.z) <= kMaxCoord;
    if (compact_.empty() || !bounded) return referenceSegmentCrossesSolid(from, to);
    // Far sides still to walk. A push happens at most once per node of the current path, so the
    // validated depth bounds the stack. The answer is a plain "any solid leaf", so the order in
    // which sides are walked only decides how soon a hit ends the walk.
    // Plain floats, not Vec3: the array must not be zero-filled on every call.
    struct Pending {
        int32_t node;
        float start[3], end[3];
    };
    Pending stack[kMaxCompactDepth];
    int top = 0;
    int32_t node = segmentRoot_;
    Vec3 start = from, end = to;
    WalkPoint s(start), e(end);
    while (true) {
        if (node < 0) {
            if (node == kSolidSubtree) return true;
            if (top == 0) return false;
            const Pending& next = stack[--top];
            node = next.node;
            start = Vec3::fromArray(next.start);
            end = Vec3::fromArray(next.end);
            s = WalkPoint(start);
            e = WalkPoint(end);
            continue;
        }
        const CompactNode& n = segmentTree_[size_t(node)];
        const SegmentStep step = segmentStep(nodeDistance(n, s), nodeDistance(n, e));
        if (!step.split) {
            node = n.children[step.side];
        } else {
            const Vec3 mid = start + (end - start) * step.frac;
            stack[top++] = Pending{n.children[1 - step.side], {mid.x, mid.y, mid.z}, {end.x, end.y, end.z}};
            node = n.children[step.side];
            end = mid;
            e = WalkPoint(mid);
        }
    }
}

bool BspTree::hullClearOfSolid(std::span<const Vec3> points) const {
    if (bsp_.nodes.empty()) return true;
    if (compact_.empty() || points.empty()) return false;
    if (segmentRoot_ == kOpenSubtree) return true;
    if (segmentRoot_ == kSolidSubtree) return false;
    // The points' box gives an axial plane's distances at once; others take every point.
    double boxLo[3], boxHi[3];
    for (int k = 0; k < 3; ++k) boxLo[k] = boxHi[k] = points[0][k];
    for (const Vec3 p : points) {
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return false;
        for (int k = 0; k < 3; ++k) {
            boxLo[k] = std::min(boxLo[k], double(p[k]));
            boxHi[k] = std::max(boxHi[k], double(p[k]));
        }
    }
    double extent = 0;
    for (int k = 0; k < 3; ++k) extent = std::max({extent, std::fabs(boxLo[k]), std::fabs(boxHi[k])});
    if (extent > 1e30) return false;
    // A walk splits its segment at float midpoints, each of which may stray from the hull by under
    // 1e-6 of the extent (a few roundings of float coordinates): the margin covers chains of such
    // splits far longer than real paths take. It stays below the 0.1 on-plane epsilon within 9000
    // units, so ray starts lying on a wall still walk only its open side, as their segments do.
    const double margin = 0.01 + 1e-5 * extent;
    constexpr double kOnEpsilon = 0.1;  // as segmentStep
    constexpr int kNodeBudget = 192;
    int32_t stack[kMaxCompactDepth];
    int top = 0, visited = 0;
    int32_t node = segmentRoot_;
    while (true) {
        if (node == kSolidSubtree || ++visited > kNodeBudget) return false;
        if (node < 0) {
            if (top == 0) return true;
            node = stack[--top];
            continue;
        }
        const CompactNode& n = segmentTree_[size_t(node)];
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
            if (top == kMaxCompactDepth) return false;
            stack[top++] = n.children[1];
            node = n.children[0];
        }
    }
}

bool BspTree::referenceSegmentCrossesSolid(Vec3 from, Vec3 to) const {
    return segmentSolidEntry(from, to).has_value();
}

// The reference walk, near side first, so that the first solid leaf it meets is where the segment
// enters solid.
std::optional<Vec3> BspTree::segmentSolidEntry(Vec3 from, Vec3 to) const {
    if (bsp_.nodes.empty()) return std::nullopt;
    struct Local {
        const BspTree& tree;
        std::optional<Vec3> entry(int node, Vec3 start, Vec3 end, int depth) const {
            const bsp::Bsp& bsp = tree.bsp_;
            // Recursion only splits; the near side is walked first, the far side continues the loop.
            while (true) {
                if (node < 0) {
                    const int leaf = -(node + 1);
                    const bool solid = leaf >= int(bsp.leafs.size()) || bsp.leafs[size_t(leaf)].cluster == -1;
                    return solid ? std::optional<Vec3>(start) : std::nullopt;
                }
                if (node >= int(bsp.nodes.size()) || depth > 4096) return std::nullopt;  // hostile trees
                const bsp::Node& n = bsp.nodes[size_t(node)];
                if (n.planeNum < 0 || n.planeNum >= int(bsp.planes.size())) return std::nullopt;
                const bsp::Plane& plane = bsp.planes[size_t(n.planeNum)];
                const SegmentStep step = segmentStep(planeDistance(plane, start), planeDistance(plane, end));
                if (!step.split) {
                    node = n.children[step.side];
                } else {
                    const Vec3 mid = start + (end - start) * step.frac;
                    if (std::optional<Vec3> hit = entry(n.children[step.side], start, mid, depth + 1)) return hit;
                    node = n.children[1 - step.side];
                    start = mid;
                }
                ++depth;
            }
        }
    };
    return Local{*this}.entry(0, from, to, 0);
}

int BspTree::compactLeafFrom(int node, Vec3 point) const {
    const WalkPoint p(point);
    // A point within 0.1 of a plane tries the front child first and keeps the leaf found there
    // when it has a cluster; otherwise the back child of the innermost such node is walked, and
    // the last leaf reached is the answer when none has a cluster. `pending` holds those back
    // children, at most one per node of the path.
    int32_t pending[kMaxCompactDepth];
    int top = 0;
    while (true) {
        while (node >= 0) {
            const CompactNode& n = compact_[size_t(node)];
            const double d = nodeDistance(n, p);
            if (d > 0.1) {
                node = n.children[0];
            } else if (d < -0.1) {
                node = n.children[1];
            } else {
                pending[top++] = n.children[1];
                node = n.children[0];
            }
        }
        const int leaf = -node - 1;
        if (top == 0 || leafCluster_[size_t(leaf)] != -1) return leaf;
        node = pending[--top];
    }
}

int BspTree::leafForPoint(Vec3 point) const {
    if (compact_.empty()) return referenceLeafForPoint(point);
    if (!std::isfinite(point.x) || !std::isfinite(point.y) || !std::isfinite(point.z)) return -1;
    return compactLeafFrom(0, point);
}

int BspTree::referenceLeafForPoint(Vec3 point) const {
    if (bsp_.nodes.empty()) return bsp_.leafs.empty() ? -1 : 0;
    // A non-finite point compares as "on the plane" everywhere, which would walk both sides of
    // every node: it lies in no leaf.
    if (!std::isfinite(point.x) || !std::isfinite(point.y) || !std::isfinite(point.z)) return -1;
    // Iterative walk; a point on a plane (within 0.1) first tries the front child and keeps its
    // leaf when that leaf belongs to a cluster. A proper tree visits each node at most once, so a
    // budget of one step per node only stops cyclic trees (as no leaf), like bad indices and
    // nesting deeper than the segment walk allows.
    struct Local {
        const BspTree& tree;
        Vec3 p;
        mutable size_t budget;
        int walk(int node, int depth) const {
            const bsp::Bsp& bsp = tree.bsp_;
            while (node >= 0) {
                if (size_t(node) >= bsp.nodes.size() || budget == 0 || depth > 4096) return -1;
                --budget;
                const bsp::Node& n = bsp.nodes[size_t(node)];
                if (n.planeNum < 0 || size_t(n.planeNum) >= bsp.planes.size()) return -1;
                const double d = planeDistance(bsp.planes[size_t(n.planeNum)], p);
                if (d > 0.1) {
                    node = n.children[0];
                } else if (d < -0.1) {
                    node = n.children[1];
                } else {
                    const int front = walk(n.children[0], depth + 1);
                    if (front >= 0 && front < int(bsp.leafs.size()) && bsp.leafs[size_t(front)].cluster != -1)
                        return front;
                    node = n.children[1];
                }
            }
            return -(node + 1);
        }
    };
    return Local{*this, point, bsp_.nodes.size()}.walk(0, 0);
}

int BspTree::clusterForPoint(Vec3 point) const {
    const int leaf = leafForPoint(point);
    return leaf < 0 || leaf >= int(bsp_.leafs.size()) ? -1 : bsp_.leafs[leaf].cluster;
}

int BspTree::areaForPoint(Vec3 point) const {
    const int leaf = leafForPoint(point);
    return leaf < 0 || leaf >= int(bsp_.leafs.size()) ? -1 : bsp_.leafs[leaf].area;
}

int BspTree::numClusters() const { return numClusters_; }

bool BspTree::clusterVisible(int from, int to) const {
    if (from < 0 || to < 0) return false;
    if (from == to) return true;
    if (bsp_.visibility.size() <= 8) return true;  // not vised: everything sees everything
    const size_t byte = 8 + size_t(from) * size_t(bytesPerCluster_) + size_t(to >> 3);
    if (from >= numClusters_ || to >= numClusters_ || byte >= bsp_.visibility.size()) return false;
    return (bsp_.visibility[byte] & (1u << (to & 7))) != 0;
}

int BspTree::clusterForPointExt(Vec3 point, float epsilon) const {
    return clusterInLeaf(leafForPoint(point), point, epsilon);
}

int BspTree::clusterInLeaf(int leafNum, Vec3 point, float epsilon) const {
    if (leafNum < 0 || leafNum >= int(bsp_.leafs.size())) return -1;
    const int cluster = bsp_.leafs[size_t(leafNum)].cluster;
    if (cluster < 0) return -1;
    // planeDistance's arithmetic: float inputs, double products and sums. For an axial plane of a
    // finite point that is p[axis] - dist bit for bit (the other products are zeros).
    const WalkPoint p(point);
    const bool finite = std::isfinite(point.x) && std::isfinite(point.y) && std::isfinite(point.z);
    const double limit = epsilon;
    for (uint32_t i = leafSolidStart_[size_t(leafNum)]; i < leafSolidStart_[size_t(leafNum) + 1]; ++i) {
        const LeafSolid& solid = leafSolids_[i];
        bool inside = true;
        for (uint32_t k = solid.firstPlane; k < solid.firstPlane + solid.numPlanes && inside; ++k) {
            const SidePlane& s = solidPlanes_[k];
            const double d = finite && s.axis < 6 ? p.v[s.axis] - double(s.dist)
                                                  : double(s.normal[0]) * p.v[0] + double(s.normal[1]) * p.v[1] +
                                                        double(s.normal[2]) * p.v[2] - double(s.dist);
            if (d > limit) inside = false;
        }
        if (inside) return -1 - solid.brush;
    }
    return cluster;
}

std::vector<Vec3> nudgeOffsets(float radius, float step) {
    std::vector<Vec3> offsets;
    if (!(step > 0.0f) || !(radius >= 0.0f)) return {Vec3{}};
    const int n = int(std::floor(radius / step + 1e-4f));
    const float limit = radius * radius * (1.0f + 1e-5f);
    for (int z = -n; z <= n; ++z)
        for (int y = -n; y <= n; ++y)
            for (int x = -n; x <= n; ++x) {
                const Vec3 o{float(x) * step, float(y) * step, float(z) * step};
                if (dot(o, o) <= limit) offsets.push_back(o);
            }
    std::stable_sort(offsets.begin(), offsets.end(), [](Vec3 a, Vec3 b) {
        return std::make_tuple(dot(a, a), a.z, a.y, a.x) < std::make_tuple(dot(b, b), b.z, b.y, b.x);
    });
    return offsets;
}

std::vector<Vec3> nudgeOffsetsInBox(Vec3 halfExtent, int divisions) {
    std::vector<Vec3> offsets;
    const int n = std::max(1, divisions);
    for (int z = -n; z <= n; ++z)
        for (int y = -n; y <= n; ++y)
            for (int x = -n; x <= n; ++x)
                offsets.push_back(Vec3{halfExtent.x * float(x) / float(n), halfExtent.y * float(y) / float(n),
                                       halfExtent.z * float(z) / float(n)});
    // q3map2 widens its random box step by step, each axis in proportion to the cell: the search
    // goes ring by ring in that box metric (largest per-axis fraction of the half extent), then by
    // length within a ring.
    auto ring = [halfExtent](Vec3 o) {
        auto f = [](float v, float h) { return h > 0 ? std::fabs(v) / h : 0.0f; };
        return std::max({f(o.x, halfExtent.x), f(o.y, halfExtent.y), f(o.z, halfExtent.z)});
    };
    std::stable_sort(offsets.begin(), offsets.end(), [&](Vec3 a, Vec3 b) {
        return std::make_tuple(ring(a), dot(a, a), a.z, a.y, a.x) < std::make_tuple(ring(b), dot(b, b), b.z, b.y, b.x);
    });
    return offsets;
}

std::optional<Vec3> BspTree::nudgeOutOfSolid(Vec3 point, float radius, float step, float epsilon) const {
    return nudgeOutOfSolid(point, nudgeOffsets(radius, step), epsilon);
}

BspTree::OffsetBox BspTree::offsetBox(std::span<const Vec3> offsets) {
    OffsetBox box;
    box.finite = !offsets.empty();
    for (size_t i = 0; i < offsets.size(); ++i) {
        const Vec3 o = offsets[i];
        if (!std::isfinite(o.x) || !std::isfinite(o.y) || !std::isfinite(o.z)) box.finite = false;
        box.lo = i == 0 ? o : vmin(box.lo, o);
        box.hi = i == 0 ? o : vmax(box.hi, o);
    }
    return box;
}

std::optional<Vec3> BspTree::nudgeOutOfSolid(Vec3 point, std::span<const Vec3> offsets, float epsilon) const {
    return nudgeOutOfSolid(point, offsets, offsetBox(offsets), epsilon);
}

std::optional<Vec3> BspTree::nudgeOutOfSolid(Vec3 point, std::span<const Vec3> offsets, const OffsetBox& box,
                                             float epsilon) const {
    // The candidates' box: while it lies wholly beyond 0.1 of a node plane on one side, every
    // candidate's walk takes that side, so all walks can start below. The margin covers the
    // rounding of box-corner distances against per-point ones many times over.
    int32_t start = 0;
    const Vec3 boxLo = point + box.lo, boxHi = point + box.hi;
    bool boxed = !compact_.empty() && offsets.size() > 1 && box.finite;
    float lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    for (int k = 0; k < 3 && boxed; ++k) {
        if (!std::isfinite(boxLo[k]) || !std::isfinite(boxHi[k])) boxed = false;
        lo[k] = boxLo[k];
        hi[k] = boxHi[k];
    }
    // Which children every candidate's walk can take at a node: 0 front, 1 back, 2 either.
    auto boxSide = [&](const CompactNode& n) {
        double dLo = -n.dist, dHi = -n.dist, scale = std::fabs(n.dist);
        for (int k = 0; k < 3; ++k) {
            const double w = n.normal[k];
            dLo += w * (w >= 0 ? lo[k] : hi[k]);
            dHi += w * (w >= 0 ? hi[k] : lo[k]);
            scale += std::fabs(w) * std::max(std::fabs(lo[k]), std::fabs(hi[k]));
        }
        const double margin = 0.01 + 1e-9 * scale;
        return dLo > 0.1 + margin ? 0 : dHi < -0.1 - margin ? 1 : 2;
    };
    while (boxed && start >= 0) {
        const int side = boxSide(compact_[size_t(start)]);
        if (side == 2) break;
        start = compact_[size_t(start)].children[side];
    }
    // Deep in solid, every leaf the box reaches lies outside every cluster: no candidate can be
    // free, which a bounded walk of the box tells at once.
    if (boxed && start >= 0) {
        constexpr int kNodeBudget = 256;
        int32_t pending[kMaxCompactDepth];
        int top = 0, visited = 0;
        int32_t node = start;
        bool allSolid = true;
        while (allSolid) {
            if (node < 0) {
                if (leafCluster_[size_t(-(node + 1))] != -1) allSolid = false;
                else if (top == 0) break;
                else node = pending[--top];
                continue;
            }
            if (++visited > kNodeBudget) allSolid = false;
            const CompactNode& n = compact_[size_t(node)];
            const int side = boxSide(n);
            if (side == 2) pending[top++] = n.children[1];
            node = n.children[side == 2 ? 0 : side];
        }
        if (allSolid) return std::nullopt;
    }
    if (boxed && start < 0) {
        // Every candidate lies in this one leaf; only its brushes remain to test.
        const int leaf = -(start + 1);
        if (bsp_.leafs[size_t(leaf)].cluster < 0) return std::nullopt;
        for (const Vec3& offset : offsets) {
            const Vec3 candidate = point + offset;
            if (clusterInLeaf(leaf, candidate, epsilon) >= 0) return candidate;
        }
        return std::nullopt;
    }
    for (const Vec3& offset : offsets) {
        const Vec3 candidate = point + offset;
        int leaf;
        if (boxed) {
            leaf = compactLeafFrom(start, candidate);
        } else {
            leaf = leafForPoint(candidate);
        }
        if (clusterInLeaf(leaf, candidate, epsilon) >= 0) return candidate;
    }
    return std::nullopt;
}

}  // namespace q3::light
