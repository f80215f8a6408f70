// Every patch of the openarena-oacmp1 .map sources tessellates: corners on control corners, surface
// inside the control hull, unit normals, and the same mesh twice.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstring>

#include "map_file.h"
#include "patch.h"
#include "test_data.h"

using namespace q3;
using namespace q3::patch;

namespace {

ControlGrid gridOf(const map::MapPatch& p) {
    ControlGrid g;
    g.width = p.width;
    g.height = p.height;
    for (const map::PatchControl& c : p.control) {
        PatchVertex v;
        v.xyz = c.xyz;
        v.st[0] = c.st[0];
        v.st[1] = c.st[1];
        g.points.push_back(v);
    }
    return g;
}

// True when all control points lie on one line (q3map2 drops such patches as degenerate).
bool collinear(const ControlGrid& g) {
    const Vec3 origin = g.points[0].xyz;
    Vec3 dir;
    for (const PatchVertex& p : g.points)
        if (length(p.xyz - origin) > 1e-3f) {
            dir = normalize(p.xyz - origin);
            break;
        }
    for (const PatchVertex& p : g.points)
        if (length(cross(p.xyz - origin, dir)) > 1e-2f) return false;
    return true;
}

}  // namespace

TEST(PatchRealData, EveryOacmpPatchTessellates) {
    const auto sources = q3::test::oacmpMapSources();
    ASSERT_EQ(sources.size(), 13u);
    std::array<int, kMaxIterations + 1> levels{};
    int patches = 0, degenerate = 0, lodGroups = 0;
    for (const auto& path : sources) {
        SCOPED_TRACE(path.filename().string());
        const map::MapFile mapFile = map::loadMap(path);
        for (const map::MapEntity& e : mapFile.entities) {
            std::vector<ControlGrid> entityGrids;
            for (const map::MapPatch& p : e.patches) entityGrids.push_back(gridOf(p));
            const std::vector<int> groups = patchLodGroups(entityGrids);
            const std::vector<float> grouped = groupedLongestCurves(entityGrids);
            ASSERT_EQ(grouped.size(), entityGrids.size());
            for (size_t i = 0; i < entityGrids.size(); ++i) {
                EXPECT_GE(grouped[i], longestCurve(entityGrids[i]));
                for (size_t j = 0; j < entityGrids.size(); ++j)
                    if (groups[i] == groups[j]) {
                        EXPECT_EQ(grouped[i], grouped[j]);
                    }
            }
            if (!groups.empty()) lodGroups += *std::max_element(groups.begin(), groups.end()) + 1;
            for (const map::MapPatch& p : e.patches) {
                const ControlGrid g = gridOf(p);
                ASSERT_TRUE(isValidGrid(g)) << "patch on line " << p.line;
                ++patches;
                const int level = iterationsForCurve(longestCurve(g), kDefaultSubdivisions);
                ++levels[level];
                const bool flatLine = collinear(g);
                degenerate += flatLine;

                PatchMesh mesh = tessellate(g, {.iterations = level});
                ASSERT_EQ(mesh.verts.size(), size_t(mesh.width) * mesh.height);
                EXPECT_EQ(mesh.at(0, 0).xyz, g.at(0, 0).xyz);
                EXPECT_EQ(mesh.at(mesh.width - 1, mesh.height - 1).xyz, g.at(g.width - 1, g.height - 1).xyz);
                EXPECT_EQ(mesh.at(0, mesh.height - 1).xyz, g.at(0, g.height - 1).xyz);
                EXPECT_EQ(mesh.at(mesh.width - 1, 0).xyz, g.at(g.width - 1, 0).xyz);
                Bounds hull = controlBounds(g);
                hull.mins -= Vec3::splat(0.01f);
                hull.maxs += Vec3::splat(0.01f);
                const Bounds mb = meshBounds(mesh);
                EXPECT_TRUE(hull.contains(mb.mins) && hull.contains(mb.maxs)) << "patch on line " << p.line;
                if (!flatLine) {
                    for (const PatchVertex& v : mesh.verts) {
                        ASSERT_TRUE(isFinite(v.normal));
                        EXPECT_NEAR(length(v.normal), 1.0f, 1e-4f) << "patch on line " << p.line;
                    }
                }
                PatchMesh lit = tessellateForLighting(g);
                EXPECT_LE(lit.verts.size(), mesh.verts.size());
                EXPECT_EQ(lit.indices.size(), size_t(lit.width - 1) * (lit.height - 1) * 6);
                PatchMesh again = tessellateForLighting(g);
                ASSERT_EQ(again.verts.size(), lit.verts.size());
                EXPECT_EQ(std::memcmp(again.verts.data(), lit.verts.data(), lit.verts.size() * sizeof(PatchVertex)), 0);
            }
        }
    }
    EXPECT_GT(patches, 2000);
    // Editors build arches and pipes from several patches that meet: fewer groups than patches.
    EXPECT_LT(lodGroups, patches);
    EXPECT_GT(lodGroups, 0);
    EXPECT_LT(degenerate, patches / 100);
    // Real maps use more than one level: both straight-ish trims and long curves exist.
    EXPECT_GT(levels[0], 0);
    EXPECT_GT(levels[1] + levels[2] + levels[3], 0);
    std::printf("patches %d (degenerate %d, %d LOD groups), levels 0..3: %d %d %d %d\n", patches, degenerate, lodGroups,
                levels[0], levels[1], levels[2], levels[3]);
}
