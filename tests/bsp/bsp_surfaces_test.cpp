// The draw surface steps of -bsp on hand-made faces and maps: triangulation, classification,
// filtering, the .srf text, and whole compiles of small rooms.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <sstream>

#include "bsp_compile.h"
#include "bsp_test_maps.h"
#include "face_surfaces.h"
#include "file_io.h"
#include "max_area_triangles.h"
#include "model_test_files.h"
#include "model_surfaces.h"
#include "model_transform.h"
#include "patch_surfaces.h"
#include "srf_writer.h"
#include "structure_emit.h"
#include "surface_classify.h"
#include "surface_filter.h"
#include "surface_triangles.h"
#include "tjunctions.h"
#include "vfs.h"

namespace q3::bspstage {
namespace {

const ShaderInfo& plainShader() {
    static const ShaderInfo shader = makeImplicitShader("textures/base/wall");
    return shader;
}

DrawSurface faceFrom(std::initializer_list<Vec3> points) {
    DrawSurface ds;
    ds.shader = &plainShader();
    for (const Vec3& p : points) {
        bsp::DrawVert v{};
        p.toArray(v.xyz);
        v.normal[2] = 1;
        ds.verts.push_back(v);
    }
    return ds;
}

TEST(SurfaceTriangles, QuadStripStartsAtTheLowestVertexAndWalksBothEnds) {
    // Lowest vertex is index 1: triangles (1, 3, 0) and (2, 3, 1), as q3map2 writes them.
    DrawSurface ds = faceFrom({{64, 64, 0}, {0, 0, 0}, {0, 64, 0}, {64, 0, 0}});
    TriangulationCounts counts;
    triangulateFace(ds, &counts);
    EXPECT_EQ(ds.indexes, (std::vector<int>{1, 3, 0, 2, 3, 1}));
    EXPECT_EQ(counts.strips, 1);
}

TEST(SurfaceTriangles, SliverStripsFallBackToAFan) {
    // Six points on a line: every strip has a triangle without the apex, a sliver. A fan around a
    // new centre vertex replaces it.
    DrawSurface ds = faceFrom({{0, 0, 0}, {32, 0, 0}, {64, 0, 0}, {96, 0, 0}, {128, 0, 0}, {160, 0, 0}, {80, 64, 0}});
    TriangulationCounts counts;
    triangulateFace(ds, &counts);
    EXPECT_EQ(counts.fans, 1);
    ASSERT_EQ(ds.verts.size(), 8u);
    EXPECT_FLOAT_EQ(ds.verts[0].xyz[0], 80.0f);
    EXPECT_EQ(ds.indexes.size(), 21u);
    EXPECT_EQ((std::vector<int>(ds.indexes.end() - 3, ds.indexes.end())), (std::vector<int>{0, 7, 1}));
}

TEST(SurfaceTriangles, MinimumAngleAndArea) {
    EXPECT_NEAR(triangleMinAngleSquaredSin({0, 0, 0}, {1, 0, 0}, {0, 1, 0}), 0.5, 1e-6);
    EXPECT_NEAR(triangleArea2x({0, 0, 0}, {2, 0, 0}, {0, 3, 0}), 6.0, 1e-6);
    EXPECT_EQ(triangleMinAngleSquaredSin({0, 0, 0}, {0, 0, 0}, {0, 1, 0}), 0.0);
}

TEST(SurfaceTriangles, MaxAreaCutsTheBestTriangleThenTheRunsBesideIt) {
    // In a square every triangle has the same area; the perimeter penalty prefers the ones with
    // the diagonal as their first side, and the first of those wins.
    DrawSurface square = faceFrom({{0, 0, 0}, {64, 0, 0}, {64, 64, 0}, {0, 64, 0}});
    LibcRandom random;
    TriangulationCounts counts;
    triangulateFaceByMaxArea(square, random, &counts);
    EXPECT_EQ(square.indexes, (std::vector<int>{0, 1, 2, 2, 3, 0}));
    EXPECT_EQ(counts.maxArea, 1);
}

TEST(SurfaceTriangles, MaxAreaRetriesAroundCollinearVerticesWithoutSlivers) {
    // A 6.6 x 2 strip with a T-junction vertex (3) on its top edge: the best triangle leaves the
    // collinear run 2-3-4 alone, so random retries have to find another cut.
    const std::initializer_list<Vec3> points = {{670, -269.25f, -208}, {664.25f, -266, -208}, {664.25f, -266, -206},
                                                {667.875f, -268.125f, -206}, {670, -269.25f, -206}};
    DrawSurface ds = faceFrom(points);
    LibcRandom random;
    TriangulationCounts counts;
    triangulateFaceByMaxArea(ds, random, &counts);
    ASSERT_EQ(ds.indexes.size(), 9u);
    EXPECT_EQ(counts.maxArea, 1);
    double area = 0;
    for (size_t i = 0; i < 9; i += 3) {
        const double a = triangleArea2x(xyzOf(ds.verts[size_t(ds.indexes[i])]), xyzOf(ds.verts[size_t(ds.indexes[i + 1])]),
                                        xyzOf(ds.verts[size_t(ds.indexes[i + 2])]));
        EXPECT_GE(a, 1.0);
        area += a;
    }
    double fan = 0;  // the face's area, from a fan around vertex 0
    for (size_t i = 1; i + 1 < 5; ++i)
        fan += triangleArea2x(xyzOf(ds.verts[0]), xyzOf(ds.verts[i]), xyzOf(ds.verts[i + 1]));
    EXPECT_NEAR(area, fan, 1e-3);  // the whole face, once
}

TEST(SurfaceTriangles, MaxAreaFallsBackToAStripWhenEverythingIsASliver) {
    DrawSurface thin = faceFrom({{0, 0, 0}, {64, 0, 0}, {64, 0.01f, 0}, {0, 0.01f, 0}});
    LibcRandom random;
    TriangulationCounts counts;
    triangulateFaceByMaxArea(thin, random, &counts);
    EXPECT_EQ(counts.maxArea, 0);
    EXPECT_EQ(counts.strips + counts.fans, 1);
    EXPECT_FALSE(thin.indexes.empty());
}

TEST(LibcRandom, GlibcSequenceWithoutSeed) {
    LibcRandom random;  // glibc rand() without srand: 1804289383, 846930886, 1681692777, ...
    EXPECT_EQ(random.next(), 1804289383);
    EXPECT_EQ(random.next(), 846930886);
    EXPECT_EQ(random.next(), 1681692777);
}

TEST(SurfaceTriangles, VertexCacheOrderRotatesEachTriangleToItsSmallestIndex) {
    std::vector<int> indexes;
    for (int i = 0; i < 8; ++i) indexes.insert(indexes.end(), {i + 2, i + 1, 0});
    std::vector<int> sorted = indexes;
    optimizeForVertexCache(indexes);
    for (size_t i = 0; i < indexes.size(); i += 3) {
        EXPECT_LT(indexes[i], indexes[i + 1]);
        EXPECT_LT(indexes[i], indexes[i + 2]);
    }
    std::vector<int> a = indexes, b = sorted;
    std::sort(a.begin(), a.end());
    std::sort(b.begin(), b.end());
    EXPECT_EQ(a, b);  // same triangles, reordered
    std::vector<int> small{2, 1, 0};
    optimizeForVertexCache(small);
    EXPECT_EQ(small, (std::vector<int>{2, 1, 0}));  // 16 indexes or fewer stay as they are
}

TEST(SurfaceClassify, LightmapAxisFollowsTheDominantComponent) {
    EXPECT_EQ(lightmapAxisForNormal({0, 0, -1}), (Vec3{0, 0, -1}));
    EXPECT_EQ(lightmapAxisForNormal({0.6f, 0.8f, 0}), (Vec3{0, 1, 0}));
    EXPECT_EQ(lightmapAxisForNormal({0.7071f, 0, 0.7071f}), (Vec3{0, 0, 1}));  // Z wins ties
    EXPECT_EQ(lightmapAxisForNormal({0, 0, 0}), (Vec3{0, 0, 0}));
    EXPECT_TRUE(std::signbit(lightmapAxisForNormal({0, 0, -1}).x));  // printed as -0.000000
}

TEST(SurfaceClassify, FlatFacesGetAPlaneCurvedOnesDoNot) {
    PlaneSet planes;
    DrawSurface flat = faceFrom({{0, 0, 8}, {0, 64, 8}, {64, 64, 8}});
    flat.kind = SurfaceKind::Triangles;
    ClassifyOptions options;
    classifySurface(flat, planes, options);
    EXPECT_TRUE(flat.planar);
    ASSERT_GE(flat.planeNum, 0);
    EXPECT_DOUBLE_EQ(planes[flat.planeNum].dist(), 8.0);
    EXPECT_EQ(flat.sampleSize, 0);  // triangle models are vertex lit

    DrawSurface bent = faceFrom({{0, 0, 0}, {0, 64, 4}, {64, 64, 0}});
    bent.kind = SurfaceKind::Face;
    bent.sampleSize = 0;
    bent.lightmapScale = 2;
    classifySurface(bent, planes, options);
    EXPECT_FALSE(bent.planar);
    EXPECT_EQ(bent.planeNum, -1);
    EXPECT_EQ(bent.lightmapAxis, (Vec3{0, 0, 1}));  // every normal faces +Z
    EXPECT_EQ(bent.sampleSize, 32);
}

TEST(SurfaceClassify, TextureBiasMovesCoordinatesNearZero) {
    DrawSurface ds = faceFrom({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    ds.verts[0].st[0] = 10.25f;
    ds.verts[1].st[0] = 11.75f;
    ds.verts[2].st[0] = 10.5f;
    ds.verts[2].st[1] = -3.5f;
    biasSurfaceTextures(ds);
    EXPECT_FLOAT_EQ(ds.verts[0].st[0], -0.75f);  // floor(11.0) taken off
    EXPECT_FLOAT_EQ(ds.verts[1].st[0], 0.75f);
    EXPECT_FLOAT_EQ(ds.verts[2].st[1], -1.5f);  // floor(-1.75) = -2
}

TEST(PatchSurfaces, GridNormalsOfAFlatPatchPointOneWay) {
    std::vector<bsp::DrawVert> verts(9);
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 3; ++x) {
            verts[size_t(y * 3 + x)].xyz[0] = float(x * 32);
            verts[size_t(y * 3 + x)].xyz[1] = float(y * 32);
        }
    makeGridNormals(verts, 3, 3);
    for (const bsp::DrawVert& v : verts) {
        EXPECT_FLOAT_EQ(std::fabs(v.normal[2]), 1.0f);
        EXPECT_FLOAT_EQ(v.normal[2], verts[0].normal[2]);
    }
}

TEST(PatchSurfaces, CollinearControlPointsAreDegenerate) {
    map::MapPatch p;
    p.width = p.height = 3;
    for (int i = 0; i < 9; ++i) p.control.push_back({Vec3{float(i), float(2 * i), 0}, {0, 0}});
    EXPECT_TRUE(isDegeneratePatch(p));
    p.control[4].xyz.z = 5;
    EXPECT_FALSE(isDegeneratePatch(p));
}

TEST(SurfaceFilter, FacesReferenceOnlyOpenLeaves) {
    // A tree split at x = 0: the front leaf is open, the back one opaque.
    PlaneSet planes;
    const int split = planes.find({{1, 0, 0}, 0});
    Tree tree;
    tree.nodes.resize(3);
    tree.head = 0;
    tree.nodes[0].planeNum = split & ~1;
    tree.nodes[0].children[0] = 1;
    tree.nodes[0].children[1] = 2;
    tree.nodes[2].opaque = true;
    DrawSurface crossing = faceFrom({{-32, 0, 0}, {-32, 64, 0}, {32, 64, 0}, {32, 0, 0}});
    EXPECT_EQ(filterSurfaceIntoTree(crossing, tree, planes, 7), 1);
    EXPECT_EQ(tree.nodes[1].drawSurfaces, (std::vector<int>{7}));
    EXPECT_TRUE(tree.nodes[2].drawSurfaces.empty());
    DrawSurface behind = faceFrom({{-32, 0, 0}, {-32, 64, 0}, {-16, 64, 0}});
    EXPECT_EQ(filterSurfaceIntoTree(behind, tree, planes, 8), 0);
}

TEST(TJunctions, AFaceTakesTheVertexItsNeighbourHasOnItsEdge) {
    // A 128-wide floor face beside two 64-wide faces: the floor's shared edge gets their middle
    // vertex, with the texture coordinate interpolated and the T-junction mark set.
    std::vector<DrawSurface> surfaces;
    surfaces.push_back(faceFrom({{0, 0, 0}, {0, 128, 0}, {128, 128, 0}, {128, 0, 0}}));
    surfaces.push_back(faceFrom({{128, 0, 0}, {128, 64, 0}, {192, 64, 0}, {192, 0, 0}}));
    surfaces.push_back(faceFrom({{128, 64, 0}, {128, 128, 0}, {192, 128, 0}, {192, 64, 0}}));
    for (DrawSurface& ds : surfaces) ds.kind = SurfaceKind::Face;
    surfaces[0].verts[2].st[1] = 1;  // t is 1 at (128 128) and 0 at (128 0)
    const TJunctionCounts counts = fixTJunctions(surfaces);
    EXPECT_EQ(counts.addedVerts, 1);
    ASSERT_EQ(surfaces[0].verts.size(), 5u);
    ASSERT_EQ(surfaces[0].tjunctionVerts.size(), 5u);
    int added = -1;
    for (size_t i = 0; i < 5; ++i)
        if (surfaces[0].tjunctionVerts[i]) added = int(i);
    ASSERT_GE(added, 0);
    EXPECT_EQ(Vec3::fromArray(surfaces[0].verts[size_t(added)].xyz), (Vec3{128, 64, 0}));
    EXPECT_FLOAT_EQ(surfaces[0].verts[size_t(added)].st[1], 0.5f);
    EXPECT_EQ(surfaces[1].verts.size(), 4u);  // nothing lies inside their edges
    EXPECT_EQ(surfaces[2].verts.size(), 4u);
}

// The edge line counts below are q3map2 2.5.17n's (-v) on maps cut down from oacmpdm5 to the
// brushes that hold these faces.
TEST(TJunctions, AFaceRegistersItsClosingEdgeFirst) {
    // A 0.125-thick side of a jump pad: its closing edge, along y, creates the line that then holds
    // both short vertical edges and the other long one (the first edge, vertical, made two lines).
    std::vector<DrawSurface> surfaces;
    surfaces.push_back(faceFrom({{-696, -400, 0.25f}, {-696, -400, 0.125f}, {-696, -344, 0.125f}, {-696, -344, 0.25f}}));
    surfaces[0].kind = SurfaceKind::Face;
    EXPECT_EQ(fixTJunctions(surfaces).axialLines, 1);
}

TEST(TJunctions, AxialEdgesNormaliseExactly) {
    // 41 units: a float reciprocal makes the direction 0.99999994 long, which sent these edges to
    // the non-axial pass.
    std::vector<DrawSurface> surfaces;
    surfaces.push_back(faceFrom({{0, 0, 0}, {0, 41, 0}, {41, 41, 0}, {41, 0, 0}}));
    surfaces[0].kind = SurfaceKind::Face;
    const TJunctionCounts counts = fixTJunctions(surfaces);
    EXPECT_EQ(counts.axialLines, 4);
    EXPECT_EQ(counts.nonAxialLines, 0);
}

TEST(TJunctions, AHorizontalLineHasAVerticalPlane) {
    // The far end of the second edge is 0.286 beside the first edge's line, within 0.25 of both
    // tilted planes the older MakeNormalVectors made, but not of the vertical one: two lines.
    std::vector<DrawSurface> surfaces;
    surfaces.push_back(faceFrom({{-752, 168, 0}, {-744, 163.5f, 0}, {-752, 163.5f, 0}}));
    surfaces.push_back(faceFrom({{-650.75f, 111.375f, 0}, {-736, 159, 0}, {-736, 111.375f, 0}}));
    for (DrawSurface& ds : surfaces) ds.kind = SurfaceKind::Face;
    EXPECT_EQ(fixTJunctions(surfaces).nonAxialLines, 2);
}

TEST(TJunctions, NearlyCoincidentVerticesAreWelded) {
    std::vector<DrawSurface> surfaces;
    surfaces.push_back(faceFrom({{0, 0, 0}, {0, 64, 0}, {0.05f, 64, 0}, {64, 64, 0}, {64, 0, 0}}));
    surfaces[0].kind = SurfaceKind::Face;
    fixTJunctions(surfaces);
    ASSERT_EQ(surfaces[0].verts.size(), 4u);
    surfaces.push_back(faceFrom({{0, 0, 0}, {0.05f, 0, 0}, {0, 0.05f, 0}}));
    surfaces[1].kind = SurfaceKind::Face;
    EXPECT_EQ(fixTJunctions(surfaces).broken, 1);
    EXPECT_EQ(surfaces[1].kind, SurfaceKind::Bad);
}

TEST(ModelSurfaces, RenameAppendsBspOrRmgBspToTheShaderName) {
    // A game folder with one model, read through the VFS as a compile would.
    const std::filesystem::path root =
        std::filesystem::temp_directory_path() / ("q3bsp-rename-" + std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()));
    std::filesystem::create_directories(root / "baseq3/models/test");
    const auto bytes = model::test::md3Image({{0, 0, 0}, {64, 0, 0}, {0, 64, 0}}, {{0, 2, 1}}, {{{0, 0}}, {{1, 0}}, {{0, 1}}});
    writeFileAtomic(root / "baseq3/models/test/box.md3", std::string(bytes.begin(), bytes.end()));
    static Log log(false);
    static const ShaderTable shaders = test::commonShaders(log);
    VfsOptions vfsOptions;
    vfsOptions.basePaths = {root};
    const Vfs vfs(vfsOptions, log);
    const map::MapFile file = map::parseMap(
        test::worldspawn(test::hollowRoom({0, 0, 0}, {256, 256, 256})) +
            "{\n\"classname\" \"misc_model\"\n\"model\" \"models/test/box.md3\"\n\"origin\" \"64 64 64\"\n}\n"
            "{\n\"classname\" \"misc_model\"\n\"model\" \"models/test/box.md3\"\n\"origin\" \"96 64 64\"\n"
            "\"spawnflags\" \"1\"\n}\n",
        "test.map");
    LoadedMap map = loadMapForBsp(file, shaders, {}, log);
    std::vector<DrawSurface> plain, renamed;
    std::vector<Brush> clip;
    addModelSurfaces(map.entities[0], true, map, {file, shaders, &vfs}, plain, clip, log);
    addModelSurfaces(map.entities[0], true, map, {file, shaders, &vfs, true}, renamed, clip, log);
    std::filesystem::remove_all(root);
    ASSERT_EQ(plain.size(), 2u);
    ASSERT_EQ(renamed.size(), 2u);
    EXPECT_EQ(map.shaderName(*plain[0].shader), "models/test/skin");
    EXPECT_EQ(map.shaderName(*renamed[0].shader), "models/test/skin_BSP");
    EXPECT_EQ(map.shaderName(*renamed[1].shader), "models/test/skin_RMG_BSP");
}

TEST(ModelTransform, YawThenScaleThenOrigin) {
    const ModelTransform t = ModelTransform::place({100, 0, 0}, 0, 90, 0, {2, 2, 2});
    const Vec3 p = t.point({1, 0, 0});
    EXPECT_NEAR(p.x, 100, 1e-5);
    EXPECT_NEAR(p.y, 2, 1e-5);
    EXPECT_FALSE(t.leftHanded());
    EXPECT_TRUE(ModelTransform::place({}, 0, 0, 0, {-1, 1, 1}).leftHanded());
    Vec3 n = t.normal({0, 1, 0});
    normalizeInPlace(n);
    EXPECT_NEAR(n.x, -1, 1e-5);
}

TEST(SurfaceExtraFile, DefaultBlockThenOnlyWhatDiffers) {
    Log log(false);
    const ShaderTable shaders = test::commonShaders(log);
    std::unique_ptr<test::CompiledMap> c = test::compileMapText(test::worldspawn(test::boxBrush({0, 0, 0}, {64, 64, 64})));
    DrawSurface a = faceFrom({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    a.kind = SurfaceKind::Face;
    a.shader = &shaders.find("textures/base/wall");
    a.planar = true;
    a.indexes = {0, 1, 2};
    a.sampleSize = 16;
    a.lightmapAxis = -Vec3{0, 0, 1};
    DrawSurface b = a;
    b.kind = SurfaceKind::Patch;
    b.planar = false;
    b.indexes.clear();
    b.mapEntityNum = 3;
    b.castShadows = 0;
    b.sampleSize = 8;
    b.longestCurve = 12.5f;
    b.lightmapAxis = {0, 0, 0};
    DrawSurface d = a;  // an entity whose ambient equals the world's: nothing written
    d.mapEntityNum = 2;
    // Worldspawn "_color" "1 0.5 0.25" "ambient" "4"; entity 2 the same; entity 3 "_ambient" "5".
    std::vector<EntitySurfaceParams> params(4);
    params[0].ambientColor = params[2].ambientColor = {4, 2, 1};
    params[3].ambientColor = {5, 5, 5};
    const std::string text = surfaceExtraText({&a, &b, &d}, 16, c->map, params);
    EXPECT_EQ(text,
              "default\n{\n\tcastShadows 1\n\treceiveShadows 1\n\tsampleSize 16\n"
              "\tambientColor ( 4.000000 2.000000 1.000000 )\n\tlongestCurve 0.000000\n}\n\n"
              "0 // ESurfaceType::Face V: 3 I: 3 planar\n{\n\tshader textures/base/wall\n"
              "\tlightmapAxis ( -0.000000 -0.000000 -1.000000 )\n}\n\n"
              "1 // ESurfaceType::Patch V: 3 I: 0 \n{\n\tshader textures/base/wall\n\tentity 3\n"
              "\tcastShadows 0\n\tsampleSize 8\n\tambientColor ( 5.000000 5.000000 5.000000 )\n"
              "\tlongestCurve 12.500000\n}\n\n"
              "2 // ESurfaceType::Face V: 3 I: 3 planar\n{\n\tshader textures/base/wall\n\tentity 2\n"
              "\tlightmapAxis ( -0.000000 -0.000000 -1.000000 )\n}\n\n");
}

// The ambient colour of an entity: _color (white when zero or missing) times _ambient, else ambient.
TEST(SurfaceExtraFile, EntityAmbientIsColorTimesAmbient) {
    auto ambientOf = [](const std::string& keys) {
        const map::MapFile file = map::parseMap("{\n\"classname\" \"worldspawn\"\n" + keys + "}\n", "a.map");
        return entitySurfaceParams(file.entities.at(0), true).ambientColor;
    };
    EXPECT_EQ(ambientOf("\"_color\" \"1 0.5 0.25\"\n\"ambient\" \"4\"\n"), (Vec3{4, 2, 1}));
    EXPECT_EQ(ambientOf("\"_ambient\" \"3\"\n\"ambient\" \"9\"\n"), (Vec3{3, 3, 3}));
    EXPECT_EQ(ambientOf("\"_color\" \"0 0 0\"\n\"ambient\" \"2\"\n"), (Vec3{2, 2, 2}));
    EXPECT_EQ(ambientOf("\"_color\" \"0.5 0.5 2\"\n\"_ambient\" \"-2\"\n"), (Vec3{-1, -1, -4}));
    EXPECT_EQ(ambientOf("\"_color\" \"1 0 0\"\n"), (Vec3{0, 0, 0}));
}

// A whole compile of a map text with the test shaders (default 64x64 texture sizes).
CompiledBsp compileText(const std::string& text, BspCompileOptions options = {}, MapLoadOptions load = {}) {
    static Log log(false);
    static const ShaderTable shaders = test::commonShaders(log);
    static std::vector<std::unique_ptr<test::CompiledMap>> keep;  // the loaded map outlives the result
    auto c = std::make_unique<test::CompiledMap>();
    c->file = map::parseMap(text, "test.map");
    c->map = loadMapForBsp(c->file, shaders, load, log);
    const TextureSizes textures;
    CompiledBsp out = compileBsp({c->map, c->file, shaders, textures}, options, log);
    keep.push_back(std::move(c));
    return out;
}

const std::string kBoxRoom = test::worldspawn(test::hollowRoom({64, 64, 64}, {448, 448, 320})) +
                             test::pointEntity("info_player_deathmatch", {256, 256, 128});

TEST(BspCompile, SealedRoomHasSixInwardFacesInItsOneLeaf) {
    const CompiledBsp out = compileText(kBoxRoom);
    EXPECT_NO_THROW(bsp::validateBsp(out.bsp, "room"));
    ASSERT_EQ(out.bsp.surfaces.size(), 6u);
    for (const bsp::Surface& s : out.bsp.surfaces) {
        EXPECT_EQ(s.surfaceType, bsp::MST_PLANAR);
        EXPECT_EQ(s.numVerts, 4);
        EXPECT_EQ(s.numIndexes, 6);
        EXPECT_EQ(s.lightmapNum, bsp::kLightmapByVertex);
        EXPECT_EQ(s.fogNum, -1);
        // Inward faces: the normal points to the room's centre.
        const bsp::DrawVert& v = out.bsp.drawVerts[size_t(s.firstVert)];
        const Vec3 toCentre = Vec3{256, 256, 192} - Vec3::fromArray(v.xyz);
        EXPECT_GT(dot(toCentre, Vec3::fromArray(v.normal)), 0);
    }
    int open = 0;
    for (size_t i = 1; i < out.bsp.leafs.size(); ++i)  // leaf 0 is the dummy
        if (out.bsp.leafs[i].cluster >= 0) {
            ++open;
            EXPECT_EQ(out.bsp.leafs[i].numLeafSurfaces, 6);
        }
    EXPECT_EQ(open, 1);
    EXPECT_EQ((std::vector<int32_t>(out.bsp.drawIndexes.begin(), out.bsp.drawIndexes.begin() + 6)),
              (std::vector<int32_t>{0, 1, 2, 0, 2, 3}));  // the seeded quad
    EXPECT_LT(out.bsp.drawIndexes.size(), 6u + 6u * 6);   // equal strips share their run
    EXPECT_NE(out.surfaceExtra.find("5 // ESurfaceType::Face V: 4 I: 6 planar"), std::string::npos);
    EXPECT_FALSE(out.world.leaked);
}

TEST(BspCompile, NodrawFacesAreNotDrawnAndBrushModelsGetTheirOwnSurfaces) {
    const std::string map =
        test::worldspawn(test::hollowRoom({64, 64, 64}, {448, 448, 320}, 16, "common/caulk") +
                         test::boxBrush({64, 64, 48}, {448, 448, 64})) +
        "{\n\"classname\" \"func_door\"\n" + test::boxBrush({200, 200, 64}, {232, 232, 128}) + "}\n" +
        test::pointEntity("info_player_deathmatch", {256, 256, 128});
    const CompiledBsp out = compileText(map);
    ASSERT_EQ(out.bsp.models.size(), 2u);
    EXPECT_EQ(out.bsp.models[0].numSurfaces, 1);  // only the floor's top: the caulk room draws nothing
    // Culling only compares brushes of one entity: the door's bottom on the floor stays.
    EXPECT_EQ(out.bsp.models[1].numSurfaces, 6);
    EXPECT_EQ(out.bsp.models[1].firstSurface, 1);
    const bsp::Leaf& doorLeaf = out.bsp.leafs.back();
    EXPECT_EQ(doorLeaf.numLeafSurfaces, 6);
    EXPECT_EQ(out.bsp.leafSurfaces[size_t(doorLeaf.firstLeafSurface)], 1);
}

TEST(BspCompile, FlaresOnlyWithTheOption) {
    const std::string map = kBoxRoom + "{\n\"classname\" \"light\"\n\"origin\" \"256 256 300\"\n\"_flare\" \"1\"\n"
                                       "\"_color\" \"1 0.5 0\"\n}\n";
    EXPECT_EQ(compileText(map).bsp.surfaces.size(), 6u);
    BspCompileOptions options;
    options.flares = true;
    const CompiledBsp out = compileText(map, options);
    ASSERT_EQ(out.bsp.surfaces.size(), 7u);
    const bsp::Surface& flare = out.bsp.surfaces.back();
    EXPECT_EQ(flare.surfaceType, bsp::MST_FLARE);
    EXPECT_EQ(flare.numVerts, 0);
    EXPECT_EQ(Vec3::fromArray(flare.lightmapOrigin), (Vec3{256, 256, 300}));
    EXPECT_EQ(Vec3::fromArray(flare.lightmapVecs[0]), (Vec3{1, 0.5f, 0}));  // the light's colour
    EXPECT_EQ(Vec3::fromArray(flare.lightmapVecs[2]), (Vec3{0, 0, -1}));    // no target: pointing down
    EXPECT_STREQ(out.bsp.shaders[size_t(flare.shaderNum)].name, "flareshader");
    EXPECT_NE(out.surfaceExtra.find("6 // ESurfaceType::Flare V: 0 I: 0 \n"), std::string::npos);
}

TEST(BspCompile, SkyFixAddsTheSixBoxImagesOnceAsShaderOnlySurfaces) {
    // A room whose ceiling is two sky brushes: both sky faces share one set of image surfaces.
    const std::string map =
        test::worldspawn(test::hollowRoom({64, 64, 64}, {448, 448, 320}) +
                         test::boxBrush({64, 64, 300}, {256, 448, 320}, "skies/stars") +
                         test::boxBrush({256, 64, 300}, {448, 448, 320}, "skies/stars")) +
        test::pointEntity("info_player_deathmatch", {256, 256, 128});
    const CompiledBsp plain = compileText(map);
    BspCompileOptions options;
    options.skyFix = true;
    const CompiledBsp fixed = compileText(map, options);
    ASSERT_EQ(fixed.bsp.surfaces.size(), plain.bsp.surfaces.size() + 6);
    std::vector<std::string> images;
    for (size_t i = 0; i < fixed.bsp.surfaces.size(); ++i) {
        const bsp::Surface& s = fixed.bsp.surfaces[i];
        if (s.surfaceType != bsp::MST_FLARE) continue;
        images.push_back(fixed.bsp.shaders[size_t(s.shaderNum)].name);
        EXPECT_EQ(s.numVerts, 0);
        EXPECT_EQ(Vec3::fromArray(s.lightmapOrigin), (Vec3{0, 0, 0}));
        for (int32_t ref : fixed.bsp.leafSurfaces) EXPECT_NE(ref, int32_t(i));  // drawn by no leaf
    }
    EXPECT_EQ(images, (std::vector<std::string>{"env/stars_lf", "env/stars_rt", "env/stars_ft", "env/stars_bk",
                                                "env/stars_up", "env/stars_dn"}));
    EXPECT_NE(fixed.surfaceExtra.find("// ESurfaceType::Shader V: 0 I: 0 \n{\n\tshader env/stars_lf\n"
                                      "\tcastShadows 0\n\treceiveShadows 0\n"),
              std::string::npos);
}

TEST(BspCompile, AutocaulkListsTheWorldBrushesSidesAndStops) {
    // Six walls and a func_group pillar: the pillar stays its own entity, so only the walls are
    // listed, each with its one inner side kept and the rest caulkable.
    const std::string map = test::worldspawn(test::hollowRoom({64, 64, 64}, {448, 448, 320})) +
                            "{\n\"classname\" \"func_group\"\n" + test::boxBrush({200, 200, 64}, {232, 232, 320}) +
                            "}\n" + test::pointEntity("info_player_deathmatch", {128, 128, 128});
    BspCompileOptions options;
    options.autocaulk = true;
    MapLoadOptions load;
    load.keepGroups = true;
    const CompiledBsp out = compileText(map, options, load);
    EXPECT_TRUE(out.stoppedForAutocaulk);
    EXPECT_TRUE(out.bsp.surfaces.empty());
    std::istringstream lines(out.autocaulk);
    int count = 0;
    for (std::string line; std::getline(lines, line); ++count) {
        const std::string letters = line.substr(line.find(' ') + 1);
        EXPECT_EQ(letters.size(), 6u) << line;  // no bevels either
        EXPECT_EQ(std::count(letters.begin(), letters.end(), '-'), 1) << line;
        EXPECT_EQ(std::count(letters.begin(), letters.end(), 'c'), 5) << line;
    }
    EXPECT_EQ(count, 6);
}

TEST(BspCompile, FogHullIsABoxAroundTheWorldSeenFromEveryOpenLeaf) {
    const std::string map = test::worldspawn(test::hollowRoom({64, 64, 64}, {448, 448, 320}),
                                             "\"_foghull\" \"skies/stars\"\n") +
                            test::pointEntity("info_player_deathmatch", {256, 256, 128});
    const CompiledBsp out = compileText(map);
    ASSERT_EQ(out.bsp.surfaces.size(), 7u);  // the six walls, then the hull
    const bsp::Surface& hull = out.bsp.surfaces.back();
    EXPECT_STREQ(out.bsp.shaders[size_t(hull.shaderNum)].name, "textures/skies/stars");
    EXPECT_EQ(hull.surfaceType, bsp::MST_TRIANGLE_SOUP);
    EXPECT_EQ(hull.numVerts, 8);
    EXPECT_EQ(hull.numIndexes, 36);
    // The walls span 48..464 and 48..336: the hull lies 128 beyond.
    const bsp::DrawVert& first = out.bsp.drawVerts[size_t(hull.firstVert)];
    EXPECT_EQ(Vec3::fromArray(first.xyz), (Vec3{-80, -80, -80}));
    const bsp::DrawVert& last = out.bsp.drawVerts[size_t(hull.firstVert + 7)];
    EXPECT_EQ(Vec3::fromArray(last.xyz), (Vec3{592, -80, 464}));
    int referencing = 0;
    for (int32_t ref : out.bsp.leafSurfaces) referencing += ref == 6;
    EXPECT_EQ(referencing, 1);  // the room's one open leaf
    EXPECT_NE(out.surfaceExtra.find("6 // ESurfaceType::Foghull V: 8 I: 36 \n"), std::string::npos);
}

TEST(BspCompile, DebugPortalsDrawThePortalOfARoomAcrossABlockBoundary) {
    // x = 1024 cuts the room in two leaves: one passable portal between them.
    const std::string map = test::worldspawn(test::hollowRoom({900, 64, 64}, {1100, 448, 320})) +
                            test::pointEntity("info_player_deathmatch", {950, 256, 128});
    EXPECT_EQ(compileText(map).bsp.surfaces.size(), 6u);  // the walls' two halves make one hull each
    BspCompileOptions options;
    options.debugPortals = true;
    const CompiledBsp out = compileText(map, options);
    ASSERT_EQ(out.bsp.surfaces.size(), 7u);
    const bsp::Surface& portal = out.bsp.surfaces.back();
    EXPECT_STREQ(out.bsp.shaders[size_t(portal.shaderNum)].name, "debugportals");
    ASSERT_EQ(portal.numVerts, 4);
    for (int i = 0; i < 4; ++i) {
        const bsp::DrawVert& v = out.bsp.drawVerts[size_t(portal.firstVert + i)];
        EXPECT_EQ(v.xyz[0], 1024.0f);
        EXPECT_EQ(v.color[3], 32);
    }
}

TEST(BspCompile, DebugInsetPullsEveryCornerIntoItsFace) {
    BspCompileOptions options;
    options.emit.debugInset = true;
    const CompiledBsp out = compileText(kBoxRoom, options);
    ASSERT_EQ(out.bsp.surfaces.size(), 6u);
    const Vec3 lo{64, 64, 64}, hi{448, 448, 320};
    for (const bsp::Surface& s : out.bsp.surfaces) {
        for (int i = 0; i < s.numVerts; ++i) {
            const Vec3 p = Vec3::fromArray(out.bsp.drawVerts[size_t(s.firstVert + i)].xyz);
            int onWall = 0, inside = 0;
            for (int k = 0; k < 3; ++k) {
                onWall += p[k] == lo[k] || p[k] == hi[k];
                inside += p[k] > lo[k] + 0.5f && p[k] < hi[k] - 0.5f;
            }
            EXPECT_EQ(onWall, 1);  // still on its wall...
            EXPECT_EQ(inside, 2);  // ...but away from the wall's edges
        }
    }
}

TEST(ShaderFlagRules, NoObSparesSurfaceparmObAndGlobalFlagsClearThenSet) {
    ShaderFlagRules rules;
    ShaderInfo plain = makeImplicitShader("textures/base/wall");
    ShaderInfo marked = plain;
    ASSERT_TRUE(applySurfaceParm("ob", marked));
    EXPECT_EQ(rules.surfaceFlags(plain), 0u);
    rules.noOb = true;
    EXPECT_EQ(rules.surfaceFlags(plain), surfaceflags::NoOb);
    EXPECT_EQ(rules.surfaceFlags(marked), 0u);
    EXPECT_TRUE(rules.addGlobalFlag("slick"));
    EXPECT_TRUE(rules.addGlobalFlag("nodamage"));
    EXPECT_EQ(rules.globalSurfaceFlags, surfaceflags::Slick | surfaceflags::NoDamage);
    EXPECT_TRUE(rules.addGlobalFlag("default"));  // clears every surface flag, as q3map2 applies it
    EXPECT_EQ(rules.globalSurfaceFlags, 0u);
    EXPECT_FALSE(rules.addGlobalFlag("no-such-parm"));
}

TEST(BspCompile, NoObAndGlobalFlagsReachEveryShaderEntry) {
    MapLoadOptions load;
    load.flagRules.noOb = true;
    ASSERT_TRUE(load.flagRules.addGlobalFlag("slick"));
    const CompiledBsp plain = compileText(kBoxRoom);
    const CompiledBsp flagged = compileText(kBoxRoom, {}, load);
    ASSERT_EQ(flagged.bsp.shaders.size(), plain.bsp.shaders.size());
    for (size_t i = 0; i < plain.bsp.shaders.size(); ++i)
        EXPECT_EQ(uint32_t(flagged.bsp.shaders[i].surfaceFlags),
                  uint32_t(plain.bsp.shaders[i].surfaceFlags) | surfaceflags::NoOb | surfaceflags::Slick)
            << plain.bsp.shaders[i].name;
}

TEST(BspCompile, AWorldWithoutBrushesIsAnError) {
    EXPECT_THROW(compileText(test::worldspawn("") + test::pointEntity("info_player_deathmatch", {0, 0, 0})),
                 CompileError);
}

TEST(BspCompile, LeakingRoomWritesALineAndNoPortals) {
    const std::string map = test::worldspawn(test::boxBrush({0, 0, 0}, {256, 256, 16})) +
                            test::pointEntity("info_player_deathmatch", {128, 128, 64});
    const CompiledBsp out = compileText(map);
    EXPECT_TRUE(out.world.leaked);
    EXPECT_FALSE(out.world.leakLine.empty());
    EXPECT_TRUE(out.world.portalFile.empty());
}

}  // namespace
}  // namespace q3::bspstage
