// The shared winding operations: bounds, area, centroid, and the axial split with and without
// per-vertex attributes.
#include <gtest/gtest.h>

#include <vector>

#include "winding_ops.h"

namespace q3::light {
namespace {

const std::vector<Vec3> kSquare{{0, 0, 0}, {10, 0, 0}, {10, 10, 0}, {0, 10, 0}};

TEST(WindingOps, AreaBoundsCentroid) {
    EXPECT_FLOAT_EQ(windingArea(kSquare), 100.0f);
    const Bounds b = windingBounds(kSquare);
    EXPECT_EQ(b.mins, Vec3(0, 0, 0));
    EXPECT_EQ(b.maxs, Vec3(10, 10, 0));
    EXPECT_EQ(windingCentroid(kSquare), Vec3(5, 5, 0));
    // The centroid is the mean of the points, not the centre of the bounds.
    const std::vector<Vec3> triangle{{0, 0, 0}, {9, 0, 0}, {9, 9, 0}};
    EXPECT_EQ(windingCentroid(triangle), Vec3(6, 3, 0));
    EXPECT_FLOAT_EQ(windingArea(std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}}), 0.0f);
}

TEST(WindingOps, AxialSplitKeepsArea) {
    std::vector<Vec3> front, back;
    clipWindingAxial(kSquare, 0, 3.0f, 0.1f, front, back);
    ASSERT_EQ(front.size(), 4u);
    ASSERT_EQ(back.size(), 4u);
    EXPECT_FLOAT_EQ(windingArea(front), 70.0f);
    EXPECT_FLOAT_EQ(windingArea(back), 30.0f);
    for (const Vec3& p : front) EXPECT_GE(p.x, 3.0f);
    for (const Vec3& p : back) EXPECT_LE(p.x, 3.0f);
}

TEST(WindingOps, PointsWithinEpsilonGoToBothSides) {
    // The split plane passes within epsilon of two corners: no new vertex, both sides share them.
    const std::vector<Vec3> triangle{{0, 0, 0}, {10, 0, 0}, {5.05f, 10, 0}};
    std::vector<Vec3> front, back;
    clipWindingAxial(triangle, 0, 5.0f, 0.125f, front, back);
    EXPECT_EQ(front.size(), 3u);
    EXPECT_EQ(back.size(), 3u);
    EXPECT_NEAR(windingArea(front) + windingArea(back), windingArea(triangle), 1e-3f);
}

struct TaggedVertex {
    Vec3 xyz;
    float tag = 0;
};

TEST(WindingOps, SplitInterpolatesAttributes) {
    const std::vector<TaggedVertex> w{{{0, 0, 0}, 0}, {{8, 0, 0}, 8}, {{8, 8, 0}, 16}, {{0, 8, 0}, 8}};
    const auto position = [](auto& v) -> auto& { return v.xyz; };
    const auto split = [](const TaggedVertex& a, const TaggedVertex& b, float t) {
        return TaggedVertex{lerp(a.xyz, b.xyz, t), a.tag + (b.tag - a.tag) * t};
    };
    std::vector<TaggedVertex> front, back;
    clipWindingAxial(w, 0, 2.0f, 0.125f, front, back, split, position);
    ASSERT_EQ(back.size(), 4u);
    // Every vertex's tag is x + y, so the new vertices at x = 2 carry 2 + y.
    for (const TaggedVertex& v : front) EXPECT_NEAR(v.tag, v.xyz.x + v.xyz.y, 1e-5f);
    for (const TaggedVertex& v : back) EXPECT_NEAR(v.tag, v.xyz.x + v.xyz.y, 1e-5f);
    EXPECT_NEAR(windingArea(back, position), 16.0f, 1e-5f);
}

}  // namespace
}  // namespace q3::light
