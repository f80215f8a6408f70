#include <gtest/gtest.h>

#include "winding.h"

namespace q3::bspstage {
namespace {

Winding square(double size, double z = 0) {
    // Clockwise seen from +Z, like a q3map2 winding on a floor.
    return {{0, size, z}, {size, size, z}, {size, 0, z}, {0, 0, z}};
}

TEST(Winding, BaseWindingLiesOnItsPlaneAndFacesIt) {
    const DPlane plane{normalize(DVec3{1, 2, 3}), 50};
    // The float base winding is q3map2's: its corners, 2^17 units out, are off the plane by up to
    // about 0.01 (float spacing there is 0.0156); the one fitted to bounds stays on it.
    const DBounds bounds{{-40, -60, -80}, {40, 60, 80}};
    const std::pair<Winding, double> windings[] = {{baseWindingForPlane(plane), 0.02},
                                                   {baseWindingForPlaneInBounds(plane, bounds), 1e-9}};
    for (const auto& [w, tolerance] : windings) {
        ASSERT_EQ(w.size(), 4u);
        for (const DVec3& p : w) EXPECT_NEAR(plane.distanceTo(p), 0, tolerance);
        EXPECT_GT(dot(windingPlane(w).normal, plane.normal), 0.999);
    }
    EXPECT_GT(windingArea(windings[0].first), 1e10);
    // Axial planes stay exact in both.
    for (const DVec3& p : baseWindingForPlane({DVec3{0, 0, 1}, 100})) EXPECT_EQ(p.z, 100);
}

// The winding fitted to a brush's box is that box's face, starting at the corner q3map2's starts
// at: the first point decides where every face of a box brush begins.
TEST(Winding, BaseWindingInBoundsStartsAtQ3map2sCorner) {
    const DBounds box{{100, 150, 50}, {180, 260, 90}};
    struct Case {
        DVec3 normal;
        double dist;
        DVec3 first, second;
    };
    const Case cases[] = {
        {{-1, 0, 0}, -100, {100, 150, 90}, {100, 150, 50}}, {{1, 0, 0}, 180, {180, 260, 90}, {180, 260, 50}},
        {{0, -1, 0}, -150, {180, 150, 50}, {100, 150, 50}}, {{0, 1, 0}, 260, {180, 260, 90}, {100, 260, 90}},
        {{0, 0, -1}, -50, {100, 260, 50}, {100, 150, 50}},  {{0, 0, 1}, 90, {180, 260, 90}, {180, 150, 90}},
    };
    for (const Case& c : cases) {
        const Winding w = baseWindingForPlaneInBounds({c.normal, c.dist}, box);
        ASSERT_EQ(w.size(), 4u);
        EXPECT_EQ(w[0], c.first) << c.normal.x << " " << c.normal.y << " " << c.normal.z;
        EXPECT_EQ(w[1], c.second) << c.normal.x << " " << c.normal.y << " " << c.normal.z;
        EXPECT_GT(dot(windingPlane(w).normal, c.normal), 0.999);  // clockwise seen from the front
    }
    EXPECT_TRUE(baseWindingForPlaneInBounds({DVec3{0, 0, 1}, 0}, DBounds{}).empty());
}

TEST(Winding, ChopKeepsTheFront) {
    Winding w = square(64);
    chopWindingInPlace(w, {DVec3{1, 0, 0}, 16}, 0);
    ASSERT_EQ(w.size(), 4u);
    EXPECT_DOUBLE_EQ(windingArea(w), 48 * 64);
    EXPECT_DOUBLE_EQ(windingBounds(w).mins.x, 16);
    chopWindingInPlace(w, {DVec3{1, 0, 0}, 100}, 0);
    EXPECT_TRUE(w.empty());
}

TEST(Winding, StrictClipOfAWindingOnThePlaneGivesNothing) {
    const Winding w = square(64);
    auto [front, back] = clipWindingStrict(w, {DVec3{0, 0, 1}, 0}, 0.1);
    EXPECT_TRUE(front.empty());
    EXPECT_TRUE(back.empty());
    auto [f2, b2] = clipWinding(w, {DVec3{0, 0, 1}, 0}, 0.1);
    EXPECT_TRUE(f2.empty());
    EXPECT_EQ(b2, w);
    auto [f3, b3] = clipWindingStrict(w, {DVec3{0, 1, 0}, 32}, 0.1);
    EXPECT_DOUBLE_EQ(windingArea(f3), 32 * 64);
    EXPECT_DOUBLE_EQ(windingArea(b3), 32 * 64);
}

TEST(Winding, SideTestsUseTheOnEpsilon) {
    const Winding w = square(64);
    EXPECT_EQ(windingOnPlaneSide(w, {DVec3{0, 0, 1}, 0.05}), PlaneSide::On);
    EXPECT_EQ(windingOnPlaneSide(w, {DVec3{0, 0, 1}, -0.2}), PlaneSide::Front);
    EXPECT_EQ(windingOnPlaneSide(w, {DVec3{0, 0, 1}, 0.2}), PlaneSide::Back);
    EXPECT_EQ(windingOnPlaneSide(w, {DVec3{1, 0, 0}, 10}), PlaneSide::Cross);
}

TEST(Winding, TinyMeansFewerThanThreeLongEdges) {
    EXPECT_FALSE(windingIsTiny(square(1)));
    EXPECT_TRUE(windingIsTiny(square(0.15)));
    const Winding sliver{{0, 0, 0}, {64, 0, 0}, {64, 0.1, 0}, {0, 0.1, 0}};
    EXPECT_TRUE(windingIsTiny(sliver));
}

TEST(Winding, WeldPrefersIntegers) {
    Winding w{{0, 0, 0}, {10.004, 0, 0}, {10.05, 0.02, 0}, {10, 10, 0}};
    weldShortEdges(w);
    ASSERT_EQ(w.size(), 3u);
    EXPECT_EQ(w[1], (DVec3{10, 0, 0}));
}

TEST(Winding, ConvexHullGrowsToCoverBothPieces) {
    Winding hull;
    const DVec3 up{0, 0, 1};
    addWindingToConvexHull(square(32), hull, up);
    EXPECT_EQ(hull.size(), 4u);
    Winding shifted = square(32);
    for (DVec3& p : shifted) p.x += 32;
    addWindingToConvexHull(shifted, hull, up);
    EXPECT_DOUBLE_EQ(windingArea(hull), 64 * 32);
    EXPECT_EQ(windingBounds(hull).maxs.x, 64);
    EXPECT_GT(dot(windingPlane(hull).normal, up), 0.999);  // orientation kept
    // A piece inside changes nothing.
    const Winding before = hull;
    Winding inner{{10, 20, 0}, {20, 20, 0}, {20, 10, 0}};
    addWindingToConvexHull(inner, hull, up);
    EXPECT_EQ(hull, before);
}

TEST(Winding, CoplanarOverlap) {
    const DVec3 up{0, 0, 1};
    Winding other = square(32);
    for (DVec3& p : other) p.x += 16;
    EXPECT_TRUE(coplanarWindingsIntersect(square(32), other, up));
    for (DVec3& p : other) p.x += 16;  // now only touching along x = 32
    EXPECT_FALSE(coplanarWindingsIntersect(square(32), other, up));
}

}  // namespace
}  // namespace q3::bspstage
