// The vis passes on a hand-made portal graph: four rooms A-B-C-D in a row along +x, where the
// openings zig-zag so that no straight line gets from A through B and C into D.
//
//   A | B      | C      | D        openings (x, y range, all z 0..10):
//     P1       P2       P3          P1 x=0 y 0..10, P2 x=10 y 30..40, P3 x=20 y 0..10
#include "base_vis.h"
#include "cluster_vis.h"
#include "leaf_merge.h"
#include "passages.h"
#include "portal_file.h"
#include "portal_flow.h"
#include "vis_graph.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>

namespace q3::vis {
namespace {

// A square opening in the plane x = `x`, over y in [y0, y0 + 10] and z in [0, 10], from cluster
// `a` into cluster `b` (points ordered so that the forward normal is +x).
std::string opening(int a, int b, float x, float y0) {
    char line[160];
    std::snprintf(line, sizeof line, "4 %d %d 0 (%g %g 0 ) (%g %g 0 ) (%g %g 10 ) (%g %g 10 )\n", a, b, x, y0, x,
                  y0 + 10, x, y0 + 10, x, y0);
    return line;
}

PortalFile zigZag() {
    return parsePortalFile("PRT1\n4\n3\n0\n" + opening(0, 1, 0, 0) + opening(1, 2, 10, 30) + opening(2, 3, 20, 0),
                           "zigzag.prt");
}

bool sees(const std::vector<uint8_t>& lump, int from, int to) {
    const int rowBytes = visRowBytes(4);
    return (lump[8 + static_cast<size_t>(from * rowBytes + to / 8)] >> (to % 8)) & 1;
}

std::vector<uint8_t> runVis(const VisGraph& graph, bool fast, FlowMode mode) {
    const BaseVis base = computeBaseVis(graph, FarPlane{});
    if (fast) return buildVisibilityLump(graph, portalClusterSets(graph, base.flood));
    const Passages passages = createPassages(graph, base);
    FlowOptions options;
    options.mode = mode;
    return buildVisibilityLump(graph, computePortalFlow(graph, base, &passages, options));
}

TEST(PortalFlow, FastVisFloodsThroughEveryRoom) {
    const std::vector<uint8_t> lump = runVis(buildVisGraph(zigZag(), false), true, FlowMode::PassagePortal);
    ASSERT_EQ(lump.size(), 8u + 4u * 8u);
    for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b) EXPECT_TRUE(sees(lump, a, b)) << a << " -> " << b;
}

TEST(PortalFlow, EveryFlowModeSeesNeighboursButNotAroundTheZigZag) {
    for (FlowMode mode : {FlowMode::Portal, FlowMode::PassagePortal, FlowMode::Passage}) {
        SCOPED_TRACE(static_cast<int>(mode));
        const std::vector<uint8_t> lump = runVis(buildVisGraph(zigZag(), false), false, mode);
        for (int a = 0; a < 4; ++a)
            for (int b = 0; b < 4; ++b) {
                const bool expected = !((a == 0 && b == 3) || (a == 3 && b == 0));
                EXPECT_EQ(sees(lump, a, b), expected) << a << " -> " << b;
            }
    }
}

TEST(PortalFlow, StraightCorridorSeesEnd) {
    // The same rooms with the openings in line: everything sees everything.
    const PortalFile file = parsePortalFile(
        "PRT1\n4\n3\n0\n" + opening(0, 1, 0, 0) + opening(1, 2, 10, 0) + opening(2, 3, 20, 0), "line.prt");
    const std::vector<uint8_t> lump = runVis(buildVisGraph(file, false), false, FlowMode::PassagePortal);
    for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b) EXPECT_TRUE(sees(lump, a, b)) << a << " -> " << b;
}

TEST(FarPlane, ParsesDistanceAndMode) {
    EXPECT_EQ(FarPlane::parse("").distance, 0.0f);
    const FarPlane plain = FarPlane::parse("512");
    EXPECT_EQ(plain.distance, 512.0f);
    EXPECT_EQ(plain.mode, '2');  // no letter: centre distance minus both radii
    const FarPlane origins = FarPlane::parse("1000o");
    EXPECT_EQ(origins.distance, 1000.0f);
    EXPECT_EQ(origins.mode, 'o');
}

TEST(FarPlane, CullsPortalsFartherApartThanTheDistance) {
    // The straight corridor: openings 10 units apart, each about 7.07 in radius. At a far plane
    // of 5 the first and last openings (20 apart, 5.9 between their spheres) no longer see each
    // other, so room 0 loses room 3 even in the base flood; the middle ones stay.
    const PortalFile file = parsePortalFile(
        "PRT1\n4\n3\n0\n" + opening(0, 1, 0, 0) + opening(1, 2, 10, 0) + opening(2, 3, 20, 0), "line.prt");
    const VisGraph graph = buildVisGraph(file, false);
    const std::vector<uint8_t> culled = buildVisibilityLump(graph, portalClusterSets(graph, computeBaseVis(graph, FarPlane::parse("5")).flood));
    EXPECT_FALSE(sees(culled, 0, 3));
    EXPECT_FALSE(sees(culled, 3, 0));
    EXPECT_TRUE(sees(culled, 0, 2));
    EXPECT_TRUE(sees(culled, 1, 3));
    // Sky portals are exempt.
    PortalFile skyFile = file;
    for (FilePortal& p : skyFile.portals) p.flags = kPortalFlagSky;
    const VisGraph sky = buildVisGraph(skyFile, false);
    const std::vector<uint8_t> kept = buildVisibilityLump(sky, portalClusterSets(sky, computeBaseVis(sky, FarPlane::parse("5")).flood));
    EXPECT_TRUE(sees(kept, 0, 3));
}

TEST(PortalFlow, WavesCoverEveryPortalOnceInOrder) {
    for (size_t n : {0u, 1u, 31u, 32u, 33u, 1000u, 12345u}) {
        const std::vector<size_t> bounds = flowWaveBounds(n);
        ASSERT_EQ(bounds.front(), 0u);
        ASSERT_EQ(bounds.back(), n);
        for (size_t i = 1; i < bounds.size(); ++i) EXPECT_LT(bounds[i - 1], bounds[i]);
    }
}

TEST(LeafMerge, CoplanarNeighbourPortalsMergeIntoOne) {
    // Two openings side by side between the same two rooms become one 0..20 opening.
    const PortalFile file =
        parsePortalFile("PRT1\n2\n2\n0\n" + opening(0, 1, 0, 0) + opening(0, 1, 0, 10), "pair.prt");
    VisGraph graph = buildVisGraph(file, false);
    const PortalMergeCount merged = mergeLeafPortals(graph);
    EXPECT_EQ(merged.portals, 2);  // once in each direction
    int active = 0;
    for (const VisPortal& p : graph.portals) {
        if (p.removed) continue;
        ++active;
        EXPECT_EQ(p.winding.count, 4);
        float minY = 1e9f, maxY = -1e9f;
        for (Vec3 v : p.winding.view()) {
            minY = std::min(minY, v.y);
            maxY = std::max(maxY, v.y);
        }
        EXPECT_EQ(minY, 0.0f);
        EXPECT_EQ(maxY, 20.0f);
    }
    EXPECT_EQ(active, 2);
}

TEST(LeafMerge, ConvexNeighboursMergeAndKeepTheirRows) {
    // A straight corridor of three rooms is convex: -merge folds it into one leaf, and every
    // original cluster still gets a row that sees all clusters.
    const PortalFile file =
        parsePortalFile("PRT1\n3\n2\n0\n" + opening(0, 1, 0, 0) + opening(1, 2, 10, 0), "line.prt");
    VisGraph graph = buildVisGraph(file, false);
    EXPECT_GT(mergeLeaves(graph, false), 0);
    const BaseVis base = computeBaseVis(graph, FarPlane{});
    const std::vector<uint8_t> lump = buildVisibilityLump(graph, portalClusterSets(graph, base.flood));
    for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) EXPECT_TRUE(sees(lump, a, b)) << a << " -> " << b;
}

TEST(LeafMerge, NeverThroughHintPortals) {
    PortalFile file = parsePortalFile("PRT1\n2\n1\n0\n" + opening(0, 1, 0, 0), "hint.prt");
    file.portals[0].flags = kPortalFlagHint;
    VisGraph graph = buildVisGraph(file, true);  // -hint: both directions are hints
    EXPECT_EQ(mergeLeaves(graph, true), 0);
}

}  // namespace
}  // namespace q3::vis
