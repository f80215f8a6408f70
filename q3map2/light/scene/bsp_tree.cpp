#include "bsp_tree.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <iterator>
#include <limits>
#include <tuple>

namespace q3::light {

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
            LeafSolid solid{b, uint32_t(solidPlanes_.size()), 0, 0, {}};
            std::fill(std::begin(solid.box), std::end(solid.box), std::numeric_limits<double>::infinity());
            // Axial sides first: they are the brush's box, which most points lie outside of, and
            // each takes one subtraction (the order of the tests does not change their answer).
            for (const bool axial : {true, false})
                for (int k = 0; k < brush.numSides; ++k) {
                    const bsp::Plane& plane = bsp_.planes[bsp_.brushSides[brush.firstSide + k].planeNum];
                    const int32_t axis = axialPlaneCode(plane.normal);
                    if ((axis < 6) != axial) continue;
                    solidPlanes_.push_back({{plane.normal[0], plane.normal[1], plane.normal[2]}, plane.dist, axis});
                    if (!axial) continue;
                    solid.box[axis] = std::min(solid.box[axis], double(plane.dist));
                    ++solid.numAxial;
                }
            solid.numPlanes = uint32_t(solidPlanes_.size()) - solid.firstPlane;
            leafSolids_.push_back(solid);
        }
    }
    leafSolidStart_[numLeafs] = uint32_t(leafSolids_.size());
}

static double planeDistance(const bsp::Plane& plane, Vec3 p) {
    return double(plane.normal[0]) * p.x + double(plane.normal[1]) * p.y + double(plane.normal[2]) * p.z -
           double(plane.dist);
}

void BspTree::buildCompactTree() {
    const size_t numLeafs = bsp_.leafs.size();
    std::vector<uint8_t> outside(numLeafs);
    for (size_t i = 0; i < numLeafs; ++i) outside[i] = bsp_.leafs[i].cluster == -1 ? 1 : 0;
    // The compact walks rely on a proper tree (the segment tree checks it); anything else keeps the
    // reference walks.
    segmentTree_ = SolidSegmentTree(bsp_, outside);
    if (!segmentTree_.usable()) return;
    leafCluster_.resize(numLeafs);
    for (size_t i = 0; i < numLeafs; ++i) leafCluster_[i] = bsp_.leafs[i].cluster;
    compact_ = compactCopy(bsp_, [](int32_t child) { return child >= 0; }, [](int32_t child) { return child; });
    buildLeafRegions();
}

void BspTree::buildLeafRegions() {
    leafRegions_.assign(bsp_.leafs.size(), LeafRegion{});
    std::vector<uint8_t> reached(bsp_.leafs.size(), 0);
    // Depth first with the path: (node, side taken) pairs from the root.
    std::vector<RegionStep> path;
    struct Visit {
        int32_t node;
        size_t depth;
        int32_t side;  // the side of the parent that leads here
    };
    std::vector<Visit> stack{{0, 0, -1}};
    while (!stack.empty()) {
        const Visit v = stack.back();
        stack.pop_back();
        path.resize(v.depth);
        if (v.depth > 0) path.back().side = v.side;
        if (v.node >= 0) {
            path.push_back({v.node, 0});
            for (int32_t side = 1; side >= 0; --side)
                stack.push_back({compact_[size_t(v.node)].children[side], v.depth + 1, side});
            continue;
        }
        const size_t leaf = size_t(-(v.node + 1));
        if (leaf >= bsp_.leafs.size() || reached[leaf]++) {
            if (leaf < bsp_.leafs.size()) leafRegions_[leaf].usable = false;  // two paths: no region
            continue;
        }
        LeafRegion& region = leafRegions_[leaf];
        const bsp::Leaf& l = bsp_.leafs[leaf];
        for (int axis = 0; axis < 3; ++axis) region.lo[axis] = l.mins[axis], region.hi[axis] = l.maxs[axis];
        region.firstStep = uint32_t(regionSteps_.size());
        region.usable = true;
        for (const RegionStep& step : path) {
            const int side = boxSide(compact_[size_t(step.node)], region.lo, region.hi);
            if (side == step.side) continue;  // every point of the box walks this way
            if (side != 2) region.usable = false;  // the box lies beyond the path
            regionSteps_.push_back(step);
        }
        region.numSteps = uint32_t(regionSteps_.size()) - region.firstStep;
    }
}

int BspTree::leafForPoint(Vec3 point, LeafHint& hint) const {
    if (hint.leaf >= 0 && size_t(hint.leaf) < leafRegions_.size()) {
        const LeafRegion& r = leafRegions_[size_t(hint.leaf)];
        const double x = point.x, y = point.y, z = point.z;
        if (r.usable && x >= r.lo[0] && x <= r.hi[0] && y >= r.lo[1] && y <= r.hi[1] && z >= r.lo[2] && z <= r.hi[2]) {
            const WalkPoint p(point);
            bool straight = true;
            for (uint32_t k = r.firstStep; k < r.firstStep + r.numSteps && straight; ++k) {
                const double d = nodeDistance(compact_[size_t(regionSteps_[k].node)], p);
                straight = regionSteps_[k].side == 0 ? d > 0.1 : d < -0.1;
            }
            if (straight) return hint.leaf;
        }
    }
    const int leaf = leafForPoint(point);
    hint.leaf = leaf;
    return leaf;
}

bool BspTree::segmentCrossesSolid(Vec3 from, Vec3 to) const { return segmentSolidEntry(from, to).has_value(); }

HullVerdict BspTree::hullWalkOfSolid(std::span<const Vec3> points) const {
    if (bsp_.nodes.empty()) return {true, std::nullopt};
    return segmentTree_.hullWalk(points);
}

bool BspTree::segmentCrossesSolidFrom(const HullVerdict& hull, Vec3 from, Vec3 to) const {
    if (!hull.start || bsp_.nodes.empty() || compact_.empty() || !withinWalkRange(from, to))
        return segmentCrossesSolid(from, to);
    return segmentTree_.entryFrom(*hull.start, from, to).has_value();
}

std::optional<Vec3> BspTree::segmentSolidEntry(Vec3 from, Vec3 to) const {
    if (bsp_.nodes.empty()) return std::nullopt;
    if (compact_.empty() || !withinWalkRange(from, to)) return referenceSegmentSolidEntry(from, to);
    return segmentTree_.entry(from, to);
}

void BspTree::segmentSolidEntries(Vec3 from, std::span<const Vec3> directions, float length,
                                  std::span<std::optional<Vec3>> out) const {
    const size_t count = std::min(directions.size(), out.size());
    // The ends lie within `length` of `from` but for the rounding of from + direction * length
    // (and of a direction's unit length): a slightly larger ball holds them all.
    const float radius = length * 1.001f + 0.01f;
    const bool shared = !bsp_.nodes.empty() && !compact_.empty() && std::isfinite(radius) &&
                        withinWalkRange(from - Vec3::splat(radius), from + Vec3::splat(radius));
    if (!shared || count > kMaxFanRays) {
        const int32_t start = shared ? segmentTree_.sharedStart(from, radius) : 0;
        for (size_t i = 0; i < count; ++i) {
            const Vec3 to = from + directions[i] * length;
            out[i] = shared && withinWalkRange(from, to) ? segmentTree_.entryFrom(start, from, to)
                                                         : segmentSolidEntry(from, to);
        }
        return;
    }
    // Every segment joins two points of its group's hull (the start and the group's ends): a group
    // whose hull no walk inside can take into solid needs no walk at all (rays that point away from
    // the nearest wall), and the others begin where their hull's walk first forks. Groups of
    // neighbouring directions (for dirt's cone, a quarter of its azimuths) have small hulls.
    constexpr size_t kGroup = 12;
    std::array<Vec3, kMaxFanRays> ends;
    for (size_t i = 0; i < count; ++i) ends[i] = from + directions[i] * length;
    const int32_t ballStart = segmentTree_.sharedStart(from, radius);
    std::array<Vec3, kGroup + 2> hull;
    hull[0] = from;
    for (size_t first = 0, n = 0; first < count; first += n) {
        // A last ray alone (dirt's cone has 48 and the normal) joins the group before it: the hull
        // of one segment costs more than the walk it could spare.
        n = count - first <= kGroup + 1 ? count - first : kGroup;
        for (size_t i = 0; i < n; ++i) hull[i + 1] = ends[first + i];
        const HullVerdict verdict = segmentTree_.hullWalk(std::span(hull.data(), n + 1));
        const int32_t start = verdict.start.value_or(ballStart);
        for (size_t i = first; i < first + n; ++i)
            out[i] = verdict.clear ? std::nullopt : segmentTree_.entryFrom(start, from, ends[i]);
    }
}

// The reference walk, near side first, so that the first solid leaf it meets is where the segment
// enters solid.
std::optional<Vec3> BspTree::referenceSegmentSolidEntry(Vec3 from, Vec3 to) const {
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

bool BspTree::polygonInSolid(std::span<const Vec3> polygon) const {
    if (bsp_.nodes.empty() || polygon.size() < 3) return false;
    for (const Vec3 p : polygon)
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return false;
    constexpr double kOnPlane = 0.01;
    // Each node at most once per part of the polygon that reaches it: the budget stops cyclic or
    // absurdly fragmenting trees, whose answer stays "not in solid".
    size_t budget = 4 * bsp_.nodes.size() + 64;
    struct Part {
        int32_t node;
        std::vector<Vec3> points;
    };
    std::vector<Part> pending{{0, std::vector<Vec3>(polygon.begin(), polygon.end())}};
    std::vector<double> distances;
    while (!pending.empty()) {
        Part part = std::move(pending.back());
        pending.pop_back();
        while (part.node >= 0) {
            if (size_t(part.node) >= bsp_.nodes.size() || budget-- == 0) return false;
            const bsp::Node& n = bsp_.nodes[size_t(part.node)];
            if (n.planeNum < 0 || size_t(n.planeNum) >= bsp_.planes.size()) return false;
            const bsp::Plane& plane = bsp_.planes[size_t(n.planeNum)];
            distances.clear();
            bool anyFront = false, anyBack = false;
            for (const Vec3 p : part.points) {
                distances.push_back(planeDistance(plane, p));
                anyFront = anyFront || distances.back() > -kOnPlane;
                anyBack = anyBack || distances.back() < kOnPlane;
            }
            if (!anyBack) {
                part.node = n.children[0];
            } else if (!anyFront) {
                part.node = n.children[1];
            } else {
                // Cut: the front part walks on here, the back part waits. Points near the plane
                // belong to both, so neither part loses a sliver.
                std::vector<Vec3> front, back;
                const size_t count = part.points.size();
                for (size_t i = 0; i < count; ++i) {
                    const Vec3 a = part.points[i], b = part.points[(i + 1) % count];
                    const double da = distances[i], db = distances[(i + 1) % count];
                    if (da > -kOnPlane) front.push_back(a);
                    if (da < kOnPlane) back.push_back(a);
                    if ((da > kOnPlane && db < -kOnPlane) || (da < -kOnPlane && db > kOnPlane)) {
                        const Vec3 mid = lerp(a, b, float(da / (da - db)));
                        front.push_back(mid);
                        back.push_back(mid);
                    }
                }
                // A part may be a mere point or edge touching the plane's margin: it walks on too.
                if (!back.empty()) pending.push_back({n.children[1], std::move(back)});
                if (front.empty()) break;
                part = {n.children[0], std::move(front)};
            }
        }
        if (part.node >= 0) continue;
        const size_t leaf = size_t(-(part.node + 1));
        if (leaf < bsp_.leafs.size() && bsp_.leafs[leaf].cluster != -1) return false;
    }
    return true;
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

int BspTree::clusterForPointExt(Vec3 point, float epsilon) const {
    return clusterInLeaf(leafForPoint(point), point, epsilon);
}

int BspTree::clusterForPointExt(Vec3 point, float epsilon, LeafHint& hint) const {
    return clusterInLeaf(leafForPoint(point, hint), point, epsilon);
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
        // A finite point outside the box is outside the brush (the same subtractions as the axial
        // sides' own tests); inside it, only the other sides remain.
        uint32_t first = solid.firstPlane;
        if (finite) {
            if (p.v[0] - solid.box[0] > limit || p.v[1] - solid.box[1] > limit || p.v[2] - solid.box[2] > limit ||
                p.v[3] - solid.box[3] > limit || p.v[4] - solid.box[4] > limit || p.v[5] - solid.box[5] > limit)
                continue;
            first += solid.numAxial;
        }
        bool inside = true;
        for (uint32_t k = first; k < solid.firstPlane + solid.numPlanes && inside; ++k) {
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

bool BspTree::leafBrushHoldsBox(int leafNum, const double lo[3], const double hi[3], float epsilon) const {
    // The box's farthest corner from each side must lie within epsilon, less a margin for the
    // rounding that separates corner distances from the distances of points inside.
    constexpr double kMargin = 0.01;
    const double limit = double(epsilon) - kMargin;
    for (uint32_t i = leafSolidStart_[size_t(leafNum)]; i < leafSolidStart_[size_t(leafNum) + 1]; ++i) {
        const LeafSolid& solid = leafSolids_[i];
        bool holds = hi[0] - solid.box[0] <= limit && hi[1] - solid.box[1] <= limit &&
                     hi[2] - solid.box[2] <= limit && -lo[0] - solid.box[3] <= limit &&
                     -lo[1] - solid.box[4] <= limit && -lo[2] - solid.box[5] <= limit;
        for (uint32_t k = solid.firstPlane + solid.numAxial; k < solid.firstPlane + solid.numPlanes && holds; ++k) {
            const SidePlane& side = solidPlanes_[k];
            double farthest = -double(side.dist);
            for (int axis = 0; axis < 3; ++axis) {
                const double w = side.normal[axis];
                farthest += w * (w >= 0 ? hi[axis] : lo[axis]);
            }
            holds = farthest <= limit;
        }
        if (holds) return true;
    }
    return false;
}

bool BspTree::boxInSolidFrom(int32_t node, const double lo[3], const double hi[3], float epsilon) const {
    constexpr int kNodeBudget = 512;
    // A back child waits for each node of the path that sends the box both ways: the validated
    // depth bounds the stack.
    int32_t pending[kMaxCompactDepth];
    int top = 0, visited = 0;
    while (true) {
        if (node < 0) {
            const int leaf = -(node + 1);
            if (leafCluster_[size_t(leaf)] != -1 && !leafBrushHoldsBox(leaf, lo, hi, epsilon)) return false;
            if (top == 0) return true;
            node = pending[--top];
            continue;
        }
        if (++visited > kNodeBudget) return false;
        const CompactNode& n = compact_[size_t(node)];
        const int side = boxSide(n, lo, hi);
        if (side == 2) pending[top++] = n.children[1];
        node = n.children[side == 2 ? 0 : side];
    }
}

bool BspTree::boxInSolid(Vec3 lo, Vec3 hi, float epsilon) const {
    if (compact_.empty()) return false;
    const double boxLo[3] = {lo.x, lo.y, lo.z}, boxHi[3] = {hi.x, hi.y, hi.z};
    for (int axis = 0; axis < 3; ++axis)
        if (!std::isfinite(boxLo[axis]) || !std::isfinite(boxHi[axis]) || boxLo[axis] > boxHi[axis]) return false;
    return boxInSolidFrom(0, boxLo, boxHi, epsilon);
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
    // candidate's walk takes that side, so all walks can start below.
    int32_t start = 0;
    const Vec3 boxLo = point + box.lo, boxHi = point + box.hi;
    bool boxed = !compact_.empty() && offsets.size() > 1 && box.finite;
    double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    for (int k = 0; k < 3 && boxed; ++k) {
        if (!std::isfinite(boxLo[k]) || !std::isfinite(boxHi[k])) boxed = false;
        lo[k] = boxLo[k];
        hi[k] = boxHi[k];
    }
    while (boxed && start >= 0) {
        const int side = boxSide(compact_[size_t(start)], lo, hi);
        if (side == 2) break;
        start = compact_[size_t(start)].children[side];
    }
    // Deep in solid, the box is (boxInSolid): no candidate can be free, which a bounded walk of the
    // box tells at once.
    if (boxed && start >= 0 && boxInSolidFrom(start, lo, hi, epsilon)) return std::nullopt;
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
