#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "bspfile.h"
#include "lightmap_layout.h"
#include "lightmap_layout_merge.h"
#include "lightmap_pack.h"
#include "log.h"
#include "patch.h"
#include "test_data.h"

namespace q3::light {
namespace {

// Lays out every lightmapped surface of real maps, packs made-up texels and checks that the BSP
// fields written back are consistent.
TEST(LightmapRealData, LayoutAndPackingAreConsistent) {
    int totalPatches = 0;
    for (const std::string name : {"oa_dm1", "oacmpdm1", "oacmpdm3"}) {
        const bsp::Bsp original = bsp::readBsp(test::realBsp(name));
        Log log(false);
        std::vector<LightmapBlock> blocks;
        int surfaces = 0, patches = 0;
        for (size_t s = 0; s < original.surfaces.size(); ++s) {
            const bsp::Surface& surface = original.surfaces[s];
            if (!isLightmappedSurface(surface, false)) continue;
            SurfaceGeometry g = surfaceGeometry(original, int(s));
            if (surface.surfaceType == bsp::MST_PATCH) g.mesh = curvedMesh(original, surface);
            const auto lm = layoutSurfaceLightmap(g, {}, {}, &log);
            ASSERT_TRUE(lm.has_value()) << name << " surface " << s;
            ++surfaces;
            patches += surface.surfaceType == bsp::MST_PATCH;
            ASSERT_LE(lm->width, 128);
            ASSERT_LE(lm->height, 128);
            for (const auto& c : lm->vertexCoords) {
                EXPECT_GE(c[0], 0.0f);
                EXPECT_GE(c[1], 0.0f);
                EXPECT_LE(c[0], float(lm->width));
                EXPECT_LE(c[1], float(lm->height));
            }
            int mapped = 0;
            for (const Luxel& l : lm->luxels) {
                mapped += l.mapped;
                if (l.mapped) {
                    ASSERT_TRUE(isFinite(l.origin) && isFinite(l.normal));
                }
            }
            EXPECT_GT(mapped, 0) << name << " surface " << s;

            LightmapBlock b;
            b.width = lm->width;
            b.height = lm->height;
            for (int y = 0; y < b.height; ++y)
                for (int x = 0; x < b.width; ++x) {
                    b.texels.push_back({uint8_t(s * 7 + x * 3), uint8_t(s * 13 + y * 5), uint8_t(x * y)});
                    b.used.push_back(lm->luxel(x, y).mapped ? 1 : 0);
                }
            b.sortKey = original.shaders[size_t(surface.shaderNum)].name;
            b.surfaces = {int(s)};
            b.vertexCoords = {lm->vertexCoords};
            blocks.push_back(std::move(b));
        }
        EXPECT_GT(surfaces, 100) << name;
        totalPatches += patches;

        bsp::Bsp lit = original;
        const PackedLightmaps packed = packLightmaps(blocks, PackOptions{});
        applyPackedLightmaps(lit, blocks, packed);
        EXPECT_EQ(lit.lightmaps.size(), packed.pages.size() * size_t(bsp::kLightmapPageBytes)) << name;
        EXPECT_NO_THROW(bsp::validateBsp(lit, name));

        // Every vertex's lightmap coordinate lies inside its block, on its page.
        for (size_t i = 0; i < blocks.size(); ++i) {
            const BlockPlacement& p = packed.placements[i];
            const bsp::Surface& surface = lit.surfaces[size_t(blocks[i].surfaces[0])];
            EXPECT_EQ(surface.lightmapNum, p.page);
            for (int v = 0; v < surface.numVerts; ++v) {
                const bsp::DrawVert& dv = lit.drawVerts[size_t(surface.firstVert + v)];
                const float s = dv.lightmap[0] * 128.0f, t = dv.lightmap[1] * 128.0f;
                EXPECT_GE(s, float(p.x) - 1e-3f);
                EXPECT_GE(t, float(p.y) - 1e-3f);
                EXPECT_LE(s, float(p.x + p.width) + 1e-3f);
                EXPECT_LE(t, float(p.y + p.height) + 1e-3f);
            }
        }
        // No two blocks claim the same page texel, and the page holds each block's texels.
        std::map<std::tuple<int, int, int>, size_t> owner;
        for (size_t i = 0; i < blocks.size(); ++i) {
            const BlockPlacement& p = packed.placements[i];
            if (p.twinOf >= 0) continue;
            const auto& page = packed.pages[size_t(p.page)];
            for (int y = 0; y < p.height; ++y)
                for (int x = 0; x < p.width; ++x) {
                    const size_t bi = size_t(y) * blocks[i].width + x;
                    if (!p.solid && !blocks[i].used[bi]) continue;
                    const auto key = std::make_tuple(p.page, p.x + x, p.y + y);
                    EXPECT_EQ(owner.count(key), 0u) << name << " texel claimed twice";
                    owner[key] = i;
                    if (!p.solid) {
                        const size_t o = (size_t(p.y + y) * 128 + size_t(p.x + x)) * 3;
                        EXPECT_EQ(page[o], blocks[i].texels[bi][0]);
                        EXPECT_EQ(page[o + 1], blocks[i].texels[bi][1]);
                    }
                }
        }
        RecordProperty(name + "_pages", int(packed.pages.size()));
    }
    EXPECT_GT(totalPatches, 700);  // curved and flat patches of the oacmp maps
}

// The same with coplanar surfaces merged into shared raw lightmaps, as q3map2 does.
TEST(LightmapRealData, MergedLayoutCoversEverySurfaceOnce) {
    for (const std::string name : {"oa_dm1", "oacmpdm1"}) {
        const bsp::Bsp original = bsp::readBsp(test::realBsp(name));
        std::vector<SurfaceLightmapInput> inputs;
        for (size_t m = 0; m < original.models.size(); ++m) {
            const bsp::Model& model = original.models[m];
            for (int s = model.firstSurface; s < model.firstSurface + model.numSurfaces; ++s) {
                const bsp::Surface& surface = original.surfaces[size_t(s)];
                if (!isLightmappedSurface(surface, false)) continue;
                SurfaceLightmapInput in;
                in.geometry = surfaceGeometry(original, s);
                if (surface.surfaceType == bsp::MST_PATCH) in.geometry.mesh = curvedMesh(original, surface);
                in.traits.model = int(m);
                in.traits.shader = original.shaders[size_t(surface.shaderNum)].name;
                inputs.push_back(std::move(in));
            }
        }
        Log log(false);
        const std::vector<RawLightmap> lms = layoutMergedLightmaps(inputs, {}, &log);
        std::vector<int> seen(original.surfaces.size(), 0);
        std::vector<LightmapBlock> blocks;
        for (const RawLightmap& lm : lms) {
            ASSERT_EQ(lm.surfaces.size(), lm.surfaceCoords.size());
            LightmapBlock b;
            b.width = lm.width;
            b.height = lm.height;
            for (int y = 0; y < b.height; ++y)
                for (int x = 0; x < b.width; ++x) {
                    b.texels.push_back({uint8_t(lm.surfaceIndex * 7 + x * 3), uint8_t(y * 5), uint8_t(x * y)});
                    b.used.push_back(lm.luxel(x, y).mapped ? 1 : 0);
                }
            for (size_t k = 0; k < lm.surfaces.size(); ++k) {
                ++seen[size_t(lm.surfaces[k])];
                for (const auto& c : lm.surfaceCoords[k]) {
                    EXPECT_GE(c[0], 0.0f);
                    EXPECT_LE(c[0], float(lm.width));
                    EXPECT_LE(c[1], float(lm.height));
                }
            }
            b.surfaces = lm.surfaces;
            b.vertexCoords = lm.surfaceCoords;
            blocks.push_back(std::move(b));
        }
        for (const SurfaceLightmapInput& in : inputs) EXPECT_EQ(seen[size_t(in.geometry.surfaceIndex)], 1) << name;
        // Sharing happens (these maps were built with -meta, which already merged most coplanar
        // faces): at least 10% fewer raw lightmaps than surfaces.
        EXPECT_LT(lms.size() * 10, inputs.size() * 9) << name;

        bsp::Bsp lit = original;
        const PackedLightmaps packed = packLightmaps(blocks, PackOptions{});
        applyPackedLightmaps(lit, blocks, packed);
        for (size_t i = 0; i < blocks.size(); ++i) {
            const BlockPlacement& p = packed.placements[i];
            for (int s : blocks[i].surfaces) {
                const bsp::Surface& surface = lit.surfaces[size_t(s)];
                EXPECT_EQ(surface.lightmapX, p.x);
                for (int v = 0; v < surface.numVerts; ++v) {
                    const bsp::DrawVert& dv = lit.drawVerts[size_t(surface.firstVert + v)];
                    EXPECT_GE(dv.lightmap[0] * 128.0f, float(p.x) - 1e-3f);
                    EXPECT_LE(dv.lightmap[0] * 128.0f, float(p.x + p.width) + 1e-3f);
                    EXPECT_GE(dv.lightmap[1] * 128.0f, float(p.y) - 1e-3f);
                    EXPECT_LE(dv.lightmap[1] * 128.0f, float(p.y + p.height) + 1e-3f);
                }
            }
        }
        RecordProperty(name + "_raw_lightmaps", int(lms.size()));
    }
}

// q3map2 wrote the shipped maps' lightmap coordinates as (x + s) / 128 with s = distance along the
// projection's s axis / sample size + 0.5. For every planar surface with a real (non-solid)
// lightmap, our projection axes must reproduce them with one sample size per surface.
TEST(LightmapRealData, ProjectionAxesMatchShippedLightmapCoordinates) {
    int checked = 0, mismatched = 0, onTexelCorner = 0;
    for (const std::string name : {"oa_dm1", "oa_dm4", "oacmpdm1", "oacmpdm3"}) {
        const bsp::Bsp b = bsp::readBsp(test::realBsp(name));
        for (size_t si = 0; si < b.surfaces.size(); ++si) {
            const bsp::Surface& surface = b.surfaces[si];
            if (surface.surfaceType != bsp::MST_PLANAR || surface.lightmapNum < 0 || surface.numVerts < 3) continue;
            const auto lm = layoutSurfaceLightmap(surfaceGeometry(b, int(si)), {}, {});
            ASSERT_TRUE(lm.has_value());
            const int sAxis = lm->axisNum == 0 ? 1 : 0;
            const int tAxis = lm->axisNum == 2 ? 1 : 2;
            const bsp::DrawVert* v = &b.drawVerts[size_t(surface.firstVert)];
            // The vertex farthest from vertex 0 along each axis gives the sample size.
            bool solid = true;
            float ss[2] = {0, 0};
            for (int axis = 0; axis < 2; ++axis) {
                const int world = axis == 0 ? sAxis : tAxis;
                float best = 0;
                for (int k = 1; k < surface.numVerts; ++k) {
                    const float dp = v[k].xyz[world] - v[0].xyz[world];
                    const float du = (v[k].lightmap[axis] - v[0].lightmap[axis]) * 128.0f;
                    if (std::fabs(du) > 1e-3f) solid = false;
                    if (std::fabs(dp) > std::fabs(best) && std::fabs(du) > 1e-3f) {
                        best = dp;
                        ss[axis] = dp / du;
                    }
                }
            }
            if (solid) continue;
            ++checked;
            bool ok = ss[0] > 0.5f && std::fabs(ss[0] - ss[1]) < 0.01f * ss[0];
            for (int k = 1; k < surface.numVerts && ok; ++k)
                for (int axis = 0; axis < 2 && ok; ++axis) {
                    const int world = axis == 0 ? sAxis : tAxis;
                    const float predicted = (v[k].xyz[world] - v[0].xyz[world]) / ss[0];
                    const float actual = (v[k].lightmap[axis] - v[0].lightmap[axis]) * 128.0f;
                    ok = std::fabs(predicted - actual) < 0.02f;
                }
            if (ok) {
                // The block origin (u at the surface's minimum, less q3map2's half-texel) is a texel
                // corner unless the surface shared a raw lightmap whose bounds start elsewhere.
                bool integral = true;
                for (int axis = 0; axis < 2; ++axis) {
                    const int world = axis == 0 ? sAxis : tAxis;
                    float mins = v[0].xyz[world];
                    for (int k = 1; k < surface.numVerts; ++k) mins = std::min(mins, v[k].xyz[world]);
                    const float corner = v[0].lightmap[axis] * 128.0f - (v[0].xyz[world] - mins) / ss[0] - 0.5f;
                    integral = integral && std::fabs(corner - std::round(corner)) < 0.02f;
                }
                onTexelCorner += integral;
            }
            if (!ok) {
                ++mismatched;
                ADD_FAILURE() << name << " surface " << si << " axis " << lm->axisNum << " sample sizes " << ss[0] << " "
                              << ss[1];
                if (mismatched > 10) return;
            }
        }
    }
    EXPECT_GT(checked, 1000);
    EXPECT_EQ(mismatched, 0);
    // 7019 surfaces checked, 6578 start on a texel corner when this was written; the rest shared a
    // raw lightmap with a neighbour.
    EXPECT_GT(onTexelCorner * 10, checked * 9);
    RecordProperty("checked", checked);
    RecordProperty("on_texel_corner", onTexelCorner);
}

// Curved patches: q3map2 spreads the control points evenly over w - 1 luxels, so the shipped
// coordinates give its lightmap size; ours (mesh lengths at the default sample size) must agree
// (all 460 non-solid curved patches of these maps did when this was written).
TEST(LightmapRealData, CurvedPatchSizesMatchShippedLightmaps) {
    int checked = 0, matched = 0;
    for (const std::string name : {"oacmpdm1", "oacmpdm3"}) {
        const bsp::Bsp b = bsp::readBsp(test::realBsp(name));
        for (size_t si = 0; si < b.surfaces.size(); ++si) {
            const bsp::Surface& surface = b.surfaces[si];
            if (surface.surfaceType != bsp::MST_PATCH || surface.lightmapNum < 0) continue;
            SurfaceGeometry g = surfaceGeometry(b, int(si));
            g.mesh = curvedMesh(b, surface);
            const auto lm = layoutSurfaceLightmap(g, {}, {});
            ASSERT_TRUE(lm.has_value());
            if (lm->axisNum >= 0) continue;  // flat patch
            const bsp::DrawVert* v = &b.drawVerts[size_t(surface.firstVert)];
            const float shippedW = (v[surface.patchWidth - 1].lightmap[0] - v[0].lightmap[0]) * 128.0f + 1.0f;
            const float shippedH =
                (v[(surface.patchHeight - 1) * surface.patchWidth].lightmap[1] - v[0].lightmap[1]) * 128.0f + 1.0f;
            if (std::fabs(shippedW - 1.0f) < 1e-3f && std::fabs(shippedH - 1.0f) < 1e-3f) continue;  // solid
            ++checked;
            matched += std::fabs(shippedW - float(lm->width)) < 0.02f && std::fabs(shippedH - float(lm->height)) < 0.02f;
        }
    }
    EXPECT_GT(checked, 100);
    EXPECT_EQ(matched, checked);
    RecordProperty("checked", checked);
    RecordProperty("matched", matched);
}

}  // namespace
}  // namespace q3::light
