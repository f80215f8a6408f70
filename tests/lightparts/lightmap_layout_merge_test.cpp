#include <gtest/gtest.h>

#include "lightmap_layout_merge.h"

namespace q3::light {
namespace {

SurfaceLightmapInput floorPiece(int index, float x0, float x1, float z = 0.0f) {
    SurfaceLightmapInput in;
    SurfaceGeometry& g = in.geometry;
    g.surfaceIndex = index;
    g.surfaceType = bsp::MST_PLANAR;
    g.positions = {{x0, 0, z}, {x1, 0, z}, {x1, 32, z}, {x0, 32, z}};
    g.normals.assign(4, Vec3{0, 0, 1});
    g.triangles = {0, 1, 2, 0, 2, 3};
    g.planeNormal = {0, 0, 1};
    in.traits.shader = "textures/test/floor";
    return in;
}

TEST(LightmapMerge, TouchingCoplanarSurfacesShareALightmap) {
    std::vector<SurfaceLightmapInput> in = {floorPiece(10, 0, 64), floorPiece(11, 64, 128)};
    const auto groups = groupSurfacesForLightmaps(in);
    ASSERT_EQ(groups.size(), 1u);
    // Larger minimum first, as q3map2 sorts.
    EXPECT_EQ(groups[0], (std::vector<size_t>{1, 0}));
    const auto lms = layoutMergedLightmaps(in, {});
    ASSERT_EQ(lms.size(), 1u);
    const RawLightmap& lm = lms[0];
    EXPECT_EQ(lm.surfaces, (std::vector<int>{11, 10}));
    EXPECT_EQ(lm.width, 9);   // 0..128
    EXPECT_EQ(lm.height, 3);  // 0..32
    ASSERT_EQ(lm.surfaceCoords.size(), 2u);
    EXPECT_FLOAT_EQ(lm.surfaceCoords[0][0][0], 4.5f);  // surface 11 starts at x = 64
    EXPECT_FLOAT_EQ(lm.surfaceCoords[1][0][0], 0.5f);
    EXPECT_EQ(lm.vertexCoords, lm.surfaceCoords[0]);
    int mapped = 0;
    for (const Luxel& l : lm.luxels) mapped += l.mapped;
    EXPECT_EQ(mapped, 9 * 3);  // s 0.5..8.5, t 0.5..2.5
}

TEST(LightmapMerge, ChainsAndSeparations) {
    // A chain of three touching pieces becomes one group; a piece with a gap stays alone.
    std::vector<SurfaceLightmapInput> chain = {floorPiece(0, 0, 64), floorPiece(1, 128, 192), floorPiece(2, 64, 128),
                                               floorPiece(3, 300, 400)};
    const auto groups = groupSurfacesForLightmaps(chain);
    ASSERT_EQ(groups.size(), 2u);
    EXPECT_EQ(groups[0], (std::vector<size_t>{3}));
    EXPECT_EQ(groups[1], (std::vector<size_t>{1, 2, 0}));

    auto separate = [](SurfaceLightmapInput a, SurfaceLightmapInput b) {
        std::vector<SurfaceLightmapInput> v = {std::move(a), std::move(b)};
        return groupSurfacesForLightmaps(v).size() == 2;
    };
    EXPECT_TRUE(separate(floorPiece(0, 0, 64), floorPiece(1, 64, 128, 8.0f)));  // another plane
    SurfaceLightmapInput other = floorPiece(1, 64, 128);
    other.traits.entity = 3;
    EXPECT_TRUE(separate(floorPiece(0, 0, 64), other));
    other = floorPiece(1, 64, 128);
    other.params.sampleSize = 8;
    EXPECT_TRUE(separate(floorPiece(0, 0, 64), other));
    other = floorPiece(1, 64, 128);
    other.traits.model = 1;
    EXPECT_TRUE(separate(floorPiece(0, 0, 64), other));
    other = floorPiece(1, 64, 128);
    other.traits.brightness = 2.0f;
    EXPECT_TRUE(separate(floorPiece(0, 0, 64), other));
    other = floorPiece(1, 64, 128);
    other.traits.shader = "textures/test/other";  // a different shader alone does not prevent sharing
    EXPECT_FALSE(separate(floorPiece(0, 0, 64), other));

    // q3map_lightmapMergable lets surfaces on different planes share when their axis matches.
    SurfaceLightmapInput lower = floorPiece(0, 0, 64), ramp = floorPiece(1, 64, 128);
    ramp.geometry.positions[1].z = ramp.geometry.positions[2].z = 8.0f;
    ramp.geometry.planeNormal = normalize(Vec3{-8, 0, 64});
    lower.params.axis = ramp.params.axis = {0, 0, 1};
    EXPECT_TRUE(separate(lower, ramp));
    ramp.traits.mergeable = true;
    EXPECT_FALSE(separate(lower, ramp));
}

TEST(LightmapMerge, CurvedPatchesStayAlone) {
    SurfaceLightmapInput patchIn;
    SurfaceGeometry& g = patchIn.geometry;
    g.surfaceIndex = 5;
    g.surfaceType = bsp::MST_PATCH;
    g.patchWidth = g.patchHeight = 3;
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 3; ++x) {
            g.positions.push_back({32.0f * float(x), 16.0f * float(y), x == 1 ? 32.0f : 0.0f});
            g.normals.push_back({0, 0, 1});
        }
    std::vector<SurfaceLightmapInput> in = {floorPiece(0, 0, 64), patchIn};
    EXPECT_EQ(groupSurfacesForLightmaps(in).size(), 2u);
    const auto lms = layoutMergedLightmaps(in, {});
    ASSERT_EQ(lms.size(), 2u);
    const std::vector<SurfaceGeometry> both = {in[0].geometry, patchIn.geometry};
    Log log(false);
    EXPECT_FALSE(layoutSurfaceGroup(std::vector<SurfaceGeometry>{patchIn.geometry, in[0].geometry}, {}, {}, &log).has_value());
    EXPECT_EQ(log.warningCount(), 1);
}

TEST(LightmapMerge, MergedSizeCanForceALargerSampleSize) {
    // Each piece fits a 128 page at 16 units, together (2048 units) they need 17.
    std::vector<SurfaceLightmapInput> in = {floorPiece(0, 0, 1024), floorPiece(1, 1024, 2048)};
    Log log(false);
    const auto lms = layoutMergedLightmaps(in, {}, &log);
    ASSERT_EQ(lms.size(), 1u);
    EXPECT_EQ(lms[0].sampleSize, 17);  // 17*ceil(2048/17) = 2057 -> 122 luxels; 16 -> 129
    EXPECT_EQ(log.warningCount(), 1);
}

}  // namespace
}  // namespace q3::light
