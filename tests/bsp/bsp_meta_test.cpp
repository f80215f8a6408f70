// -meta on hand-made faces: meta triangles (degenerate and duplicate ones dropped), smoothing,
// merging with q3map2's scores and limits, -patchmeta, and whole compiles of small rooms.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <set>

#include "bsp_compile.h"
#include "bsp_test_maps.h"
#include "log.h"
#include "map_file.h"
#include "meta/meta_smooth.h"
#include "meta/meta_surfaces.h"
#include "meta/meta_triangles.h"
#include "shaping/autosprite2.h"
#include "shader_info.h"

namespace q3::bspstage {
namespace {

const ShaderInfo& wallShader() {
    static const ShaderInfo shader = makeImplicitShader("textures/base/wall");
    return shader;
}

// An implicit shader with one change.
template <typename Change>
ShaderInfo shaderWith(const char* name, Change change) {
    ShaderInfo s = makeImplicitShader(name);
    change(s);
    return s;
}

const ShaderInfo& vertexLitShader() {
    static const ShaderInfo shader =
        shaderWith("textures/base/vertexlit", [](ShaderInfo& s) { applySurfaceParm("pointlight", s); });
    return shader;
}

// A face on the plane through its first three points (counter-clockwise seen from the front),
// texture coordinates projected along Z at 1/64 per unit.
DrawSurface face(PlaneSet& planes, std::vector<Vec3> points, const ShaderInfo& shader = wallShader()) {
    DrawSurface ds;
    ds.kind = SurfaceKind::Face;
    ds.shader = &shader;
    ds.planeNum = planes.fromPoints(DVec3(points[0]), DVec3(points[2]), DVec3(points[1]));
    ds.planar = true;
    const Vec3 n = planes[ds.planeNum].normal().toFloat();
    for (const Vec3& p : points) {
        bsp::DrawVert v{};
        p.toArray(v.xyz);
        n.toArray(v.normal);
        v.st[0] = p.x / 64;
        v.st[1] = p.y / 64;
        for (uint8_t& c : v.color) c = 255;
        ds.verts.push_back(v);
    }
    return ds;
}

// A floor quad at height z from (x0, y0) to (x1, y1), facing up.
DrawSurface floorQuad(PlaneSet& planes, float x0, float y0, float x1, float y1, float z = 0,
                      const ShaderInfo& shader = wallShader()) {
    return face(planes, {{x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}}, shader);
}

// `count` floor quads `step` long and `depth` deep side by side along X from the origin.
std::vector<DrawSurface> floorRow(PlaneSet& planes, int count, float step, float depth,
                                  const ShaderInfo& shader = wallShader()) {
    std::vector<DrawSurface> out;
    for (int i = 0; i < count; ++i) out.push_back(floorQuad(planes, float(i) * step, 0, float(i + 1) * step, depth, 0, shader));
    return out;
}

struct Meta {
    PlaneSet planes;
    TextureSizes textures;
    ClassifyOptions classify;
    LibcRandom random;
    map::MapEntity entity;
    meta::MetaOptions options;
    Log log{false};

    Meta() { options.meta = true; }

    meta::MetaCounts run(std::vector<DrawSurface>& surfaces) {
        return meta::makeMetaSurfaces(surfaces, {entity, planes, textures, classify, random}, options, log);
    }
};

int metaCount(const std::vector<DrawSurface>& surfaces) {
    return int(std::count_if(surfaces.begin(), surfaces.end(), [](const DrawSurface& ds) { return ds.kind == SurfaceKind::Meta; }));
}

TEST(MetaMerge, CoplanarQuadsSharingAnEdgeBecomeOneSurface) {
    Meta m;
    std::vector<DrawSurface> surfaces{floorQuad(m.planes, 0, 0, 64, 64), floorQuad(m.planes, 64, 0, 128, 64)};
    const meta::MetaCounts counts = m.run(surfaces);
    EXPECT_EQ(counts.metaSurfaces, 2);
    EXPECT_EQ(counts.metaTriangles, 4);
    EXPECT_EQ(counts.metaVerts, 6);  // positions
    ASSERT_EQ(surfaces.size(), 1u);  // the faces are gone, one meta surface replaces them
    const DrawSurface& ds = surfaces[0];
    EXPECT_EQ(ds.kind, SurfaceKind::Meta);
    EXPECT_EQ(ds.verts.size(), 6u);
    EXPECT_EQ(ds.indexes.size(), 12u);
    EXPECT_TRUE(ds.planar);
    EXPECT_EQ(ds.lightmapAxis, (Vec3{0, 0, 1}));
    EXPECT_EQ(ds.sampleSize, 16);
    EXPECT_EQ(ds.metaSides.size(), 4u);  // one per triangle
}

TEST(MetaMerge, DifferentTexturesOrShadersStayApart) {
    Meta m;
    static const ShaderInfo other = makeImplicitShader("textures/base/other");
    std::vector<DrawSurface> surfaces{floorQuad(m.planes, 0, 0, 64, 64),
                                      face(m.planes, {{64, 0, 0}, {128, 0, 0}, {128, 64, 0}, {64, 64, 0}}, other)};
    m.run(surfaces);
    EXPECT_EQ(metaCount(surfaces), 2);
}

TEST(MetaMerge, AFaceOnAnotherPlaneOnlyJoinsWithNp) {
    // A floor and a ramp rising gently from its edge: the same lightmap axis, other planes.
    Meta m;
    const auto make = [&] {
        return std::vector<DrawSurface>{floorQuad(m.planes, 0, 0, 64, 64),
                                        face(m.planes, {{64, 0, 0}, {128, 0, 8}, {128, 64, 8}, {64, 64, 0}})};
    };
    std::vector<DrawSurface> surfaces = make();
    m.run(surfaces);
    EXPECT_EQ(metaCount(surfaces), 2);

    m.options.limits.npDegrees = 30;
    surfaces = make();
    const meta::MetaCounts counts = m.run(surfaces);
    ASSERT_EQ(metaCount(surfaces), 1);
    EXPECT_EQ(surfaces[0].verts.size(), 6u);
    // -np also smooths: the corners on the crease share one normal, between the two planes'.
    EXPECT_GT(counts.smoothed, 0);
    int creased = 0;
    for (const bsp::DrawVert& v : surfaces[0].verts)
        if (v.xyz[0] == 64) {
            ++creased;
            EXPECT_GT(v.normal[0], -0.0625f);
            EXPECT_LT(v.normal[0], 0);
            EXPECT_NEAR(length(normalOf(v)), 1, 1e-5);
        }
    EXPECT_EQ(creased, 2);
}

TEST(MetaMerge, VertexLimitOfLightmappedAndVertexLitSurfaces) {
    // A row of 20 quads: 42 corners on one plane.
    Meta m;
    std::vector<DrawSurface> surfaces = floorRow(m.planes, 20, 32, 32);
    m.options.limits.maxLightmappedVerts = 10;
    m.run(surfaces);
    int verts = 0;
    for (const DrawSurface& ds : surfaces) {
        EXPECT_LE(ds.verts.size(), 10u);
        verts += int(ds.verts.size());
    }
    EXPECT_GE(surfaces.size(), 5u);
    EXPECT_GE(verts, 42);

    // Vertex-lit shaders are held by the larger limit only.
    Meta lit;
    surfaces = floorRow(lit.planes, 20, 32, 32, vertexLitShader());
    lit.options.limits.maxLightmappedVerts = 10;
    lit.run(surfaces);
    ASSERT_EQ(surfaces.size(), 1u);
    EXPECT_EQ(surfaces[0].verts.size(), 42u);
    EXPECT_EQ(surfaces[0].lightmapAxis, (Vec3{0, 0, 0}));
    EXPECT_EQ(surfaces[0].sampleSize, 0);
}

TEST(MetaMerge, IndexLimit) {
    Meta m;
    std::vector<DrawSurface> surfaces = floorRow(m.planes, 4, 32, 32);
    m.options.limits.maxIndexes = 9;
    m.run(surfaces);
    EXPECT_EQ(surfaces.size(), 3u);  // 8 triangles, 3 per surface
    for (const DrawSurface& ds : surfaces) EXPECT_LE(ds.indexes.size(), 9u);
}

TEST(MetaMerge, LightmapExtentLimitsSurfacesToTheLightmapPage) {
    // 64 quads of 64 units along X: 4096 units. One lightmap page spans 16 x 127 = 2032 units.
    Meta m;
    std::vector<DrawSurface> surfaces = floorRow(m.planes, 64, 64, 16);
    m.options.limits.maxLightmappedVerts = 1000;
    m.run(surfaces);
    EXPECT_EQ(surfaces.size(), 3u);
    for (const DrawSurface& ds : surfaces) {
        float lo = 1e9f, hi = -1e9f;
        for (const bsp::DrawVert& v : ds.verts) {
            lo = std::min(lo, v.xyz[0]);
            hi = std::max(hi, v.xyz[0]);
        }
        EXPECT_LE(hi - lo, 2032);
    }
    // A larger sample size makes the page wider.
    Meta coarse;
    coarse.classify.sampleSize = 64;
    coarse.options.limits.maxLightmappedVerts = 1000;
    surfaces = floorRow(coarse.planes, 64, 64, 16);
    coarse.run(surfaces);
    EXPECT_EQ(surfaces.size(), 1u);
}

TEST(MetaMerge, ScoresPreferTheSeedsOwnFaceAndGoodScoresAreTakenAtOnce) {
    // Two equal fans of two triangles around a shared corner: the seed's own other triangle wins
    // the tie, so a surface never mixes them while its own is left.
    Meta m;
    m.options.limits.maxIndexes = 6;
    std::vector<DrawSurface> surfaces{floorQuad(m.planes, 0, 0, 64, 64), floorQuad(m.planes, 64, 0, 128, 64)};
    m.run(surfaces);
    ASSERT_EQ(surfaces.size(), 2u);
    for (const DrawSurface& ds : surfaces) {
        EXPECT_EQ(ds.verts.size(), 4u);
        float lo = 1e9f;
        for (const bsp::DrawVert& v : ds.verts) lo = std::min(lo, v.xyz[0]);
        EXPECT_TRUE(lo == 0 || lo == 64);
    }
    // An adequate score above every possible one leaves each triangle alone.
    Meta strict;
    strict.options.limits.adequateScore = 200000;
    surfaces = {floorQuad(strict.planes, 0, 0, 64, 64)};
    strict.run(surfaces);
    EXPECT_EQ(surfaces.size(), 2u);
}

TEST(MetaMerge, ForcedMetaShadersMergeWithoutTheOption) {
    Meta m;
    m.options.meta = false;
    static const ShaderInfo forced = shaderWith("textures/base/forced", [](ShaderInfo& s) { s.forceMeta = true; });
    std::vector<DrawSurface> surfaces{floorQuad(m.planes, 0, 0, 64, 64),
                                      face(m.planes, {{0, 0, 64}, {64, 0, 64}, {64, 64, 64}, {0, 64, 64}}, forced),
                                      face(m.planes, {{64, 0, 64}, {128, 0, 64}, {128, 64, 64}, {64, 64, 64}}, forced)};
    m.run(surfaces);
    ASSERT_EQ(surfaces.size(), 2u);
    EXPECT_EQ(surfaces[0].kind, SurfaceKind::Face);  // untouched
    EXPECT_EQ(surfaces[1].kind, SurfaceKind::Meta);
    EXPECT_EQ(surfaces[1].verts.size(), 6u);
}

TEST(MetaMerge, AutospriteFacesStayFaces) {
    Meta m;
    static const ShaderInfo sprite = shaderWith("textures/base/sprite", [](ShaderInfo& s) { s.autosprite = true; });
    std::vector<DrawSurface> surfaces{face(m.planes, {{0, 0, 0}, {64, 0, 0}, {64, 64, 0}, {0, 64, 0}}, sprite)};
    m.run(surfaces);
    ASSERT_EQ(surfaces.size(), 1u);
    EXPECT_EQ(surfaces[0].kind, SurfaceKind::Face);
}

TEST(MetaTriangles, ShortEdgesRepeatedIndexesAndDuplicatesAreDropped) {
    PlaneSet planes;
    Log log(false);
    meta::MetaTriangles set;
    DrawSurface ds = floorQuad(planes, 0, 0, 64, 64);
    ds.lightmapAxis = {0, 0, 1};
    ds.indexes = {0, 1, 2, 0, 2, 3, 0, 0, 1};
    set.addSurface(ds, 0, planes, log);
    EXPECT_EQ(set.triangles.size(), 2u);
    EXPECT_EQ(set.groups.size(), 4u);
    // The same triangles again, also turned the other way: dropped as duplicates.
    ds.indexes = {0, 1, 2, 2, 0, 3};
    set.addSurface(ds, 1, planes, log);
    EXPECT_EQ(set.triangles.size(), 2u);
    EXPECT_EQ(set.duplicates, 2);
    EXPECT_EQ(log.warningCount(), 2);
    // A corner 1/16 unit from another makes a degenerate triangle.
    DrawSurface sliver = floorQuad(planes, 0, 0, 64, 64);
    sliver.verts[1].xyz[0] = 0.0625f;
    sliver.verts[1].xyz[1] = 0;
    sliver.indexes = {0, 1, 2};
    set.addSurface(sliver, 2, planes, log);
    EXPECT_EQ(set.triangles.size(), 2u);
}

TEST(MetaTriangles, VerticesAtOnePositionShareAGroup) {
    PlaneSet planes;
    Log log(false);
    meta::MetaTriangles set;
    DrawSurface floor = floorQuad(planes, 0, 0, 64, 64);
    floor.indexes = {0, 1, 2};
    DrawSurface wall = face(planes, {{64, 0, 0}, {64, 64, 0}, {64, 64, 64}});
    wall.indexes = {0, 1, 2};
    set.addSurface(floor, 0, planes, log);
    set.addSurface(wall, 1, planes, log);
    EXPECT_EQ(set.vertices.size(), 6u);  // other normals: other vertices
    EXPECT_EQ(set.groups.size(), 4u);    // two shared positions
    EXPECT_EQ(set.triangles[1].lightmapAxis, (Vec3{1, 0, 0}));
}

TEST(MetaSmooth, ShaderShadeAngleAveragesNormalsWithinIt) {
    static const ShaderInfo smooth = shaderWith("textures/base/smooth", [](ShaderInfo& s) { s.shadeAngleDegrees = 45; });
    PlaneSet planes;
    Log log(false);
    const auto build = [&](float rise) {
        meta::MetaTriangles set;
        DrawSurface a = face(planes, {{0, 0, 0}, {64, 0, 0}, {64, 64, 0}}, smooth);
        DrawSurface b = face(planes, {{64, 0, 0}, {128, 0, rise}, {64, 64, 0}}, smooth);
        a.indexes = b.indexes = {0, 1, 2};
        set.addSurface(a, 0, planes, log);
        set.addSurface(b, 1, planes, log);
        return set;
    };
    meta::MetaTriangles gentle = build(16);  // 14 degrees apart: smoothed
    EXPECT_EQ(meta::smoothMetaTriangles(gentle, 0), 2);
    const Vec3 n0 = normalOf(gentle.vertices[size_t(gentle.triangles[0].verts[1])].vert);
    const Vec3 n1 = normalOf(gentle.vertices[size_t(gentle.triangles[1].verts[0])].vert);
    EXPECT_EQ(n0, n1);
    EXPECT_LT(n0.x, 0);
    meta::MetaTriangles steep = build(128);  // 63 degrees apart: left alone
    EXPECT_EQ(meta::smoothMetaTriangles(steep, 0), 0);
}

TEST(Autosprite2, QuadIsRewrittenWithItsShortEdgesFirst) {
    // A 2 x 28 quad standing on the Y = 0 plane, facing -Y, listed from a long edge.
    PlaneSet planes;
    DrawSurface ds = face(planes, {{0, 0, 0}, {0, 0, 28}, {2, 0, 28}, {2, 0, 0}});
    ds.indexes = {0, 1, 2, 0, 2, 3};
    EXPECT_EQ(fixAutosprite2(ds), "");
    EXPECT_EQ(ds.indexes, (std::vector<int>{3, 0, 2, 2, 0, 1}));
    // Vertices 0-1 and 2-3 are the short edges, running opposite ways.
    EXPECT_EQ(xyzOf(ds.verts[0]).z, xyzOf(ds.verts[1]).z);
    EXPECT_EQ(xyzOf(ds.verts[2]).z, xyzOf(ds.verts[3]).z);
    EXPECT_NE(xyzOf(ds.verts[0]).z, xyzOf(ds.verts[2]).z);
    EXPECT_EQ(xyzOf(ds.verts[0]).x, xyzOf(ds.verts[3]).x);
    // A square has no long axis and stays as it was.
    DrawSurface square = face(planes, {{0, 0, 0}, {0, 0, 8}, {8, 0, 8}, {8, 0, 0}});
    square.indexes = {0, 1, 2, 0, 2, 3};
    EXPECT_EQ(fixAutosprite2(square), "autosprite2 surface: two shortest edges share a vertex");
    EXPECT_EQ(square.indexes, (std::vector<int>{0, 1, 2, 0, 2, 3}));
}

// Whole compiles.
CompiledBsp compileText(const std::string& text, const BspCompileOptions& options) {
    static Log log(false);
    static const ShaderTable shaders = test::commonShaders(log);
    static std::vector<std::unique_ptr<test::CompiledMap>> keep;
    auto c = std::make_unique<test::CompiledMap>();
    c->file = map::parseMap(text, "test.map");
    c->map = loadMapForBsp(c->file, shaders, {}, log);
    const TextureSizes textures;
    CompiledBsp out = compileBsp({c->map, c->file, shaders, textures}, options, log);
    keep.push_back(std::move(c));
    return out;
}

BspCompileOptions metaOptions() {
    BspCompileOptions options;
    options.meta.meta = true;
    return options;
}

const std::string kRoom = test::worldspawn(test::hollowRoom({64, 64, 64}, {448, 448, 320})) +
                          test::pointEntity("info_player_deathmatch", {256, 256, 128});

TEST(MetaCompile, RoomWallsBecomeMetaSurfaces) {
    const CompiledBsp out = compileText(kRoom, metaOptions());
    EXPECT_NO_THROW(bsp::validateBsp(out.bsp, "room"));
    ASSERT_EQ(out.bsp.surfaces.size(), 6u);
    std::set<int> planes;
    for (const bsp::Surface& s : out.bsp.surfaces) {
        EXPECT_EQ(s.surfaceType, bsp::MST_PLANAR);
        EXPECT_EQ(s.numVerts, 4);
        EXPECT_EQ(s.numIndexes, 6);
        planes.insert(int(s.lightmapVecs[2][0] * 4 + s.lightmapVecs[2][1] * 2 + s.lightmapVecs[2][2]));
    }
    EXPECT_EQ(planes.size(), 6u);
    EXPECT_NE(out.surfaceExtra.find("0 // ESurfaceType::Meta V: 4 I: 6 planar"), std::string::npos);
}

TEST(MetaCompile, SplitFloorJoinsAgainAndMvSplitsIt) {
    // Four slabs cover the floor: with -meta their four top faces are one surface again.
    std::string world = test::hollowRoom({64, 64, 64}, {448, 448, 320});
    for (int i = 0; i < 4; ++i) world += test::boxBrush({64.0 + 96 * i, 64, 64}, {160.0 + 96 * i, 448, 80});
    const std::string map = test::worldspawn(world) + test::pointEntity("info_player_deathmatch", {256, 256, 128});
    const CompiledBsp plain = compileText(map, {});
    const CompiledBsp meta = compileText(map, metaOptions());
    EXPECT_EQ(plain.bsp.surfaces.size(), 9u);  // four walls, the ceiling and the four slab tops
    EXPECT_EQ(meta.bsp.surfaces.size(), 6u);
    BspCompileOptions small = metaOptions();
    small.meta.limits.maxLightmappedVerts = 4;
    small.emit.maxLightmappedVerts = 4;
    const CompiledBsp split = compileText(map, small);
    EXPECT_GT(split.bsp.surfaces.size(), meta.bsp.surfaces.size());
    for (const bsp::Surface& s : split.bsp.surfaces) EXPECT_LE(s.numVerts, 4);
}

}  // namespace
}  // namespace q3::bspstage
