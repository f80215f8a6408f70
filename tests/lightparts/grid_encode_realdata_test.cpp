#include <gtest/gtest.h>

#include "bspfile.h"
#include "grid_encode.h"
#include "test_data.h"

namespace q3::light {
namespace {

// q3map2 wrote the shipped OpenArena BSPs: the engine drops a grid whose lump-15 length differs
// from numPoints * 8, so our layout must give exactly their point count.
TEST(GridEncodeRealData, PointCountsMatchShippedBsps) {
    const auto paths = test::allRealBsps();
    ASSERT_GE(paths.size(), 100u);
    int compared = 0;
    for (const auto& path : paths) {
        const bsp::Bsp bsp = bsp::readBsp(path);
        if (bsp.lightGrid.empty() || bsp.models.empty()) continue;
        const auto entities = bsp::parseEntities(bsp.entities, path.string());
        ASSERT_FALSE(entities.empty()) << path;
        const Vec3 requested = parseGridSize(entities[0].value("gridsize"), path.string());
        const GridLayout layout = computeGridLayout(requested, bsp);
        EXPECT_EQ(size_t(layout.numPoints()), bsp.lightGrid.size()) << path;
        // A grid q3map2 had to grow carries the grown size in worldspawn already.
        EXPECT_FALSE(layout.sizeChanged() && layout.growSteps > 0) << path;
        ++compared;
    }
    EXPECT_GE(compared, 100);
}

}  // namespace
}  // namespace q3::light
