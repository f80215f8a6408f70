#include "face_bsp.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <unordered_map>

#include "shader_info.h"

namespace q3::bspstage {
namespace {

// Faces are cut with a doubled epsilon so that near-coplanar faces are not split into slivers.
constexpr double kFaceSplitEpsilon = kClipEpsilon * 2;

int facePriority(uint32_t compileFlags) {
    int priority = 0;
    if (compileFlags & compileflags::Hint) priority += kHintPriority;
    if (compileFlags & compileflags::AntiPortal) priority += kAntiportalPriority;
    if (compileFlags & compileflags::AreaPortal) priority += kAreaportalPriority;
    if (compileFlags & compileflags::Detail) priority += kDetailPriority;
    return priority;
}

template <class WindingOf>
std::vector<BspFace> makeFaceList(const std::vector<Brush>& brushes, bool deep, WindingOf windingOf) {
    std::vector<BspFace> faces;
    for (const Brush& b : brushes) {
        if (!deep && b.detail) continue;
        for (const BrushSide& s : b.sides) {
            const Winding& w = windingOf(s);
            if (w.empty() || (s.compileFlags & compileflags::Skip)) continue;
            BspFace f;
            f.winding = w;
            f.planeNum = s.planeNum & ~1;
            f.compileFlags = s.compileFlags | (b.detail ? compileflags::Detail : 0u);
            f.priority = facePriority(f.compileFlags);
            faces.push_back(std::move(f));
        }
    }
    // q3map2 pushes each face to the front of its list.
    std::reverse(faces.begin(), faces.end());
    return faces;
}

// Which side of `plane` a face lies on. Most faces are far from most planes: their bounding box
// decides with a safe margin over the per-point test's rounding, and only near ones are tested
// point by point (the answer is the same either way).
PlaneSide faceSide(const Winding& w, const DBounds& bounds, const DPlane& plane) {
    constexpr double kMargin = kOnEpsilon + 0.125;
    double lo = -plane.dist, hi = -plane.dist;
    for (int i = 0; i < 3; ++i) {
        const double n = plane.normal[i];
        lo += n * (n > 0 ? bounds.mins[i] : bounds.maxs[i]);
        hi += n * (n > 0 ? bounds.maxs[i] : bounds.mins[i]);
    }
    if (lo > kMargin) return PlaneSide::Front;
    if (hi < -kMargin) return PlaneSide::Back;
    return windingOnPlaneSide(w, plane);
}

struct Split {
    int planeNum = -1;  // -1: make a leaf
    uint32_t compileFlags = 0;
};

// How q3map2 weighs a candidate split plane (facebsp.cpp SelectSplitPlaneNum).
struct SplitScoring {
    bool alternate = false;                   // -altsplit
    std::unordered_map<int, int> timesUsed;  // per plane, for -altsplit
    // Faces on one plane see the same counts; q3map2 counts again for each, here a plane's
    // counts are kept for the rest of the selection (`countedAt` is the selection that made them).
    struct Counts {
        int facing = 0, splits = 0, front = 0, back = 0;
    };
    std::vector<int> countedAt;
    std::vector<Counts> counts;
    int selection = 0;
};

Split selectSplit(const TreeNode& node, const std::vector<BspFace>& faces, PlaneSet& planes, const BlockSize& block,
                  SplitScoring& scoring) {
    for (int i = 0; i < 3; ++i) {
        if (block[i] <= 0) continue;
        const double dist = double(float(block[i] * (std::floor(node.bounds.mins[i] / block[i]) + 1)));
        if (node.bounds.maxs[i] > dist) return {planes.find({DVec3::axis(i), dist}), 0};
    }
    int bestValue = -99999;
    const BspFace* best = nullptr;
    const int selection = ++scoring.selection;
    if (scoring.countedAt.size() < size_t(planes.size())) {
        scoring.countedAt.resize(size_t(planes.size()), 0);
        scoring.counts.resize(size_t(planes.size()));
    }
    std::vector<DBounds> bounds;
    bounds.reserve(faces.size());
    for (const BspFace& f : faces) bounds.push_back(windingBounds(f.winding));
    for (const BspFace& split : faces) {
        const MapPlane& plane = planes[split.planeNum];
        SplitScoring::Counts& c = scoring.counts[size_t(split.planeNum)];
        if (scoring.countedAt[size_t(split.planeNum)] != selection) {
            scoring.countedAt[size_t(split.planeNum)] = selection;
            c = {};
            for (size_t i = 0; i < faces.size(); ++i) {
                if (faces[i].planeNum == split.planeNum) {
                    ++c.facing;
                    continue;
                }
                switch (faceSide(faces[i].winding, bounds[i], plane.plane)) {
                case PlaneSide::Cross: ++c.splits; break;
                case PlaneSide::Front: ++c.front; break;
                case PlaneSide::Back: ++c.back; break;
                case PlaneSide::On: break;
                }
            }
        }
        const auto [facing, splits, front, back] = c;
        int value;
        if (scoring.alternate) {
            // Balanced, large, rarely used planes first.
            auto used = scoring.timesUsed.find(split.planeNum);
            value = 20000 - std::abs(front - back) - (used == scoring.timesUsed.end() ? 0 : used->second) - facing -
                    5 * splits;
            value = int(float(value) + float(windingArea(split.winding)) * 10);
        } else {
            value = 5 * facing - 5 * splits;
            if (plane.type < PlaneNonAxial) value += 5;
        }
        value += split.priority;
        if (value > bestValue) {
            bestValue = value;
            best = &split;
        }
    }
    if (!best) return {};
    ++scoring.timesUsed[best->planeNum];
    return {best->planeNum, best->compileFlags};
}

struct Builder {
    Tree& tree;
    PlaneSet& planes;
    const BlockSize& block;
    SplitScoring scoring;
    int leafs = 0;

    int newNode(int parent, const DBounds& bounds) {
        TreeNode n;
        n.parent = parent;
        n.bounds = bounds;
        tree.nodes.push_back(std::move(n));
        return int(tree.nodes.size()) - 1;
    }

    void build(int nodeIndex, std::vector<BspFace> faces) {
        const Split split = selectSplit(tree.node(nodeIndex), faces, planes, block, scoring);
        if (split.planeNum < 0) {
            tree.node(nodeIndex).planeNum = kLeafPlane;
            tree.node(nodeIndex).hasStructuralChildren = false;
            ++leafs;
            return;
        }
        {
            TreeNode& node = tree.node(nodeIndex);
            node.planeNum = split.planeNum;
            node.compileFlags = split.compileFlags;
            node.hasStructuralChildren = !(split.compileFlags & compileflags::Detail) && !node.opaque;
        }
        const MapPlane plane = planes[split.planeNum];
        std::vector<BspFace> children[2];
        for (BspFace& face : faces) {
            if (face.planeNum == split.planeNum) continue;  // consumed by this split
            switch (windingOnPlaneSide(face.winding, plane.plane)) {
            case PlaneSide::Cross: {
                auto [front, back] = clipWindingStrict(face.winding, plane.plane, kFaceSplitEpsilon);
                if (!front.empty()) children[0].push_back({std::move(front), face.planeNum, face.priority, face.compileFlags});
                if (!back.empty()) children[1].push_back({std::move(back), face.planeNum, face.priority, face.compileFlags});
                break;
            }
            case PlaneSide::Front: children[0].push_back(std::move(face)); break;
            case PlaneSide::Back: children[1].push_back(std::move(face)); break;
            case PlaneSide::On: break;
            }
        }
        // Children receive faces at the front of their lists, reversing the order at each level.
        for (auto& list : children) std::reverse(list.begin(), list.end());

        DBounds childBounds[2] = {tree.node(nodeIndex).bounds, tree.node(nodeIndex).bounds};
        for (int i = 0; i < 3; ++i) {
            if (plane.normal()[i] == 1) {
                childBounds[0].mins[i] = plane.dist();
                childBounds[1].maxs[i] = plane.dist();
                break;
            }
            if (plane.normal()[i] == -1) {
                childBounds[0].maxs[i] = -plane.dist();
                childBounds[1].mins[i] = -plane.dist();
                break;
            }
        }
        const int front = newNode(nodeIndex, childBounds[0]);
        const int back = newNode(nodeIndex, childBounds[1]);
        tree.node(nodeIndex).children[0] = front;
        tree.node(nodeIndex).children[1] = back;
        build(front, std::move(children[0]));
        build(back, std::move(children[1]));
        tree.node(nodeIndex).hasStructuralChildren |=
            tree.node(front).hasStructuralChildren || tree.node(back).hasStructuralChildren;
    }
};

}  // namespace

int Tree::leafCount() const {
    int count = 0;
    forEachLeaf([&](int) { ++count; });
    return count;
}

std::vector<BspFace> makeStructuralFaceList(std::vector<Brush>& brushes, bool deep) {
    for (Brush& b : brushes) {
        const auto windings = std::count_if(b.sides.begin(), b.sides.end(), [](const BrushSide& s) { return !s.winding.empty(); });
        if (windings < 4) b.detail = true;
    }
    return makeFaceList(brushes, deep, [](const BrushSide& s) -> const Winding& { return s.winding; });
}

std::vector<BspFace> makeVisibleFaceList(const std::vector<Brush>& brushes, bool deep) {
    return makeFaceList(brushes, deep, [](const BrushSide& s) -> const Winding& { return s.visibleHull; });
}

Tree buildFaceTree(std::vector<BspFace> faces, PlaneSet& planes, const BlockSize& blockSize, bool alternateSplit,
                   FaceBspCounts* counts) {
    Tree tree;
    for (const BspFace& f : faces) tree.bounds.add(windingBounds(f.winding));
    const int faceCount = int(faces.size());
    Builder builder{tree, planes, blockSize, SplitScoring{alternateSplit, {}, {}, {}, 0}};
    tree.head = builder.newNode(-1, tree.bounds);
    builder.build(tree.head, std::move(faces));
    if (counts) *counts = {faceCount, builder.leafs};
    return tree;
}

}  // namespace q3::bspstage
