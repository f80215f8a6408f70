// Merging model triangles before autoclip: coplanar ones sharing an edge become one convex polygon,
// and for the backplane shapes a ridge becomes one volume while a valley stays two.
#include <gtest/gtest.h>

#include "clip_windings.h"

namespace q3::bspstage {
namespace {

// A quad (corners in order, facing the way (c - a) x (b - a) points) as two triangles.
void addQuad(std::vector<ClipWinding>& set, DVec3 a, DVec3 b, DVec3 c, DVec3 d) {
    ClipWinding w;
    ASSERT_TRUE(clipTriangleWinding(a, b, c, 0, w));
    set.push_back(w);
    ASSERT_TRUE(clipTriangleWinding(a, c, d, 0, w));
    set.push_back(w);
}

std::vector<ClipWinding> volumesAlongZ(std::vector<ClipWinding> set) {
    std::vector<ClipWinding> faces = mergeCoplanarWindings(std::move(set));
    for (ClipWinding& w : faces) {
        w.extrusion = {0, 0, 1};
        w.fronts.push_back({w.plane, w.points, w.surface});
    }
    return mergeConvexVolumes(std::move(faces));
}

TEST(ClipWindings, TwoTrianglesOfASquareBecomeOneQuad) {
    std::vector<ClipWinding> set;
    addQuad(set, {0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0});
    const std::vector<ClipWinding> merged = mergeCoplanarWindings(set);
    ASSERT_EQ(merged.size(), 1u);
    EXPECT_EQ(merged[0].points.size(), 4u);
}

TEST(ClipWindings, TrianglesAtAnAngleStaySeparate) {
    std::vector<ClipWinding> set;
    ClipWinding w;
    ASSERT_TRUE(clipTriangleWinding({0, 0, 0}, {0, 1, 0}, {1, 1, 0}, 0, w));
    set.push_back(w);
    ASSERT_TRUE(clipTriangleWinding({0, 0, 0}, {1, 1, 0}, {1, 1, 1}, 0, w));
    set.push_back(w);
    EXPECT_EQ(mergeCoplanarWindings(set).size(), 2u);
}

TEST(ClipWindings, ARidgeMergesIntoOneVolumeAValleyDoesNot) {
    std::vector<ClipWinding> ridge;
    addQuad(ridge, {0, 0, 0}, {0, 1, 0}, {1, 1, 1}, {1, 0, 1});
    addQuad(ridge, {1, 0, 1}, {1, 1, 1}, {2, 1, 0}, {2, 0, 0});
    const std::vector<ClipWinding> roof = volumesAlongZ(ridge);
    ASSERT_EQ(roof.size(), 1u);
    EXPECT_EQ(roof[0].fronts.size(), 2u);
    EXPECT_EQ(roof[0].points.size(), 4u);  // the ridge's ends are collinear seen along Z

    std::vector<ClipWinding> valley;
    addQuad(valley, {0, 0, 1}, {0, 1, 1}, {1, 1, 0}, {1, 0, 0});
    addQuad(valley, {1, 0, 0}, {1, 1, 0}, {2, 1, 1}, {2, 0, 1});
    EXPECT_EQ(volumesAlongZ(valley).size(), 2u);
}

}  // namespace
}  // namespace q3::bspstage
