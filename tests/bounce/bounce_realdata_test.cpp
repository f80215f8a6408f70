// Bounce emitters of a real OpenArena map: every lightmapped planar or triangle-soup surface of
// oacmpdm1, lit by its own stored lightmap, becomes emitters that stay within the surfaces, never
// cover more than the surfaces, are bounded in colour, and come out the same on every run.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "bounce_lights.h"
#include "bounce_test_util.h"
#include "bspfile.h"
#include "test_data.h"

namespace q3::light {
namespace {

constexpr int32_t kSurfSky = 0x4;      // Quake 3 surface flags
constexpr int32_t kSurfNodraw = 0x80;
constexpr int kPage = 128;  // BSP lightmap page size in luxels

struct RealInputs {
    std::vector<LightingShader> shaders;
    std::vector<BounceSurface> surfaces;
    float surfaceArea = 0;  // of the surfaces that bounce
    Bounds bounds;          // of the surfaces that bounce
};

// One BounceSurface per lightmapped surface: the stored lightmap as this pass's light, no texture.
RealInputs loadSurfaces(const bsp::Bsp& b) {
    RealInputs in;
    in.shaders.resize(b.shaders.size());
    for (size_t i = 0; i < b.shaders.size(); ++i) {
        in.shaders[i].sky = (b.shaders[i].surfaceFlags & kSurfSky) != 0;
        in.shaders[i].nodraw = (b.shaders[i].surfaceFlags & kSurfNodraw) != 0;
    }
    const size_t pages = b.lightmaps.size() / static_cast<size_t>(bsp::kLightmapPageBytes);
    for (size_t n = 0; n < b.surfaces.size(); ++n) {
        const bsp::Surface& s = b.surfaces[n];
        if (s.surfaceType != bsp::MST_PLANAR && s.surfaceType != bsp::MST_TRIANGLE_SOUP) continue;
        if (s.lightmapNum < 0 || static_cast<size_t>(s.lightmapNum) >= pages) continue;
        // The stored surfaces leave lightmapWidth/Height at 0: the rectangle comes from the
        // vertices' page coordinates.
        float lo[2] = {kPage, kPage}, hi[2] = {0, 0};
        for (int v = 0; v < s.numVerts; ++v) {
            const bsp::DrawVert& d = b.drawVerts[static_cast<size_t>(s.firstVert + v)];
            for (int a = 0; a < 2; ++a) {
                lo[a] = std::min(lo[a], d.lightmap[a] * kPage);
                hi[a] = std::max(hi[a], d.lightmap[a] * kPage);
            }
        }
        int x0 = std::clamp(static_cast<int>(std::floor(lo[0])), 0, kPage - 1);
        int y0 = std::clamp(static_cast<int>(std::floor(lo[1])), 0, kPage - 1);
        const int x1 = std::clamp(static_cast<int>(std::ceil(hi[0])), x0 + 1, kPage);
        const int y1 = std::clamp(static_cast<int>(std::ceil(hi[1])), y0 + 1, kPage);
        BounceSurface out;
        out.surfaceNum = static_cast<int>(n);
        out.shader = &in.shaders[static_cast<size_t>(s.shaderNum)];
        out.width = x1 - x0;
        out.height = y1 - y0;
        const uint8_t* page =
            &b.lightmaps[static_cast<size_t>(s.lightmapNum) * static_cast<size_t>(bsp::kLightmapPageBytes)];
        for (int y = y0; y < y1; ++y) {
            for (int x = x0; x < x1; ++x) {
                const uint8_t* p = page + (y * kPage + x) * 3;
                out.luxels.push_back({static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2])});
            }
        }
        for (int v = 0; v < s.numVerts; ++v) {
            const bsp::DrawVert& d = b.drawVerts[static_cast<size_t>(s.firstVert + v)];
            BounceVertex bv;
            bv.xyz = Vec3::fromArray(d.xyz);
            bv.normal = Vec3::fromArray(d.normal);
            bv.st = {d.st[0], d.st[1]};
            bv.lm = {d.lightmap[0] * kPage - static_cast<float>(x0), d.lightmap[1] * kPage - static_cast<float>(y0)};
            out.verts.push_back(bv);
        }
        for (int i = 0; i < s.numIndexes; ++i)
            out.triangles.push_back(static_cast<uint32_t>(b.drawIndexes[static_cast<size_t>(s.firstIndex + i)]));
        if (surfaceBounces(out.shader, out.shaderBounceScale)) {
            for (size_t i = 0; i + 2 < out.triangles.size(); i += 3) {
                const std::vector<Vec3> tri{out.verts[out.triangles[i]].xyz, out.verts[out.triangles[i + 1]].xyz,
                                            out.verts[out.triangles[i + 2]].xyz};
                in.surfaceArea += test::polygonArea(tri);
                for (const Vec3& p : tri) in.bounds.add(p);
            }
        }
        in.surfaces.push_back(std::move(out));
    }
    return in;
}

TEST(BounceRealData, OacmpDm1EmittersStayOnTheirSurfaces) {
    const bsp::Bsp b = bsp::readBsp(q3::test::realBsp("oacmpdm1"));
    const RealInputs in = loadSurfaces(b);
    ASSERT_GT(in.surfaces.size(), 100u);

    const std::vector<Light> lights = createBounceLights(in.surfaces, {});
    ASSERT_GT(lights.size(), in.surfaces.size() / 2);

    float lightArea = 0;
    Bounds grown = in.bounds;
    grown.add(in.bounds.mins - Vec3::splat(1.01f));  // origins sit one unit off the surface
    grown.add(in.bounds.maxs + Vec3::splat(1.01f));
    for (const Light& l : lights) {
        ASSERT_EQ(l.type, LightType::Area);
        ASSERT_GE(l.winding.size(), 3u);
        const float area = test::polygonArea(l.winding);
        EXPECT_GE(area, 1.0f);
        lightArea += area;
        EXPECT_NEAR(length(l.normal), 1.0f, 1e-4f);
        EXPECT_TRUE(grown.contains(l.origin));
        // Luxel bytes and a white texture: every channel within 0..1, not all dark.
        EXPECT_GE(l.color.x, 0.0f);
        EXPECT_LE(maxComponent(l.color), 1.0f + 1e-5f);
        EXPECT_GE(length(l.color), kBounceMinColor);
        EXPECT_TRUE(std::isfinite(l.photons) && l.photons > 0);
        // No piece is wider than the 256 chop.
        EXPECT_LE(maxComponent(test::lightBounds(l).size()), 256.0f + 0.01f);
    }
    EXPECT_LE(lightArea, in.surfaceArea * 1.0001f);
    // Most of the lit area re-emits (dark or tiny pieces are the only ones dropped).
    EXPECT_GT(lightArea, in.surfaceArea * 0.25f);

    const std::vector<Light> again = createBounceLights(in.surfaces, {});
    ASSERT_EQ(again.size(), lights.size());
    for (size_t i = 0; i < lights.size(); ++i) {
        EXPECT_EQ(again[i].winding, lights[i].winding);
        EXPECT_EQ(again[i].color, lights[i].color);
        EXPECT_EQ(again[i].photons, lights[i].photons);
    }
    EXPECT_FALSE(bounceLightsAsMap(lights).empty());
}

}  // namespace
}  // namespace q3::light
