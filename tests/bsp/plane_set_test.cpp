#include <gtest/gtest.h>

#include "plane_set.h"

namespace q3::bspstage {
namespace {

TEST(PlaneSet, PairsAreFlippedTwinsWithPositiveAxialPlanesEven) {
    PlaneSet planes;
    const int negativeX = planes.find({DVec3{-1, 0, 0}, -64});
    EXPECT_EQ(negativeX, 1);  // its positive twin takes index 0
    EXPECT_EQ(planes.size(), 2);
    EXPECT_EQ(planes[0].normal(), (DVec3{1, 0, 0}));
    EXPECT_DOUBLE_EQ(planes[0].dist(), 64);
    EXPECT_EQ(planes[1].normal(), (DVec3{-1, 0, 0}));
    EXPECT_DOUBLE_EQ(planes[1].dist(), -64);
    EXPECT_EQ(planes[0].type, PlaneX);

    const DVec3 slanted = normalize(DVec3{1, 1, 0});
    const int s = planes.find({-slanted, 10});
    EXPECT_EQ(s, 2);  // non-axial: the plane asked for is the even one
    EXPECT_EQ(planes[3].type, PlaneNonAxial);
    EXPECT_EQ(planes.find({slanted, -10}), 3);
}

TEST(PlaneSet, MatchesWithinEpsilonsOnly) {
    PlaneSet planes;
    const int a = planes.find({DVec3{0, 0, 1}, 128});
    EXPECT_EQ(planes.find({DVec3{0, 0, 1}, 128.004}), a);  // snapped to the integer
    const int farther = planes.find({DVec3{0, 0, 1}, 128.3});
    EXPECT_EQ(farther, 2);
    EXPECT_EQ(planes.size(), 4);
}

TEST(PlaneSet, SnapsNearAxialNormalsAndIntegerDistances) {
    DVec3 n = normalize(DVec3{0.0001, 0.0002, 1});
    EXPECT_TRUE(snapNormal(n, 0.00005));
    EXPECT_EQ(n, (DVec3{0, 0, 1}));

    DVec3 slanted = normalize(DVec3{1, 1, 0.00001});
    EXPECT_TRUE(snapNormal(slanted, 0.00005));
    EXPECT_EQ(slanted.z, 0);
    DVec3 clean = normalize(DVec3{1, 2, 3});
    EXPECT_FALSE(snapNormal(clean, 0.00005));

    DPlane p{DVec3{1, 0, 0}, 31.996};
    snapPlane(p, {}, PlaneEpsilons{});
    EXPECT_EQ(p.dist, 32);
    DPlane off{DVec3{1, 0, 0}, 31.99};
    snapPlane(off, {}, PlaneEpsilons{});
    EXPECT_DOUBLE_EQ(off.dist, 31.99);
}

TEST(PlaneSet, NeighbouringHashBinsAreSearched) {
    PlaneSet planes;
    // 8191.998 and 8192.001 hash to bins 8191 and 0 (8192 & 8191): still found through the wrap.
    const int a = planes.find({normalize(DVec3{1, 1, 0}), 8191.998});
    EXPECT_EQ(planes.find({normalize(DVec3{1, 1, 0}), 8192.001}), a);
}

TEST(PlaneSet, RejectsPointsOffTheCandidate) {
    PlaneSet planes;
    const int a = planes.find({DVec3{0, 0, 1}, 0});
    const DVec3 near[1] = {{5, 5, 0.001}};
    EXPECT_EQ(planes.find({DVec3{0, 0, 1}, 0}, near), a);
    EXPECT_EQ(planes.fromPoints({0, 0, 0}, {0, 1, 0}, {1, 0, 0}), a);      // normal (c - a) x (b - a): up
    EXPECT_EQ(planes.fromPoints({0, 0, 0}, {1, 0, 0}, {0, 1, 0}), a ^ 1);  // faces down
    EXPECT_EQ(planes.fromPoints({0, 0, 0}, {1, 1, 1}, {1, 1, 1}), -1);     // degenerate
    const DVec3 far[1] = {{5, 5, 0.01}};
    EXPECT_NE(planes.find({DVec3{0, 0, 1}, 0}, far), a);  // the point is beyond the distance epsilon
}

}  // namespace
}  // namespace q3::bspstage
