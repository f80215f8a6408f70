// The compact node walks (leafForPoint, segmentCrossesSolid, nudgeOutOfSolid) against the plain
// walks over the BSP lumps, on generated trees mixing axial and oblique planes, with points and
// segments placed on, near and across the planes, and on hostile trees.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "bsp_tree.h"
#include "solid_shell.h"

namespace q3::light {
namespace {

// A random tree inside [-512, 512]^3: axial planes of both orientations at whole-unit distances
// (so lattice points land exactly on them), oblique unit-length planes, leafs in clusters 0..3, -1
// (solid to segments and points) and now and then -2 (not solid to segments, no cluster to
// points). Every leaf lists every brush: three opaque boxes.
class RandomTree {
public:
    explicit RandomTree(uint32_t seed) : rng_(seed) {
        bsp::Shader solid{};
        std::strcpy(solid.name, "textures/test/solid");
        solid.contentFlags = contents::kSolid;
        b.shaders = {solid};
        build(0);
        const float boxes[3][6] = {{-100, -100, -100, 0, 0, 0}, {32, -64, -8, 96, 64, 8}, {-20, 40, 0, 20, 48, 300}};
        for (const auto& box : boxes) {
            const int first = int(b.brushSides.size());
            for (int axis = 0; axis < 3; ++axis) {
                float maxN[3] = {0, 0, 0}, minN[3] = {0, 0, 0};
                maxN[axis] = 1;
                minN[axis] = -1;
                b.brushSides.push_back({addPlane(maxN, box[3 + axis]), 0});
                b.brushSides.push_back({addPlane(minN, -box[axis]), 0});
            }
            // The second box loses a corner to an oblique side.
            if (&box == &boxes[1]) {
                const float oblique[3] = {0.6f, 0.8f, 0};
                b.brushSides.push_back({addPlane(oblique, 80), 0});
            }
            b.leafBrushes.push_back(int(b.brushes.size()));
            b.brushes.push_back({first, int(b.brushSides.size()) - first, 0});
        }
        for (bsp::Leaf& leaf : b.leafs) leaf.numLeafBrushes = int(b.brushes.size());
        b.models = {{{-512, -512, -512}, {512, 512, 512}, 0, 0, 0, int(b.brushes.size())}};
    }

    bsp::Bsp b;

    float uniform(float lo, float hi) { return std::uniform_real_distribution<float>(lo, hi)(rng_); }
    int below(int n) { return int(rng_() % uint32_t(n)); }

private:
    int addPlane(const float n[3], float dist) {
        b.planes.push_back({{n[0], n[1], n[2]}, dist});
        return int(b.planes.size()) - 1;
    }

    int32_t build(int depth) {
        if (depth >= 9 || (depth >= 3 && below(4) == 0)) {
            const int roll = below(10);
            const int cluster = roll < 3 ? -1 : roll == 3 ? -2 : below(4);
            b.leafs.push_back({cluster, 0, {0, 0, 0}, {0, 0, 0}, 0, 0, 0, 0});
            return -int32_t(b.leafs.size());
        }
        float n[3] = {0, 0, 0};
        float dist;
        if (below(3) != 0) {
            n[below(3)] = below(2) ? 1.0f : -1.0f;
            dist = float(below(257) - 128);
        } else {
            const float v[3] = {uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)};
            const float len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
            for (int k = 0; k < 3; ++k) n[k] = len > 0 ? v[k] / len : (k == 2 ? 1.0f : 0.0f);
            dist = uniform(-100, 100);
        }
        const int node = int(b.nodes.size());
        b.nodes.push_back({addPlane(n, dist), {0, 0}, {0, 0, 0}, {0, 0, 0}});
        const int32_t front = build(depth + 1);
        const int32_t back = build(depth + 1);
        b.nodes[size_t(node)].children[0] = front;
        b.nodes[size_t(node)].children[1] = back;
        return node;
    }

    std::mt19937 rng_;
};

// Points on, just within and just beyond 0.1 of the generator's planes, plus lattice and random
// points.
std::vector<Vec3> probePoints(RandomTree& t) {
    std::vector<Vec3> points;
    for (int i = 0; i < 3000; ++i) {
        Vec3 p{t.uniform(-300, 300), t.uniform(-300, 300), t.uniform(-300, 300)};
        if (i % 3 == 0) p = Vec3{float(t.below(257) - 128), float(t.below(257) - 128), float(t.below(257) - 128)};
        if (i % 5 == 1) {
            const bsp::Plane& plane = t.b.planes[size_t(t.below(int(t.b.planes.size())))];
            const float offsets[] = {0.0f, 0.05f, -0.05f, 0.1f, -0.1f, 0.1000001f, -0.1000001f, 0.0999999f};
            const float o = offsets[t.below(8)];
            const double d = double(plane.normal[0]) * p.x + double(plane.normal[1]) * p.y +
                             double(plane.normal[2]) * p.z - double(plane.dist);
            for (int k = 0; k < 3; ++k) p[k] = float(double(p[k]) - (d - o) * double(plane.normal[k]));
        }
        points.push_back(p);
    }
    return points;
}

// clusterForPointExt against the definition: the leaf's cluster unless some opaque brush listed
// in the leaf has every side within `epsilon` of the point (the distances in double).
TEST(BspTreeWalk, PointInBrushTestsMatchTheirDefinition) {
    for (uint32_t seed = 1; seed <= 6; ++seed) {
        RandomTree t(seed);
        const BspTree tree(t.b);
        std::vector<Vec3> points = probePoints(t);
        for (int i = 0; i < 2000; ++i)  // around the brushes, on and near their sides
            points.push_back({float(t.below(241) - 120) * 0.5f + t.uniform(-0.2f, 0.2f) * float(i % 2),
                              float(t.below(241) - 120) * 0.5f, float(t.below(321) - 110) * 0.5f});
        for (const float epsilon : {-0.125f, 0.0f, 0.125f})
            for (size_t i = 0; i < points.size(); ++i) {
                const Vec3 p = points[i];
                const int leaf = tree.leafForPoint(p);
                int expected = t.b.leafs[size_t(leaf)].cluster < 0 ? -1 : t.b.leafs[size_t(leaf)].cluster;
                for (int k = 0; expected >= 0 && k < t.b.leafs[size_t(leaf)].numLeafBrushes; ++k) {
                    const int brush = t.b.leafBrushes[size_t(t.b.leafs[size_t(leaf)].firstLeafBrush + k)];
                    const bsp::Brush& br = t.b.brushes[size_t(brush)];
                    bool inside = true;
                    for (int s = 0; s < br.numSides; ++s) {
                        const bsp::Plane& pl = t.b.planes[size_t(t.b.brushSides[size_t(br.firstSide + s)].planeNum)];
                        const double d = double(pl.normal[0]) * p.x + double(pl.normal[1]) * p.y +
                                         double(pl.normal[2]) * p.z - double(pl.dist);
                        if (d > double(epsilon)) inside = false;
                    }
                    if (inside) expected = -1 - brush;
                }
                ASSERT_EQ(tree.clusterForPointExt(p, epsilon), expected) << seed << " " << i << " " << epsilon;
            }
    }
}

TEST(BspTreeWalk, CompactWalksMatchThePlainOnes) {
    for (uint32_t seed = 1; seed <= 12; ++seed) {
        RandomTree t(seed);
        const BspTree compact(t.b), plain(t.b, {}, false);
        ASSERT_TRUE(compact.usesCompactTree());
        ASSERT_FALSE(plain.usesCompactTree());
        const std::vector<Vec3> points = probePoints(t);
        for (size_t i = 0; i < points.size(); ++i) {
            const Vec3 p = points[i];
            ASSERT_EQ(compact.leafForPoint(p), plain.leafForPoint(p)) << seed << " " << i;
            ASSERT_EQ(compact.clusterForPointExt(p, -0.125f), plain.clusterForPointExt(p, -0.125f));
            const Vec3 q = points[(i * 7 + 3) % points.size()];
            ASSERT_EQ(compact.segmentCrossesSolid(p, q), plain.segmentCrossesSolid(p, q)) << seed << " " << i;
            // Axis-parallel segments run inside an axial plane when p lies on one.
            const Vec3 r{p.x, p.y, q.z};
            ASSERT_EQ(compact.segmentCrossesSolid(p, r), plain.segmentCrossesSolid(p, r));
            ASSERT_EQ(compact.segmentCrossesSolid(p, p), plain.segmentCrossesSolid(p, p));
            // Where the walk enters solid: the same split points, bit for bit.
            ASSERT_EQ(compact.segmentSolidEntry(p, q), plain.segmentSolidEntry(p, q)) << seed << " " << i;
            ASSERT_EQ(compact.segmentSolidEntry(p, r), plain.segmentSolidEntry(p, r)) << seed << " " << i;
        }
    }
}

TEST(BspTreeWalk, NudgeSearchMatchesThePlainOne) {
    const std::vector<Vec3> box = nudgeOffsetsInBox({32, 32, 64}, 4);
    const std::vector<Vec3> small = nudgeOffsets(2.0f, 1.0f);
    const std::vector<Vec3> tiny = nudgeOffsets(0.04f, 0.02f);  // often entirely inside one leaf
    int found = 0, missed = 0;
    for (uint32_t seed = 1; seed <= 6; ++seed) {
        RandomTree t(seed);
        const BspTree compact(t.b), plain(t.b, {}, false);
        const std::vector<Vec3> points = probePoints(t);
        for (size_t i = 0; i < points.size(); i += 3) {
            for (const auto* offsets : {&box, &small, &tiny}) {
                for (const float epsilon : {0.0f, -0.125f}) {
                    const auto a = compact.nudgeOutOfSolid(points[i], *offsets, epsilon);
                    const auto b = plain.nudgeOutOfSolid(points[i], *offsets, epsilon);
                    ASSERT_EQ(a.has_value(), b.has_value()) << seed << " " << i;
                    if (a) {
                        EXPECT_EQ(*a, *b);
                    }
                    (a ? found : missed) += 1;
                }
            }
        }
    }
    // Both outcomes are exercised.
    EXPECT_GT(found, 100);
    EXPECT_GT(missed, 100);
}

TEST(BspTreeWalk, NudgeSearchInsideOneSolidLeafEndsAtOnce) {
    // Root splits at x = 0: front leaf open, back leaf outside every cluster. All candidates well
    // behind the plane share the solid leaf; one straddling the plane still finds the front.
    bsp::Bsp b;
    b.planes = {{{1, 0, 0}, 0}};
    b.nodes = {{0, {-1, -2}, {0, 0, 0}, {0, 0, 0}}};
    b.leafs = {{0, 0, {0, 0, 0}, {0, 0, 0}, 0, 0, 0, 0}, {-1, 0, {0, 0, 0}, {0, 0, 0}, 0, 0, 0, 0}};
    const BspTree tree(b);
    const auto offsets = nudgeOffsets(4.0f, 1.0f);
    EXPECT_FALSE(tree.nudgeOutOfSolid({-10, 0, 0}, offsets).has_value());
    EXPECT_EQ(*tree.nudgeOutOfSolid({-4.0625f, 0, 0}, offsets), (Vec3{-0.0625f, 0, 0}));
    EXPECT_EQ(*tree.nudgeOutOfSolid({10, 0, 0}, offsets), (Vec3{10, 0, 0}));
}

// A hull the walk calls clear holds no segment that crosses solid: segments between its corners,
// between points inside it, and along its faces, many of them on or near the generator's planes.
TEST(BspTreeWalk, ClearHullsHoldNoSegmentThatCrossesSolid) {
    int clear = 0, unclear = 0;
    for (uint32_t seed = 1; seed <= 8; ++seed) {
        RandomTree t(seed);
        const BspTree tree(t.b);
        const std::vector<Vec3> points = probePoints(t);
        for (size_t i = 0; i + 1 < points.size(); i += 2) {
            // A small box of ray starts and a light (or a small emitter box) some way off.
            const float spread = t.uniform(0.0f, 40.0f), far = t.uniform(0.0f, 8.0f);
            const Vec3 a = points[i], b = points[i + 1];
            const Vec3 aMax = a + Vec3{spread, spread * 0.5f, 0.0f}, bMax = b + Vec3{far, far, far};
            std::vector<Vec3> corners;
            for (int c = 0; c < 8; ++c) {
                corners.push_back({(c & 1) ? aMax.x : a.x, (c & 2) ? aMax.y : a.y, (c & 4) ? aMax.z : a.z});
                corners.push_back({(c & 1) ? bMax.x : b.x, (c & 2) ? bMax.y : b.y, (c & 4) ? bMax.z : b.z});
            }
            if (!tree.hullClearOfSolid(corners)) {
                ++unclear;
                continue;
            }
            ++clear;
            for (int k = 0; k < 40; ++k) {
                const float u = t.uniform(0, 1), v = t.uniform(0, 1), w = t.uniform(0, 1);
                const Vec3 from = k < 16 ? corners[size_t(k)] : lerp(a, aMax, u);
                const Vec3 to = k < 16 ? corners[size_t(15 - k)] : lerp(b, bMax, k % 2 ? v : w);
                ASSERT_FALSE(tree.segmentCrossesSolid(from, to)) << seed << " " << i << " " << k;
            }
        }
    }
    // Both answers are exercised.
    EXPECT_GT(clear, 100);
    EXPECT_GT(unclear, 100);
}

// A hull the walk does not call clear names where the walks of its segments may begin: from there
// every segment inside it, many of them on or near the generator's planes, meets solid exactly
// when its walk from the root does.
TEST(BspTreeWalk, WalksBegunWhereTheHullPartsMatchWalksFromTheRoot) {
    int deeper = 0, crossing = 0, open = 0;
    for (uint32_t seed = 1; seed <= 8; ++seed) {
        RandomTree t(seed);
        const BspTree tree(t.b);
        const std::vector<Vec3> points = probePoints(t);
        for (size_t i = 0; i + 1 < points.size(); i += 2) {
            const float spread = t.uniform(0.0f, 40.0f);
            const Vec3 a = points[i], b = points[i + 1], aMax = a + Vec3{spread, spread * 0.5f, spread * 0.25f};
            std::vector<Vec3> corners;
            for (int c = 0; c < 8; ++c) corners.push_back({(c & 1) ? aMax.x : a.x, (c & 2) ? aMax.y : a.y,
                                                          (c & 4) ? aMax.z : a.z});
            corners.push_back(b);
            const HullVerdict hull = tree.hullWalkOfSolid(corners);
            if (hull.clear) continue;
            ASSERT_TRUE(hull.start.has_value());
            deeper += *hull.start != 0;
            // A walk begun below the root has less of the tree under it (the generator's depth is 9).
            if (*hull.start >= 0) {
                EXPECT_TRUE(hull.height >= 1 && hull.height <= 9);
            }
            for (int k = 0; k < 24; ++k) {
                const Vec3 from = k < 8 ? corners[size_t(k)] : lerp(a, aMax, t.uniform(0, 1));
                const bool viaStart = tree.segmentCrossesSolidFrom(hull, from, b);
                ASSERT_EQ(viaStart, tree.segmentCrossesSolid(from, b)) << seed << " " << i << " " << k;
                (viaStart ? crossing : open) += 1;
            }
        }
    }
    // Walks begin below the root, and both answers are exercised.
    EXPECT_GT(deeper, 50);
    EXPECT_GT(crossing, 500);
    EXPECT_GT(open, 500);
}

// The shell's promise: every segment whose walk enters solid meets one of its cells, segments on
// and near the planes included; and many segments that enter none meet no cell (walks saved).
TEST(BspTreeWalk, EverySegmentThatEntersSolidMeetsTheSolidShell) {
    int crossing = 0, spared = 0, open = 0;
    for (uint32_t seed = 1; seed <= 8; ++seed) {
        RandomTree t(seed);
        const BspTree tree(t.b);
        const SolidShell shell = solidShellOf(&t.b.models[0], tree);
        ASSERT_FALSE(shell.empty()) << seed;
        const std::vector<Vec3> points = probePoints(t);
        for (size_t i = 0; i + 1 < points.size(); ++i) {
            // Long segments between probe points, short ones across the planes, and segments that
            // run along a plane within its 0.1 epsilon (walked on whichever side the rule says).
            Vec3 from = points[i];
            Vec3 to = i % 3 == 0   ? points[i + 1]
                      : i % 3 == 1 ? from + Vec3{t.uniform(-3, 3), t.uniform(-3, 3), t.uniform(-3, 3)}
                                   : points[i + 1];
            if (i % 3 == 2) {
                const bsp::Plane& plane = t.b.planes[size_t(t.below(int(t.b.planes.size())))];
                const float offsets[] = {0.0f, 0.05f, -0.05f, 0.09f, -0.09f, 0.1f, -0.1f};
                for (Vec3* p : {&from, &to}) {
                    const double d = double(plane.normal[0]) * p->x + double(plane.normal[1]) * p->y +
                                     double(plane.normal[2]) * p->z - double(plane.dist);
                    const double o = offsets[t.below(7)];
                    for (int k = 0; k < 3; ++k) (*p)[k] = float(double((*p)[k]) - (d - o) * double(plane.normal[k]));
                }
            }
            ASSERT_TRUE(shell.region.contains(from) && shell.region.contains(to));
            const bool meets = shell.segmentMeetsAnyCell(from, to);
            if (tree.segmentCrossesSolid(from, to)) {
                ASSERT_TRUE(meets) << seed << " " << i;
                ++crossing;
                continue;
            }
            ++open;
            spared += !meets;
        }
    }
    EXPECT_GT(crossing, 2000);
    EXPECT_GT(spared, open / 4);
}

TEST(BspTreeWalk, SolidShellCellsHugTheSolidLeaf) {
    // Root splits at x = 0: front leaf open, back leaf outside every cluster. The one cell is the
    // back half of the world's padded box, moved 0.1 and its margins past the plane.
    bsp::Bsp b;
    b.planes = {{{1, 0, 0}, 0}};
    b.nodes = {{0, {-1, -2}, {0, 0, 0}, {0, 0, 0}}};
    b.leafs = {{0, 0, {0, 0, 0}, {0, 0, 0}, 0, 0, 0, 0}, {-1, 0, {0, 0, 0}, {0, 0, 0}, 0, 0, 0, 0}};
    b.models = {{{-100, -100, -100}, {100, 100, 100}, 0, 0, 0, 0}};
    const BspTree tree(b);
    const SolidShell shell = solidShellOf(&b.models[0], tree);
    ASSERT_EQ(shell.boxes.size(), 1u);
    EXPECT_GT(shell.boxes[0].maxs.x, 0.1f);
    EXPECT_LT(shell.boxes[0].maxs.x, 0.2f);
    EXPECT_LE(shell.boxes[0].mins.x, -164.0f);
    EXPECT_TRUE(shell.segmentMeetsAnyCell({5, 0, 0}, {0.09f, 3, 0}));    // ends within the room past the plane
    EXPECT_FALSE(shell.segmentMeetsAnyCell({5, 0, 0}, {0.5f, 30, 10}));  // stays clear
    EXPECT_TRUE(shell.segmentMeetsAnyCell({-5, 0, 0}, {-5, 1, 0}));      // inside the solid
    // Nothing stops a walk: no cells, every segment walked.
    b.leafs[1].cluster = 1;
    EXPECT_TRUE(solidShellOf(&b.models[0], BspTree(b)).empty());
    EXPECT_TRUE(solidShellOf(nullptr, tree).empty());
}

TEST(BspTreeWalk, HullWalkKeepsTheOnPlaneEpsilon) {
    // Root splits at x = 0: front leaf open, back leaf outside every cluster. A segment whose ends
    // both lie at -0.1 or more stays in front, so a hull just behind the plane is still clear.
    bsp::Bsp b;
    b.planes = {{{1, 0, 0}, 0}};
    b.nodes = {{0, {-1, -2}, {0, 0, 0}, {0, 0, 0}}};
    b.leafs = {{0, 0, {0, 0, 0}, {0, 0, 0}, 0, 0, 0, 0}, {-1, 0, {0, 0, 0}, {0, 0, 0}, 0, 0, 0, 0}};
    const BspTree tree(b);
    const std::vector<Vec3> inFront = {{1, 0, 0}, {50, 9, 3}, {7, -20, 4}};
    const std::vector<Vec3> onPlane = {{-0.05f, 0, 0}, {-0.05f, 10, 0}, {5, 0, 10}};
    const std::vector<Vec3> behind = {{-1, 0, 0}, {5, 0, 0}};
    EXPECT_TRUE(tree.hullClearOfSolid(inFront));
    EXPECT_TRUE(tree.hullClearOfSolid(onPlane));
    EXPECT_FALSE(tree.segmentCrossesSolid(onPlane[0], onPlane[2]));
    EXPECT_FALSE(tree.hullClearOfSolid(behind));
    EXPECT_TRUE(tree.segmentCrossesSolid(behind[0], behind[1]));
    // Solid in front, open behind: a hull reaching from well behind to just in front holds
    // segments that stay within 0.1 of the plane and so walk the solid front.
    bsp::Bsp flipped = b;
    flipped.leafs[0].cluster = -1;
    flipped.leafs[1].cluster = 0;
    const BspTree flippedTree(flipped);
    const std::vector<Vec3> straddling = {{-5, 0, 0}, {0.05f, 0, 0}, {-5, 10, 0}};
    EXPECT_TRUE(flippedTree.segmentCrossesSolid({0.05f, 0, 0}, {-0.05f, 0, 0}));
    EXPECT_FALSE(flippedTree.hullClearOfSolid(straddling));
    EXPECT_TRUE(flippedTree.hullClearOfSolid(std::vector<Vec3>{{-5, 0, 0}, {-0.5f, 3, 0}}));
    const float nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_FALSE(tree.hullClearOfSolid(std::vector<Vec3>{{1, 0, 0}, {nan, 0, 0}}));
}

TEST(BspTreeWalk, HostileTreesKeepThePlainWalks) {
    bsp::Bsp b;
    b.planes = {{{1, 0, 0}, 0}, {{0, 1, 0}, 0}};
    b.nodes = {{0, {1, -2}, {0, 0, 0}, {0, 0, 0}}, {1, {-1, -2}, {0, 0, 0}, {0, 0, 0}}};
    b.leafs = {{0, 0, {0, 0, 0}, {0, 0, 0}, 0, 0, 0, 0}, {-1, 0, {0, 0, 0}, {0, 0, 0}, 0, 0, 0, 0}};
    EXPECT_TRUE(BspTree(b).usesCompactTree());
    EXPECT_EQ(BspTree(b).leafForPoint({5, 5, 0}), 0);

    bsp::Bsp cycle = b;  // node 1 leads back to the root
    cycle.nodes[1].children[0] = 0;
    const BspTree cyclic(cycle);
    EXPECT_FALSE(cyclic.usesCompactTree());
    EXPECT_EQ(cyclic.leafForPoint({5, -5, 0}), 1);
    EXPECT_EQ(cyclic.leafForPoint({5, 5, 0}), -1);  // the walk ends instead of looping
    EXPECT_EQ(cyclic.leafForPoint({0, 0, 0}), 1);  // on both planes: every branch ends
    EXPECT_FALSE(cyclic.segmentCrossesSolid({5, 5, 0}, {6, 6, 0}));

    bsp::Bsp shared = b;  // both children of the root are node 1
    shared.nodes[0].children[1] = 1;
    EXPECT_FALSE(BspTree(shared).usesCompactTree());
    EXPECT_EQ(BspTree(shared).leafForPoint({-5, 5, 0}), 0);

    for (const int32_t bad : {7, -9, std::numeric_limits<int32_t>::min()}) {
        bsp::Bsp broken = b;
        broken.nodes[1].children[0] = bad;
        const BspTree tree(broken);
        EXPECT_FALSE(tree.usesCompactTree());
        EXPECT_EQ(tree.leafForPoint({5, -5, 0}), 1);
        EXPECT_TRUE(tree.segmentCrossesSolid({5, 5, 0}, {5, -5, 0}));  // a missing leaf counts as solid
    }
    bsp::Bsp badPlane = b;
    badPlane.nodes[1].planeNum = 5;
    EXPECT_FALSE(BspTree(badPlane).usesCompactTree());
    EXPECT_EQ(BspTree(badPlane).leafForPoint({5, 5, 0}), -1);

    // Coordinates beyond 1e30 take the plain walk too, where 0 * inf stays NaN as it always was.
    const BspTree tree(b), plain(b, {}, false);
    const float inf = std::numeric_limits<float>::infinity();
    for (const Vec3 far : {Vec3{5, inf, 0}, Vec3{-5, 1e35f, 0}, Vec3{3e38f, -3e38f, 0}})
        EXPECT_EQ(tree.segmentCrossesSolid({5, 5, 0}, far), plain.segmentCrossesSolid({5, 5, 0}, far));
}

}  // namespace
}  // namespace q3::light
