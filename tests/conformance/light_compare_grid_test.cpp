// The light grid figures: the agreement mask of two reference runs, totals, correlations and
// direction decoding.
#include <gtest/gtest.h>

#include <cmath>

#include "light_compare.h"

namespace q3::conformance {
namespace {

bsp::GridPoint point(uint8_t ambient, uint8_t directed, uint8_t lng = 0, uint8_t lat = 0) {
    bsp::GridPoint p{};
    p.ambient[0] = p.ambient[1] = p.ambient[2] = ambient;
    p.directed[0] = p.directed[1] = p.directed[2] = directed;
    p.latLong[0] = lng;
    p.latLong[1] = lat;
    return p;
}

// Ten points with varied light, pointing various ways.
std::vector<bsp::GridPoint> referenceGrid() {
    std::vector<bsp::GridPoint> g;
    for (int i = 0; i < 10; ++i) g.push_back(point(uint8_t(10 + 7 * i), uint8_t(20 + 11 * i), uint8_t(i * 9), uint8_t(i * 25)));
    return g;
}

TEST(LightCompareGrid, DirectionsDecodeAsIoquake3) {
    const Vec3 up = gridDirection(point(0, 0, 0, 0));
    EXPECT_NEAR(up.z, 1, 1e-6);
    const Vec3 east = gridDirection(point(0, 0, 64, 0));  // 90 degrees from +z, azimuth 0
    EXPECT_NEAR(east.x, 1, 1e-6);
    EXPECT_NEAR(east.z, 0, 1e-6);
    const Vec3 north = gridDirection(point(0, 0, 64, 64));
    EXPECT_NEAR(north.y, 1, 1e-6);
    const Vec3 down = gridDirection(point(0, 0, 128, 17));
    EXPECT_NEAR(down.z, -1, 1e-6);
}

TEST(LightCompareGrid, AgreementAllowsTwoPerByteOnLightOnly) {
    bsp::GridPoint a = point(100, 50, 3, 4);
    bsp::GridPoint b = a;
    b.ambient[1] += 2;
    b.directed[2] -= 2;
    b.latLong[0] = 200;  // directions are not part of the agreement test
    EXPECT_TRUE(gridPointsAgree(a, b));
    b.ambient[0] += 3;
    EXPECT_FALSE(gridPointsAgree(a, b));
    bsp::GridPoint c = a;
    c.directed[0] += 3;
    EXPECT_FALSE(gridPointsAgree(a, c));
}

TEST(LightCompareGrid, IdenticalGridsGiveOnes) {
    const std::vector<bsp::GridPoint> ref = referenceGrid();
    const GridFigures f = compareGrids(ref, ref, &ref);
    EXPECT_TRUE(f.countsMatch);
    EXPECT_TRUE(f.masked);
    EXPECT_EQ(f.agreed.points, 10);
    for (const GridStats* s : {&f.all, &f.agreed}) {
        EXPECT_NEAR(s->ambientRatio, 1, 1e-12);
        EXPECT_NEAR(s->directedRatio, 1, 1e-12);
        EXPECT_NEAR(s->ambientCorrelation, 1, 1e-12);
        EXPECT_NEAR(s->directedCorrelation, 1, 1e-12);
        EXPECT_EQ(s->directionPoints, 10);  // every directed sum is >= 60
        EXPECT_NEAR(s->directionFraction, 1, 1e-12);
    }
}

TEST(LightCompareGrid, MaskDropsPointsTheReferenceDoesNotRepeat) {
    const std::vector<bsp::GridPoint> ref = referenceGrid();
    std::vector<bsp::GridPoint> ref2 = ref;
    ref2[3].ambient[0] += 10;  // the reference is not repeatable at point 3
    std::vector<bsp::GridPoint> ours = ref;
    ours[3] = point(250, 250, 128, 128);  // ours differs there only
    const GridFigures f = compareGrids(ref, ours, &ref2);
    EXPECT_EQ(f.agreed.points, 9);
    EXPECT_NEAR(f.agreed.ambientRatio, 1, 1e-12);
    EXPECT_NEAR(f.agreed.directedCorrelation, 1, 1e-12);
    EXPECT_NEAR(f.agreed.directionFraction, 1, 1e-12);
    EXPECT_EQ(f.all.points, 10);
    EXPECT_GT(f.all.ambientRatio, 1.1);
    EXPECT_LT(f.all.directionFraction, 1.0);
}

TEST(LightCompareGrid, MaskDropsPointsTheReferenceNeverPlaced) {
    // Both reference runs agree that point 5 is empty (their random searches out of solid both gave
    // up); ours placed and lit it. The mask leaves it out; the unmasked figures keep it.
    std::vector<bsp::GridPoint> ref = referenceGrid();
    ref[5] = bsp::GridPoint{};
    EXPECT_FALSE(gridPointPlaced(ref[5]));
    EXPECT_TRUE(gridPointPlaced(point(0, 0, 128, 0)));  // placed but unlit: kept
    std::vector<bsp::GridPoint> ours = referenceGrid();
    const GridFigures f = compareGrids(ref, ours, &ref);
    EXPECT_EQ(f.agreed.points, 9);
    EXPECT_NEAR(f.agreed.ambientRatio, 1, 1e-12);
    EXPECT_EQ(f.all.points, 10);
    EXPECT_GT(f.all.ambientRatio, 1.0);
}

TEST(LightCompareGrid, TotalsScaleAndDirectionsNeedEnoughLight) {
    std::vector<bsp::GridPoint> ref = referenceGrid();
    std::vector<bsp::GridPoint> ours = ref;
    for (bsp::GridPoint& p : ours) {
        for (int c = 0; c < 3; ++c) p.directed[c] = uint8_t(p.directed[c] / 2);
        p.latLong[0] = uint8_t(p.latLong[0] + 64);  // 90 degrees off
    }
    ref[0] = point(10, 9, 0, 0);  // directed sum 27 < 30: no direction check here
    ours[0] = point(10, 4, 64, 0);
    const GridFigures f = compareGrids(ref, ours, nullptr);
    EXPECT_FALSE(f.masked);
    EXPECT_NEAR(f.all.ambientRatio, 1, 1e-12);
    EXPECT_NEAR(f.all.directedRatio, 0.5, 0.02);
    EXPECT_EQ(f.all.directionPoints, 9);
    EXPECT_NEAR(f.all.directionFraction, 0, 1e-12);
}

TEST(LightCompareGrid, DifferentCountsAreNotCompared) {
    const std::vector<bsp::GridPoint> ref = referenceGrid();
    std::vector<bsp::GridPoint> ours = ref;
    ours.pop_back();
    const GridFigures f = compareGrids(ref, ours, &ref);
    EXPECT_FALSE(f.countsMatch);
    EXPECT_EQ(f.referencePoints, 10);
    EXPECT_EQ(f.oursPoints, 9);
    EXPECT_EQ(f.all.points, 0);
    // A second reference run with another count gives no mask but still the unmasked figures.
    std::vector<bsp::GridPoint> shortRef2 = ref;
    shortRef2.pop_back();
    const GridFigures g = compareGrids(ref, ref, &shortRef2);
    EXPECT_FALSE(g.masked);
    EXPECT_EQ(g.all.points, 10);
}

TEST(LightCompareGrid, PearsonBasics) {
    EXPECT_NEAR(pearson({1, 2, 3}, {2, 4, 6}), 1, 1e-12);
    EXPECT_NEAR(pearson({1, 2, 3}, {3, 2, 1}), -1, 1e-12);
    EXPECT_TRUE(std::isnan(pearson({1, 1, 1}, {1, 2, 3})));
    EXPECT_TRUE(std::isnan(pearson({1}, {1})));
}

}  // namespace
}  // namespace q3::conformance
