// The beam between a source and a pass winding, and the cluster bounds the flow culls with.
#include "flow_beam.h"
#include "portal_file.h"
#include "vis_graph.h"

#include <gtest/gtest.h>

namespace q3::vis {
namespace {

// A 10 x 10 square in the plane x = `x`, centred on (y, z) = (cy, cz).
Winding square(float x, float cy, float cz) {
    Winding w;
    w.count = 4;
    w.points = {Vec3{x, cy - 5, cz - 5}, Vec3{x, cy + 5, cz - 5}, Vec3{x, cy + 5, cz + 5}, Vec3{x, cy - 5, cz + 5}};
    return w;
}

TEST(FlowBeam, EverySeparatorHasTheSourceBehindAndThePassInFront) {
    const Winding source = square(0, 0, 0), pass = square(10, 3, -2);
    Beam beam;
    buildBeam(source, pass, beam);
    // Two parallel squares: one separator per edge of each.
    EXPECT_EQ(beam.count, 8);
    for (int k = 0; k < beam.count; ++k) {
        const Plane& plane = beam.planes[static_cast<size_t>(k)];
        for (Vec3 p : source.view()) EXPECT_LE(plane.distanceTo(p), kOnEpsilon) << k;
        for (Vec3 p : pass.view()) EXPECT_GE(plane.distanceTo(p), -kOnEpsilon) << k;
    }
}

TEST(FlowBeam, ShutsOutBoxesNoLineThroughBothSquaresReaches) {
    const Winding source = square(0, 0, 0), pass = square(10, 0, 0);
    Beam beam;
    buildBeam(source, pass, beam);
    auto reachable = [&](const Box& box) {
        for (int k = 0; k < beam.count; ++k)
            if (boxBehind(beam.planes[static_cast<size_t>(k)], box)) return false;
        return true;
    };
    // Straight on, the lines spread to y in [-15, 15] at x = 20: a box there is reached...
    EXPECT_TRUE(reachable({{20, 0, 0}, {1, 1, 1}}));
    EXPECT_TRUE(reachable({{20, 14, 0}, {1, 1, 1}}));
    // ... one beyond the spread or off to the side is not, nor one behind the source.
    EXPECT_FALSE(reachable({{20, 40, 0}, {1, 1, 1}}));
    EXPECT_FALSE(reachable({{20, 0, -40}, {1, 1, 1}}));
    EXPECT_FALSE(reachable({{-20, 40, 0}, {1, 1, 1}}));
}

TEST(FlowBeam, ClusterBoundsHoldEveryPortalPoint) {
    const PortalFile file = parsePortalFile(
        "PRT1\n3\n2\n0\n4 0 1 0 (0 0 0 ) (0 10 0 ) (0 10 10 ) (0 0 10 )\n4 1 2 0 (10 30 0 ) (10 40 0 ) (10 40 10 ) (10 30 10 )\n",
        "bounds.prt");
    const VisGraph graph = buildVisGraph(file, false);
    const std::vector<Box> boxes = clusterPortalBounds(graph);
    ASSERT_EQ(boxes.size(), 3u);
    // Cluster 1 holds both openings: x 0..10, y 0..40, z 0..10.
    EXPECT_EQ(boxes[1].centre, (Vec3{5, 20, 5}));
    EXPECT_EQ(boxes[1].half, (Vec3{5, 20, 5}));
    EXPECT_EQ(boxes[0].half, (Vec3{0, 5, 5}));
}

}  // namespace
}  // namespace q3::vis
