// Convex cells cut from boxes one half-space at a time: bounds, face planes and what a cut keeps.
#include <gtest/gtest.h>

#include "convex_cell.h"

namespace q3::light {
namespace {

TEST(ConvexCell, BoxHasSixFacesAndItsOwnBounds) {
    const ConvexCell box = ConvexCell::box({0, 0, 0}, {2, 3, 4});
    EXPECT_EQ(box.planes().size(), 6u);
    const DBounds b = box.bounds();
    EXPECT_EQ(b.mins, (DVec3{0, 0, 0}));
    EXPECT_EQ(b.maxs, (DVec3{2, 3, 4}));
    EXPECT_TRUE(ConvexCell::box({1, 0, 0}, {0, 1, 1}).empty());
}

TEST(ConvexCell, CutKeepsThePartBehindThePlane) {
    const ConvexCell box = ConvexCell::box({0, 0, 0}, {2, 2, 2});
    // x + y <= 1 leaves a prism over the corner triangle: the x = 2 and y = 2 faces are gone.
    const ConvexCell prism = box.clipped({1, 1, 0}, 1);
    ASSERT_FALSE(prism.empty());
    EXPECT_EQ(prism.planes().size(), 5u);
    const DBounds b = prism.bounds();
    EXPECT_NEAR(b.maxs.x, 1, 1e-12);
    EXPECT_NEAR(b.maxs.y, 1, 1e-12);
    EXPECT_NEAR(b.maxs.z, 2, 1e-12);
    EXPECT_NEAR(b.mins.x, 0, 1e-12);
    // A plane the cell lies behind changes nothing; one it lies in front of leaves nothing.
    EXPECT_TRUE(box.inside({1, 0, 0}, 2));
    EXPECT_FALSE(box.inside({1, 0, 0}, 1.5));
    EXPECT_EQ(box.clipped({1, 0, 0}, 5).planes().size(), 6u);  // a plane off the cell adds no face
    EXPECT_EQ(box.clipped({1, 0, 0}, 5).bounds().maxs, (DVec3{2, 2, 2}));
    EXPECT_TRUE(box.clipped({1, 0, 0}, -1).empty());
    // Cuts in turn: a unit cube left from the corner.
    const ConvexCell cube = box.clipped({1, 0, 0}, 1).clipped({0, 1, 0}, 1).clipped({0, 0, 1}, 1);
    EXPECT_EQ(cube.planes().size(), 6u);
    EXPECT_EQ(cube.bounds().maxs, (DVec3{1, 1, 1}));
}

}  // namespace
}  // namespace q3::light
