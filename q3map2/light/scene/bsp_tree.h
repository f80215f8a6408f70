// Point queries against a compiled BSP: which leaf, cluster and area a point is in, PVS visibility
// between clusters, and whether a point lies inside an opaque world brush (q3map2's
// ClusterForPointExt), with a deterministic search for a nearby free point.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "bspfile.h"
#include "solid_segment_tree.h"
#include "vec3.h"

namespace q3::light {

// Content and surface flags of Quake 3 used to decide which brushes stop light.
namespace contents {
constexpr int32_t kSolid = 0x1;
constexpr int32_t kLava = 0x8;
constexpr int32_t kSlime = 0x10;
constexpr int32_t kWater = 0x20;
constexpr int32_t kFog = 0x40;
constexpr int32_t kAreaPortal = 0x8000;
constexpr int32_t kPlayerClip = 0x10000;
constexpr int32_t kMonsterClip = 0x20000;
constexpr int32_t kClusterPortal = 0x100000;
constexpr int32_t kDoNotEnter = 0x200000;
constexpr int32_t kBotClip = 0x400000;
constexpr int32_t kOrigin = 0x1000000;
constexpr int32_t kTranslucent = 0x20000000;
constexpr int32_t kTrigger = 0x40000000;
constexpr int32_t kNoDrop = int32_t(0x80000000u);
constexpr int32_t kSurfLightFilter = 0x8000;
constexpr int32_t kSurfAlphaShadow = 0x10000;
}  // namespace contents

// q3map2 marks a brush opaque to light unless one of its sides' shaders has the C_TRANSLUCENT compile
// flag. From the BSP alone that flag shows as these content / surface flags (surfaceparm trans,
// water, slime, lava, the clips, triggers, portals, origin, nodrop, alphashadow, lightfilter).
bool shaderIsTranslucent(const bsp::Shader& shader);

class BspTree {
public:
    // Keeps a reference to `bsp`, which must outlive the tree. `translucentShaders`, when not empty,
    // overrides shaderIsTranslucent per BSP shader index (the caller knows the real compile flags
    // from the shader scripts). The walks use a compact copy of the node tree when it is a proper
    // tree; `compactWalks` false keeps the plain walks over the BSP lumps (the reference the compact
    // ones must match answer for answer).
    explicit BspTree(const bsp::Bsp& bsp, std::span<const uint8_t> translucentShaders = {},
                     bool compactWalks = true);

    // Leaf containing the point. Points within 0.1 units of a node plane try the front side first
    // and keep it when its leaf has a cluster (q3map2 PointInLeafNum). Without nodes: leaf 0, or -1
    // when there are no leafs either.
    int leafForPoint(Vec3 point) const;
    // A leaf to try first, the one its holder found last: a caller asking about nearby points in
    // turn (the sample points of a lightmap) keeps one. The answers never depend on it.
    struct LeafHint {
        int32_t leaf = -1;
    };
    // leafForPoint, the hinted leaf tried first: it is the answer when the point lies in its box
    // and farther than 0.1 from each plane of its path that crosses the box, on the path's side
    // (the walk then goes straight to it); else the walk from the root, whose leaf the hint keeps.
    int leafForPoint(Vec3 point, LeafHint& hint) const;
    // Whether the BSP has a node tree (without one, point-in-solid tests cannot be made).
    bool hasNodes() const { return !bsp_.nodes.empty(); }
    int clusterForPoint(Vec3 point) const;  // -1 outside the world
    int areaForPoint(Vec3 point) const;     // -1 outside the world

    int numClusters() const;
    // PVS test; true when the visibility lump is absent (not vised), false for a negative cluster.
    // Inline: every luxel asks it of every light that reaches it.
    bool clusterVisible(int from, int to) const {
        if (from < 0 || to < 0) return false;
        if (from == to) return true;
        const std::vector<uint8_t>& vis = bsp_.visibility;
        if (vis.size() <= 8) return true;  // not vised: everything sees everything
        if (from >= numClusters_ || to >= numClusters_) return false;
        const size_t byte = 8 + size_t(from) * size_t(bytesPerCluster_) + size_t(to >> 3);
        return byte < vis.size() && (vis[byte] & (1u << (to & 7))) != 0;
    }

    // Whether the segment crosses a leaf outside every cluster (structural solid or the void), walked
    // front to back through the node tree with q3map2's 0.1-unit on-plane epsilon (its TraceLine_r
    // "passSolid"). Detail brushes, patches and models do not count. False without a node tree.
    bool segmentCrossesSolid(Vec3 from, Vec3 to) const;
    // Where the same walk first enters such a leaf (the start of the segment's part inside it; the
    // hit point q3map2's dirt and floodlight rays measure), nullopt when it enters none.
    std::optional<Vec3> segmentSolidEntry(Vec3 from, Vec3 to) const;
    // segmentSolidEntry of each segment from `from` along directions[i] (unit) for `length`
    // (out[i]); the walks share the descent their segments have in common, and a fan of at most
    // kMaxFanRays whose hull is clear of solid takes no walk at all.
    static constexpr size_t kMaxFanRays = 64;
    void segmentSolidEntries(Vec3 from, std::span<const Vec3> directions, float length,
                             std::span<std::optional<Vec3>> out) const;
    // True when no segment between two points of the convex hull of `points` can cross solid as
    // segmentCrossesSolid walks it (margins cover the rounding of the walk's split points), so a
    // batch of rays inside that hull needs no walk of its own. False when some may, or when the
    // answer would take more than a bounded number of nodes.
    bool hullClearOfSolid(std::span<const Vec3> points) const { return hullWalkOfSolid(points).clear; }
    // hullClearOfSolid's answer, and where the walks of segments inside the hull may begin.
    HullVerdict hullWalkOfSolid(std::span<const Vec3> points) const;
    // segmentCrossesSolid of a segment inside a hull that hullWalkOfSolid did not call clear,
    // begun where the verdict says (the same answer, fewer nodes).
    bool segmentCrossesSolidFrom(const HullVerdict& hull, Vec3 from, Vec3 to) const;

    // Whether every part of the convex polygon lies in leaves outside every cluster, the leaves
    // segmentSolidEntry stops at. Conservative: parts within 0.01 units of a node's plane go down
    // both sides, and a polygon the walk cannot settle within a bounded number of nodes (or a BSP
    // without nodes) is not in solid.
    bool polygonInSolid(std::span<const Vec3> polygon) const;

    bool brushIsOpaque(int brush) const { return brush >= 0 && brush < int(opaque_.size()) && opaque_[brush]; }

    // q3map2 ClusterForPointExt: the point's cluster, -1 outside the world, or -1 - brush when the
    // point is inside an opaque world brush of its leaf (every side plane distance <= epsilon).
    int clusterForPointExt(Vec3 point, float epsilon) const;
    int clusterForPointExt(Vec3 point, float epsilon, LeafHint& hint) const;
    // Outside the world or inside an opaque brush.
    bool pointInSolid(Vec3 point, float epsilon = 0.0f) const { return clusterForPointExt(point, epsilon) < 0; }

    // Nearest point (from a fixed lattice of offsets `step` apart within `radius`, nearest first, ties
    // in a fixed order) that is not in solid; nullopt when every candidate is. Deterministic.
    std::optional<Vec3> nudgeOutOfSolid(Vec3 point, float radius, float step, float epsilon = 0.0f) const;
    // The same search over offsets computed once with nudgeOffsets() (for many points).
    std::optional<Vec3> nudgeOutOfSolid(Vec3 point, std::span<const Vec3> offsets, float epsilon = 0.0f) const;
    // The box of a set of offsets, so that searches of many points over one set need not take it
    // again (the candidates' box is the point plus it, bit for bit: float addition is monotonic).
    struct OffsetBox {
        Vec3 lo, hi;
        bool finite = false;
    };
    static OffsetBox offsetBox(std::span<const Vec3> offsets);
    std::optional<Vec3> nudgeOutOfSolid(Vec3 point, std::span<const Vec3> offsets, const OffsetBox& box,
                                        float epsilon = 0.0f) const;

    // Whether every point of the box `lo`..`hi` is in solid for clusterForPointExt(point, epsilon):
    // each leaf the box may reach (a point within 0.1 of a node's plane may end on either side)
    // lies outside every cluster or has an opaque brush holding the whole box. False when unsure
    // (a bounded walk; without the compact walks; a box not finite).
    bool boxInSolid(Vec3 lo, Vec3 hi, float epsilon = 0.0f) const;

    // SolidSegmentTree::stoppingCells of the segment walks' solid (empty without compact walks).
    std::vector<ConvexCell> solidCells(DVec3 lo, DVec3 hi, double relax) const {
        return compact_.empty() ? std::vector<ConvexCell>{} : segmentTree_.stoppingCells(lo, hi, relax);
    }

    // Whether the compact walks are in use (the node tree is a proper tree of bounded depth).
    bool usesCompactTree() const { return !compact_.empty(); }

private:
    // The plain walks over bsp::Node / bsp::Plane, for trees that fail the construction-time check
    // (cycles, shared subtrees, very deep paths).
    int referenceLeafForPoint(Vec3 point) const;
    std::optional<Vec3> referenceSegmentSolidEntry(Vec3 from, Vec3 to) const;

    void buildCompactTree();
    void buildLeafSolids();
    void buildLeafRegions();
    int compactLeafFrom(int node, Vec3 point) const;
    int clusterInLeaf(int leafNum, Vec3 point, float epsilon) const;
    bool leafBrushHoldsBox(int leafNum, const double lo[3], const double hi[3], float epsilon) const;
    // Which children a point of the box lo..hi may walk to at `n` (compactLeafFrom): 0 front,
    // 1 back, 2 either (within 0.1 of its plane, or across it).
    // Inline: asked at every node of every box walk.
    static int boxSide(const CompactNode& n, const double lo[3], const double hi[3]) {
        double nearest = -n.dist, farthest = -n.dist, scale = std::fabs(n.dist);
        for (int axis = 0; axis < 3; ++axis) {
            const double w = n.normal[axis];
            nearest += w * (w >= 0 ? lo[axis] : hi[axis]);
            farthest += w * (w >= 0 ? hi[axis] : lo[axis]);
            scale += std::fabs(w) * std::max(std::fabs(lo[axis]), std::fabs(hi[axis]));
        }
        // The margin covers the rounding of corner distances against per-point ones many times over.
        const double margin = 0.01 + 1e-9 * scale;
        return nearest > 0.1 + margin ? 0 : farthest < -0.1 - margin ? 1 : 2;
    }
    // boxInSolid from `node` (the root, or a node above which every point of the box walks alike).
    bool boxInSolidFrom(int32_t node, const double lo[3], const double hi[3], float epsilon) const;

    const bsp::Bsp& bsp_;
    std::vector<uint8_t> opaque_;  // per brush
    int numClusters_ = 0;
    int bytesPerCluster_ = 0;
    std::vector<CompactNode> compact_;  // the whole node tree for point walks; empty: use the reference walks
    SolidSegmentTree segmentTree_;      // segment walks against leaves outside every cluster
    std::vector<int32_t> leafCluster_;  // per leaf, for the compact walks
    // Per leaf, for hinted point walks: its box and the nodes of its path whose plane comes within
    // 0.1 (and a margin) of the box, each with the side the path takes (regionSteps_).
    struct LeafRegion {
        double lo[3], hi[3];
        uint32_t firstStep = 0, numSteps = 0;
        bool usable = false;
    };
    struct RegionStep {
        int32_t node;
        int32_t side;
    };
    std::vector<LeafRegion> leafRegions_;
    std::vector<RegionStep> regionSteps_;
    // The opaque brushes listed in each leaf with their side planes inline, in the leaf's order, for
    // clusterInLeaf's point-in-brush tests without chasing leaf brush, brush and side indices.
    struct SidePlane {
        float normal[3];
        float dist;
        int32_t axis;  // as CompactNode::axis: 0..5 for a plane along an axis, 6 otherwise
    };
    struct LeafSolid {
        int32_t brush;
        uint32_t firstPlane, numPlanes;  // in solidPlanes_, the axial ones first
        uint32_t numAxial;
        // The axial sides as a box: per axis code 0..5 the least distance of its sides (+inf for
        // none), so that p.v[code] - box[code] is the largest of their distances, bit for bit.
        double box[6];
    };
    std::vector<uint32_t> leafSolidStart_;  // per leaf + 1: its range of leafSolids_
    std::vector<LeafSolid> leafSolids_;
    std::vector<SidePlane> solidPlanes_;
};

// The fixed offsets tried by nudgeOutOfSolid: every lattice point k*step (|k| <= radius/step per
// axis) within `radius`, sorted by length, then z, y, x. Exposed for tests and other searches.
std::vector<Vec3> nudgeOffsets(float radius, float step);
// Lattice offsets `divisions` steps apart per axis inside the box |o[i]| <= halfExtent[i], nearest
// first (ties by z, y, x): the region q3map2's random grid-point nudges cover (half a grid cell
// each way), searched in a fixed order.
std::vector<Vec3> nudgeOffsetsInBox(Vec3 halfExtent, int divisions);

}  // namespace q3::light
