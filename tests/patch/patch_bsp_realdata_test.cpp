// The patch surfaces of the shipped OpenArena BSPs: control grids read through the DrawVert
// conversion tessellate cleanly, and the normals q3map2 stored on the control vertices agree with
// the surface orientation this library uses (normal = dP/du x dP/dv).
#include <gtest/gtest.h>

#include <span>

#include "bspfile.h"
#include "patch.h"
#include "patch_drawvert.h"
#include "test_data.h"

using namespace q3;
using namespace q3::patch;

TEST(PatchBspRealData, ShippedPatchSurfacesTessellate) {
    const auto bsps = q3::test::allRealBsps();
    ASSERT_GT(bsps.size(), 100u);
    long surfaces = 0, compared = 0, agreeing = 0;
    for (const auto& path : bsps) {
        SCOPED_TRACE(path.filename().string());
        const bsp::Bsp file = bsp::readBsp(path);
        for (const bsp::Surface& s : file.surfaces) {
            if (s.surfaceType != bsp::MST_PATCH) continue;
            ASSERT_LE(size_t(s.firstVert) + size_t(s.numVerts), file.drawVerts.size());
            const std::span<const bsp::DrawVert> verts(file.drawVerts.data() + s.firstVert, size_t(s.numVerts));
            const ControlGrid grid = gridFromDrawVerts(verts, s.patchWidth, s.patchHeight);
            ++surfaces;
            PatchMesh lit = tessellateForLighting(grid);
            EXPECT_EQ(lit.at(0, 0).xyz, grid.at(0, 0).xyz);
            EXPECT_EQ(lit.at(lit.width - 1, lit.height - 1).xyz, grid.at(grid.width - 1, grid.height - 1).xyz);
            for (const PatchVertex& v : lit.verts) ASSERT_TRUE(isFinite(v.xyz) && isFinite(v.normal));

            // Compare orientations at the control grid's own resolution.
            PatchMesh shape = tessellate(grid, {.iterations = 0});
            PatchMesh stored = tessellate(grid, {.iterations = 0, .normals = NormalSource::Interpolated});
            for (size_t i = 0; i < shape.verts.size(); ++i) {
                if (shape.verts[i].normal == Vec3{} || stored.verts[i].normal == Vec3{}) continue;
                ++compared;
                if (dot(shape.verts[i].normal, stored.verts[i].normal) > 0.5f) ++agreeing;
            }
            // A vertex-coloured draw vertex keeps its colour at the corners.
            EXPECT_EQ(toDrawVert(lit.at(0, 0)).color[0], verts[0].color[0]);
        }
    }
    std::printf("%ld patch surfaces, %ld of %ld vertex normals agree with the surface orientation\n", surfaces, agreeing,
                compared);
    EXPECT_GT(surfaces, 1000);
    EXPECT_GT(double(agreeing), 0.97 * double(compared));
}
