#include <gtest/gtest.h>

#include <cmath>

#include "lightmap_layout.h"

namespace q3::light {
namespace {

SurfaceGeometry quad(Vec3 a, Vec3 b, Vec3 c, Vec3 d, Vec3 normal) {
    SurfaceGeometry g;
    g.surfaceIndex = 7;
    g.surfaceType = bsp::MST_PLANAR;
    g.positions = {a, b, c, d};
    g.normals = {normal, normal, normal, normal};
    g.triangles = {0, 1, 2, 0, 2, 3};
    g.planeNormal = normal;
    return g;
}

SurfaceGeometry floorQuad() { return quad({0, 0, 0}, {100, 0, 0}, {100, 50, 0}, {0, 50, 0}, {0, 0, 1}); }

int mappedCount(const RawLightmap& lm) {
    int n = 0;
    for (const Luxel& l : lm.luxels) n += l.mapped;
    return n;
}

TEST(LightmapLayout, ResolveSampleSizeAndLightmappedSurfaces) {
    EXPECT_EQ(resolveSampleSize(true, 8, 32, 16, 0), 8);     // the .srf already resolved it
    EXPECT_EQ(resolveSampleSize(false, 8, 32, 16, 0), 32);   // no .srf: the shader's value
    EXPECT_EQ(resolveSampleSize(false, 8, 0, 16, 0), 16);    // else -samplesize
    EXPECT_EQ(resolveSampleSize(false, 8, 0, 16, 2), 32);    // times -samplescale
    EXPECT_EQ(resolveSampleSize(true, 0, 0, 4, 0), 4);
    bsp::Surface s{};
    s.surfaceType = bsp::MST_PLANAR;
    s.lightmapNum = 0;
    EXPECT_TRUE(isLightmappedSurface(s, false));
    EXPECT_FALSE(isLightmappedSurface(s, true));
    s.lightmapNum = bsp::kLightmapByVertex;  // fresh from -bsp: the file's value does not decide
    EXPECT_TRUE(isLightmappedSurface(s, false));
    s.surfaceType = bsp::MST_PATCH;
    EXPECT_TRUE(isLightmappedSurface(s, false));
    s.lightmapNum = 0;
    s.surfaceType = bsp::MST_FLARE;
    EXPECT_FALSE(isLightmappedSurface(s, false));
    s.surfaceType = bsp::MST_TRIANGLE_SOUP;  // q3map2 vertex-lights soups, whatever the file held
    EXPECT_FALSE(isLightmappedSurface(s, false));
    s.surfaceType = bsp::MST_FOLIAGE;
    EXPECT_FALSE(isLightmappedSurface(s, false));
}

TEST(LightmapLayout, PlanarFloor) {
    const auto lm = layoutSurfaceLightmap(floorQuad(), {}, {});
    ASSERT_TRUE(lm.has_value());
    EXPECT_EQ(lm->axisNum, 2);
    EXPECT_TRUE(lm->planar);
    EXPECT_EQ(lm->sampleSize, 16);
    // x: 0..112 -> 8 luxels, y: 0..64 -> 5 luxels
    EXPECT_EQ(lm->width, 8);
    EXPECT_EQ(lm->height, 5);
    EXPECT_EQ(lm->origin, (Vec3{0, 0, 0}));
    EXPECT_EQ(lm->vecs[0], (Vec3{16, 0, 0}));
    EXPECT_EQ(lm->vecs[1], (Vec3{0, 16, 0}));
    EXPECT_EQ(lm->vecs[2], (Vec3{0, 0, 1}));
    ASSERT_EQ(lm->vertexCoords.size(), 4u);
    EXPECT_FLOAT_EQ(lm->vertexCoords[0][0], 0.5f);
    EXPECT_FLOAT_EQ(lm->vertexCoords[0][1], 0.5f);
    EXPECT_FLOAT_EQ(lm->vertexCoords[2][0], 100.0f / 16.0f + 0.5f);
    EXPECT_FLOAT_EQ(lm->vertexCoords[2][1], 50.0f / 16.0f + 0.5f);
    // Luxels whose square touches the surface (s 0.5..6.75, t 0.5..3.625): 7 x 4.
    EXPECT_EQ(mappedCount(*lm), 28);
    EXPECT_TRUE(lm->luxel(0, 0).mapped);
    EXPECT_EQ(lm->luxel(0, 0).origin, (Vec3{0, 0, 1}));  // pushed 1 unit off along the normal
    EXPECT_EQ(lm->luxel(6, 3).origin, (Vec3{96, 48, 1}));
    EXPECT_EQ(lm->luxel(6, 3).normal, (Vec3{0, 0, 1}));
    EXPECT_FALSE(lm->luxel(7, 0).mapped);
    EXPECT_FALSE(lm->luxel(0, 4).mapped);
}

TEST(LightmapLayout, WallProjectsAlongX) {
    const auto lm = layoutSurfaceLightmap(quad({10, 0, 0}, {10, 64, 0}, {10, 64, 32}, {10, 0, 32}, {1, 0, 0}), {}, {});
    ASSERT_TRUE(lm.has_value());
    EXPECT_EQ(lm->axisNum, 0);
    EXPECT_EQ(lm->width, 5);   // along y
    EXPECT_EQ(lm->height, 3);  // along z
    EXPECT_EQ(lm->origin, (Vec3{10, 0, 0}));
    EXPECT_EQ(lm->vecs[0], (Vec3{0, 16, 0}));
    EXPECT_EQ(lm->vecs[1], (Vec3{0, 0, 16}));
    EXPECT_EQ(lm->luxel(2, 1).origin, (Vec3{11, 32, 16}));
    // A 45 degree tie between x and z goes to z (q3map2's z bias).
    const float h = std::sqrt(0.5f);
    const auto tie = layoutSurfaceLightmap(quad({0, 0, 0}, {0, 64, 0}, {-32, 64, 32}, {-32, 0, 32}, {h, 0, h}), {}, {});
    ASSERT_TRUE(tie.has_value());
    EXPECT_EQ(tie->axisNum, 2);
}

TEST(LightmapLayout, SlopedPlaneLuxelsLieOnThePlane) {
    const Vec3 n = normalize(Vec3{0, -1, 2});  // mostly facing up
    // Plane through (0,0,10): z = 10 + y/2
    const auto g = quad({0, 0, 10}, {64, 0, 10}, {64, 64, 42}, {0, 64, 42}, n);
    SurfaceLightmapParams params;
    params.sampleOffset = 2.0f;
    const auto lm = layoutSurfaceLightmap(g, params, {});
    ASSERT_TRUE(lm.has_value());
    EXPECT_EQ(lm->axisNum, 2);
    const float d = dot(Vec3{0, 0, 10}, n);
    EXPECT_NEAR(dot(lm->origin, n), d, 1e-4f);
    EXPECT_NEAR(dot(lm->vecs[0], n), 0.0f, 1e-5f);
    EXPECT_NEAR(dot(lm->vecs[1], n), 0.0f, 1e-5f);
    EXPECT_NEAR(lm->vecs[1].x, 0.0f, 1e-6f);
    EXPECT_NEAR(lm->vecs[1].y, 16.0f, 1e-6f);  // one luxel along t is 16 units of y, climbing 8 in z
    EXPECT_NEAR(lm->vecs[1].z, 8.0f, 1e-5f);
    // The sample offset pushes along the projection axis (z), not along the normal.
    int checked = 0;
    for (const Luxel& l : lm->luxels) {
        if (!l.mapped) continue;
        EXPECT_NEAR(dot(l.origin, n) - d, 2.0f * n.z, 1e-3f);
        EXPECT_NEAR(dot(l.origin - Vec3{0, 0, 2}, n) - d, 0.0f, 1e-3f);
        ++checked;
    }
    EXPECT_EQ(checked, 5 * 5);
}

TEST(LightmapLayout, ForcedAxisFromTheSrf) {
    // A steep slope whose own dominant axis is x; the .srf forces a z projection.
    const Vec3 n = normalize(Vec3{1.2f, 0, 1});
    const auto g = quad({0, 0, 0}, {0, 64, 0}, {-40, 64, 48}, {-40, 0, 48}, n);
    EXPECT_EQ(layoutSurfaceLightmap(g, {}, {})->axisNum, 0);
    SurfaceLightmapParams params;
    params.axis = {0, 0, 1};
    const auto lm = layoutSurfaceLightmap(g, params, {});
    ASSERT_TRUE(lm.has_value());
    EXPECT_EQ(lm->axisNum, 2);
    EXPECT_EQ(lm->width, 4);   // x -48..0
    EXPECT_EQ(lm->height, 5);  // y 0..64
    EXPECT_NEAR(dot(lm->vecs[0], n), 0.0f, 1e-5f);
    for (const Luxel& l : lm->luxels)
        if (l.mapped) {
            EXPECT_NEAR(dot(l.origin, n), n.z, 1e-3f);  // one unit up the forced z axis
        }

    // An axis lying in the plane cannot project onto it: no NaNs, and nothing maps (the surface is a
    // line in lightmap space).
    SurfaceLightmapParams inPlane;
    inPlane.axis = {0, 1, 0};
    const auto flat = layoutSurfaceLightmap(floorQuad(), inPlane, {});
    ASSERT_TRUE(flat.has_value());
    EXPECT_EQ(flat->axisNum, 1);
    EXPECT_EQ(flat->height, 1);
    EXPECT_FALSE(flat->planar);
    EXPECT_TRUE(isFinite(flat->origin));
    EXPECT_EQ(mappedCount(*flat), 0);
}

TEST(LightmapLayout, SampleSizeGrowsToFitThePage) {
    Log log(false);
    const auto lm = layoutSurfaceLightmap(quad({0, 0, 0}, {3000, 0, 0}, {3000, 64, 0}, {0, 64, 0}, {0, 0, 1}), {}, {}, &log);
    ASSERT_TRUE(lm.has_value());
    // ceil(3000/23) + 1 = 132 > 128, ceil(3000/24) + 1 = 126 fits.
    EXPECT_EQ(lm->requestedSampleSize, 16);
    EXPECT_EQ(lm->sampleSize, 24);
    EXPECT_EQ(lm->width, 126);
    EXPECT_EQ(log.warningCount(), 1);
    // A larger page needs no growth.
    LayoutOptions big;
    big.pageSize = 256;
    const auto lm2 = layoutSurfaceLightmap(quad({0, 0, 0}, {3000, 0, 0}, {3000, 64, 0}, {0, 64, 0}, {0, 0, 1}), {}, big, &log);
    EXPECT_EQ(lm2->sampleSize, 16);
    EXPECT_EQ(lm2->width, 189);
    EXPECT_EQ(log.warningCount(), 1);
    // -rawlightmapsizelimit also forces growth (without the warning).
    LayoutOptions limited;
    limited.rawSizeLimit = 4;
    const auto lm3 = layoutSurfaceLightmap(floorQuad(), {}, limited, &log);
    EXPECT_EQ(lm3->sampleSize, 34);  // 34*ceil(100/34) = 102 -> 4 luxels; 33 -> 5
    EXPECT_EQ(lm3->width, 4);
    EXPECT_EQ(log.warningCount(), 1);
}

TEST(LightmapLayout, SurfacesThatCanNeverFitAreRejected) {
    // Straddling x = 0: at least 3 luxels wide at any sample size, so a 2-luxel page never fits.
    SurfaceLightmapParams params;
    params.pageWidth = params.pageHeight = 2;
    Log log(false);
    EXPECT_FALSE(layoutSurfaceLightmap(quad({-8, 0, 0}, {8, 0, 0}, {8, 8, 0}, {-8, 8, 0}, {0, 0, 1}), params, {}, &log).has_value());
    EXPECT_EQ(log.warningCount(), 1);  // the rejection
}

TEST(LightmapLayout, SuperSampling) {
    LayoutOptions o;
    o.superSample = 2;
    const auto lm = layoutSurfaceLightmap(floorQuad(), {}, o);
    ASSERT_TRUE(lm.has_value());
    EXPECT_EQ(lm->superWidth(), 16);
    EXPECT_EQ(lm->superHeight(), 10);
    EXPECT_FALSE(lm->luxel(0, 0).mapped);  // covers s 0..0.5, the surface starts at 0.5
    EXPECT_TRUE(lm->luxel(1, 1).mapped);
    EXPECT_EQ(lm->luxel(1, 1).origin, (Vec3{4, 4, 1}));  // centre s = 0.75 -> 0.25 luxel -> 4 units
    EXPECT_EQ(lm->luxel(2, 1).origin, (Vec3{12, 4, 1}));
    // The BSP-luxel coordinates of vertices do not change with -super.
    EXPECT_FLOAT_EQ(lm->vertexCoords[2][0], 6.75f);
    // Super-sampling is clamped to 8.
    o.superSample = 20;
    EXPECT_EQ(layoutSurfaceLightmap(floorQuad(), {}, o)->superSample, 8);
}

// 3x3 patch arching over x: columns at x = 0, 64, 128 with control heights 0, 64, 0.
SurfaceGeometry archPatch() {
    SurfaceGeometry g;
    g.surfaceIndex = 3;
    g.surfaceType = bsp::MST_PATCH;
    g.patchWidth = 3;
    g.patchHeight = 3;
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 3; ++x) {
            g.positions.push_back({64.0f * float(x), 32.0f * float(y), x == 1 ? 64.0f : 0.0f});
            g.normals.push_back(normalize(Vec3{float(1 - x), 0, 1}));
        }
    return g;
}

TEST(LightmapLayout, CurvedPatch) {
    const auto lm = layoutSurfaceLightmap(archPatch(), {}, {});
    ASSERT_TRUE(lm.has_value());
    EXPECT_EQ(lm->axisNum, -1);
    EXPECT_FALSE(lm->planar);
    // Columns 90.51 apart twice: ceil(181.02/16) + 1 = 13; rows: 64/16 + 1 = 5.
    EXPECT_EQ(lm->width, 13);
    EXPECT_EQ(lm->height, 5);
    ASSERT_EQ(lm->vertexCoords.size(), 9u);
    EXPECT_FLOAT_EQ(lm->vertexCoords[4][0], 6.5f);  // sBasis 6 * 1 + 0.5
    EXPECT_FLOAT_EQ(lm->vertexCoords[4][1], 2.5f);  // tBasis 2 * 1 + 0.5
    EXPECT_EQ(mappedCount(*lm), 65);
    // Curved luxels sample at the first point mapped into them, pushed off along the plane of the
    // quad it came from (the left facet of the control grid, (-1, 0, 1) / sqrt 2), not its normal.
    const Luxel& first = lm->luxel(0, 0);
    const Vec3 facet = normalize(Vec3{-1, 0, 1});
    EXPECT_EQ(first.surfacePoint, (Vec3{0, 0, 0}));
    EXPECT_NEAR(first.origin.x, facet.x, 1e-5f);
    EXPECT_NEAR(first.origin.z, facet.z, 1e-5f);
    EXPECT_NEAR(first.faceNormal.x, facet.x, 1e-5f);
    // Luxel (6, 2) sits on control point 4 (the ridge), reached first by the left quad.
    const Luxel& ridge = lm->luxel(6, 2);
    EXPECT_EQ(ridge.surfacePoint, (Vec3{64, 32, 64}));
    EXPECT_NEAR(ridge.origin.x, 64.0f + facet.x, 1e-4f);
    EXPECT_NEAR(ridge.origin.y, 32.0f, 1e-4f);
    EXPECT_NEAR(ridge.origin.z, 64.0f + facet.z, 1e-4f);
    EXPECT_EQ(lm->origin, (Vec3{0, 0, 0}));

    // With a tessellated mesh, its points map by their control-space position.
    SurfaceGeometry g = archPatch();
    g.mesh.width = 5;
    g.mesh.height = 3;
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 5; ++x) {
            const float u = float(x) / 4.0f;  // bezier along x: z = 2u(1-u)*64
            g.mesh.positions.push_back({128.0f * u, 32.0f * float(y), 128.0f * u * (1.0f - u)});
            g.mesh.normals.push_back(normalize(Vec3{-(128.0f - 256.0f * u) / 128.0f, 0, 1}));
            g.mesh.controlU.push_back(2.0f * u);
            g.mesh.controlV.push_back(float(y));
        }
    const auto curved = layoutSurfaceLightmap(g, {}, {});
    ASSERT_TRUE(curved.has_value());
    // Segment lengths sqrt(32^2 + 24^2) = 40 and sqrt(32^2 + 8^2) = 32.98, twice: 145.97 -> 11 luxels.
    EXPECT_EQ(curved->width, 11);
    const Luxel& top = curved->luxel(5, 1);  // s centre 5.5 = sBasis 5 * u 1 + 0.5: the top of the arch
    EXPECT_NEAR(top.surfacePoint.x, 64.0f, 1e-3f);
    EXPECT_NEAR(top.surfacePoint.z, 32.0f, 1e-3f);
    EXPECT_NEAR(length(top.origin - top.surfacePoint), 1.0f, 1e-4f);
    EXPECT_LT(top.origin.x, 64.0f);  // off the left facet's plane, which leans back
    EXPECT_NEAR(top.normal.z, 1.0f, 1e-5f);  // the mean of every point's normal
}

TEST(LightmapLayout, DegenerateSurfaces) {
    SurfaceGeometry empty;
    EXPECT_FALSE(layoutSurfaceLightmap(empty, {}, {}).has_value());
    SurfaceGeometry badPatch = archPatch();
    badPatch.patchWidth = 5;
    Log log(false);
    EXPECT_FALSE(layoutSurfaceLightmap(badPatch, {}, {}, &log).has_value());
    EXPECT_EQ(log.warningCount(), 1);
}

TEST(LightmapLayout, AppliesTheOriginOnly) {
    const auto lm = layoutSurfaceLightmap(quad({10, 0, 0}, {10, 64, 0}, {10, 64, 32}, {10, 0, 32}, {1, 0, 0}), {}, {});
    bsp::Surface s{};
    s.lightmapVecs[0][0] = 5;
    applyLightmapOrigin(s, *lm);
    EXPECT_EQ(s.lightmapOrigin[0], 10.0f);
    EXPECT_EQ(s.lightmapVecs[0][0], 5.0f);
}

TEST(LightmapLayout, EdgeOnALuxelBorderMapsTheNextLuxel) {
    // A strip 8 units tall facing -y: t runs 0.5..1.0, so its top edge lies on the border of row 1.
    // q3map2 drops the vertices into luxel floor(t) = 1, so row 1 samples too (row 0 may be in
    // solid under a floor); a test of square overlap would leave row 1 unmapped.
    const auto lm = layoutSurfaceLightmap(quad({0, 0, 0}, {0, 0, 8}, {64, 0, 8}, {64, 0, 0}, {0, -1, 0}), {}, {});
    ASSERT_TRUE(lm.has_value());
    EXPECT_EQ(lm->axisNum, 1);
    ASSERT_EQ(lm->height, 2);
    for (int x = 0; x < lm->width; ++x) {
        EXPECT_TRUE(lm->luxel(x, 0).mapped) << x;
        EXPECT_TRUE(lm->luxel(x, 1).mapped) << x;
        // Row 1 samples on the grid (z = 16) one unit in front, but remembers a point on the strip.
        EXPECT_EQ(lm->luxel(x, 1).origin, (Vec3{16.0f * float(x), -1, 16}));
        EXPECT_LE(lm->luxel(x, 1).surfacePoint.z, 8.0f);
        EXPECT_EQ(lm->luxel(x, 1).surfaceNormal, (Vec3{0, -1, 0}));
    }
}

TEST(LightmapLayout, DiagonalEdgesMapOnlyTheLuxelsTheyCross) {
    // Right triangle (0,0) (64,0) (0,64) on the floor: luxel (4, 4) (s 4.0..5.0, t 4.0..5.0) holds
    // the hypotenuse's point (32, 32) -> s = t = 2.5 only; beyond it nothing maps.
    SurfaceGeometry g = floorQuad();
    g.positions = {{0, 0, 0}, {64, 0, 0}, {0, 64, 0}};
    g.normals.resize(3);
    g.triangles = {0, 2, 1};
    const auto lm = layoutSurfaceLightmap(g, {}, {});
    ASSERT_TRUE(lm.has_value());
    EXPECT_TRUE(lm->luxel(0, 0).mapped);
    EXPECT_TRUE(lm->luxel(2, 2).mapped);   // on the hypotenuse (s + t = 5)
    EXPECT_TRUE(lm->luxel(4, 0).mapped);   // the vertex (64, 0) at s 4.5
    EXPECT_FALSE(lm->luxel(4, 4).mapped);  // far side of the hypotenuse
    EXPECT_FALSE(lm->luxel(3, 3).mapped);
}

}  // namespace
}  // namespace q3::light
