#include <gtest/gtest.h>

#include <bit>
#include <random>

#include "lightmap_layout.h"
#include "lightmap_layout_mapping.h"

namespace q3::light {
namespace {

// Bitwise: a sign of zero or a last bit that differs would show in the lit output.
bool sameBits(Vec3 a, Vec3 b) {
    return std::bit_cast<std::array<uint32_t, 3>>(a) == std::bit_cast<std::array<uint32_t, 3>>(b);
}

// Overlapping triangles of every shape (slivers, long diagonals, some running off the grid) on a
// 40 x 24 luxel floor, all with one normal.
MappingSurface scatteredTriangles(Vec3 normal, uint32_t seed) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<float> s(-1.0f, 41.0f), t(-1.0f, 25.0f);
    MappingSurface surface;
    for (uint32_t i = 0; i < 3 * 60; ++i) {
        const float vs = s(random), vt = t(random);
        surface.verts.push_back({{vs, vt}, {vs * 16.0f, vt * 16.0f, 0.0f}, normal});
        surface.triangles.push_back(i);
    }
    return surface;
}

RawLightmap floorLightmap() {
    SurfaceGeometry g;
    g.surfaceType = bsp::MST_PLANAR;
    g.positions = {{0, 0, 0}, {640, 0, 0}, {640, 384, 0}, {0, 384, 0}};
    g.normals.assign(4, {0, 0, 1});
    g.triangles = {0, 1, 2, 0, 2, 3};
    g.planeNormal = {0, 0, 1};
    const std::optional<RawLightmap> lm = layoutSurfaceLightmap(g, {}, {});
    EXPECT_TRUE(lm.has_value());
    return lm.value_or(RawLightmap{});
}

TEST(LuxelMapping, OneAxialNormalMapsAsTheFullSplit) {
    // With one axial normal everywhere the mapper skips splits whose points can only land on luxels
    // already mapped; a vertex with another normal (and no triangle) makes it split everything.
    for (uint32_t seed = 1; seed <= 4; ++seed) {
        const MappingSurface triangles = scatteredTriangles({0, 0, 1}, seed);
        MappingSurface otherNormal;
        otherNormal.verts.push_back({{0.5f, 0.5f}, {8, 8, 0}, {0, 0.6f, 0.8f}});
        RawLightmap skipping = floorLightmap(), full = floorLightmap();
        ASSERT_GT(skipping.luxels.size(), 0u);
        mapSurfacesOntoLuxels(skipping, std::span(&triangles, 1));
        const std::array<MappingSurface, 2> both{triangles, otherNormal};
        mapSurfacesOntoLuxels(full, both);
        int mapped = 0;
        for (size_t i = 0; i < full.luxels.size(); ++i) {
            const Luxel& a = skipping.luxels[i];
            const Luxel& b = full.luxels[i];
            ASSERT_EQ(a.mapped, b.mapped) << seed << " " << i;
            mapped += a.mapped;
            if (!a.mapped) continue;
            EXPECT_TRUE(sameBits(a.origin, b.origin)) << seed << " " << i;
            EXPECT_TRUE(sameBits(a.normal, b.normal)) << seed << " " << i;
            EXPECT_TRUE(sameBits(a.surfacePoint, b.surfacePoint)) << seed << " " << i;
            EXPECT_TRUE(sameBits(a.faceNormal, b.faceNormal)) << seed << " " << i;
        }
        EXPECT_GT(mapped, 200) << seed;
        EXPECT_LT(mapped, int(full.luxels.size())) << seed;
    }
}

}  // namespace
}  // namespace q3::light
