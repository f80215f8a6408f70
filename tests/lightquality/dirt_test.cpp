// Dirt mapping: the ray pattern, the per-sample formula against a hand computation, sky hits that do
// not darken, the 3x3 smoothing, and the whole stage darkening a corner but not an open floor nor a
// floor next to sky.
#include <gtest/gtest.h>

#include <cmath>

#include "dirt.h"
#include "../light/light_test_util.h"
#include "quality_scene.h"

namespace q3::light {
namespace {

// Floor 512 x 512 at z = 0 and a wall in the plane x = 0 (y 0..512, z 0..256).
std::vector<SceneSurface> cornerScene(const LightingShader* wallShader = nullptr) {
    return {test::quad({0, 0, 0}, {512, 0, 0}, {0, 512, 0}), test::quad({0, 0, 0}, {0, 512, 0}, {0, 0, 256}, wallShader)};
}

// Sum of 1 - t/depth over q3map2's 48 cone rays (16 azimuths x 3 elevations in 88 degrees) and the
// normal ray, for a point at height 1 and distance d from the wall x = 0, normal +z.
float expectedDirt(float d, float depth, float gain, float scale) {
    double gathered = 0;
    for (int i = 0; i < 16; ++i)
        for (int j = 0; j < 3; ++j) {
            const double azimuth = i * (2 * M_PI / 16), elevation = (j + 0.5) * (88.0 / 3) * M_PI / 180;
            const double dx = std::sin(elevation) * std::cos(azimuth);
            if (dx >= 0) continue;
            const double t = d / -dx;
            if (t <= depth) gathered += 1 - t / depth;
        }
    if (gathered <= 0) return 1;
    double dirt = std::min(1.0, std::pow(gathered / 49, static_cast<double>(gain)));
    dirt = std::min(1.0, dirt * scale);
    return static_cast<float>(1 - dirt);
}

TEST(LightQualityOptions, ParseIntoSettingsAndAreImplemented) {
    const LightOptions o = quality::lightOptions({"-dirty", "-dirtmode", "1", "-dirtdepth", "64", "-dirtscale", "2",
                                                  "-dirtgain", "0.5", "-debugdirt", "-floodlight", "-lowquality",
                                                  "-export", "-lightmapatlas", "pages.png"});
    const DirtSettings d = dirtSettingsFromOptions(o);
    EXPECT_TRUE(o.dirty);
    EXPECT_EQ(d.mode, 1);
    EXPECT_EQ(d.depth, 64.0f);
    EXPECT_EQ(d.scale, 2.0f);
    EXPECT_EQ(d.gain, 0.5f);
    EXPECT_TRUE(d.debug);
    EXPECT_TRUE(o.floodlight && o.lowQuality && o.exportLightmaps);
    EXPECT_EQ(o.lightmapAtlas, "pages.png");
    EXPECT_THROW(quality::lightOptions({"-dirtmode", "2"}), cli::UsageError);
    EXPECT_THROW(quality::lightOptions({"-dirtdepth", "0"}), cli::UsageError);
    for (const auto& option : lightOptionTable()) {
        for (const std::string& name : option.info.names) {
            if (name.rfind("-dirt", 0) == 0 || name == "-dirty" || name == "-floodlight" || name == "-lowquality" ||
                name == "-export" || name == "-lightmapatlas") {
                EXPECT_TRUE(option.info.implemented) << name;
            }
        }
    }
}

TEST(Dirt, ConeIs48DirectionsWithin88Degrees) {
    const std::vector<Vec3>& cone = dirtConeDirections();
    ASSERT_EQ(cone.size(), 48u);
    for (const Vec3& d : cone) {
        EXPECT_NEAR(length(d), 1.0f, 1e-5f);
        EXPECT_GT(d.z, std::cos(degToRad(88)));
    }
    EXPECT_NEAR(std::acos(cone[0].z), degToRad(88.0f / 6), 1e-5f);  // first elevation: half a step
    EXPECT_NEAR(std::acos(cone[2].z), degToRad(88.0f * 5 / 6), 1e-5f);
    EXPECT_NEAR(std::atan2(cone[3].y, cone[3].x), degToRad(22.5f), 1e-5f);  // next azimuth
}

TEST(HitScene, NearestHitDistanceSkyAndStreamsAgree) {
    LightingShader sky;
    sky.sky = true;
    std::vector<SceneSurface> surfaces = cornerScene();
    surfaces.push_back(test::quad({512, 0, 0}, {0, 512, 0}, {0, 0, 256}, &sky));
    HitScene scene(surfaces, {});
    const RayHit wall = scene.nearest({100, 256, 10}, {-1, 0, 0}, 0, 1000);
    EXPECT_TRUE(wall.hit);
    EXPECT_NEAR(wall.distance, 100, 1e-3f);
    EXPECT_FALSE(wall.sky);
    const RayHit toSky = scene.nearest({100, 256, 10}, {1, 0, 0}, 0, 1000);
    EXPECT_TRUE(toSky.sky);
    EXPECT_NEAR(toSky.distance, 412, 1e-3f);
    EXPECT_FALSE(scene.nearest({100, 256, 10}, {1, 0, 0}, 0, 400).hit);  // beyond tfar
    EXPECT_FALSE(scene.nearest({100, 256, 10}, {0, 0, 1}, 0, 1000).hit);

    std::vector<Vec3> directions;
    for (int i = 0; i < 150; ++i)  // more than one stream chunk
        directions.push_back(normalize(Vec3{std::cos(i * 0.37f), std::sin(i * 0.37f), 0.3f * std::sin(i * 1.3f)}));
    std::vector<RayHit> many(directions.size());
    scene.nearestMany({100, 256, 10}, directions, 0.5f, 300, many);
    for (size_t i = 0; i < directions.size(); ++i) {
        const RayHit one = scene.nearest({100, 256, 10}, directions[i], 0.5f, 300);
        EXPECT_EQ(many[i].hit, one.hit) << i;
        EXPECT_EQ(many[i].sky, one.sky) << i;
        EXPECT_NEAR(many[i].distance, one.distance, 1e-4f) << i;
    }
}

TEST(Dirt, OpenFloorIsUntouched) {
    HitScene scene(cornerScene(), {});
    EXPECT_EQ(dirtForSample({256, 256, 1}, {0, 0, 1}, scene, DirtSettings{}, 0), 1.0f);
}

TEST(Dirt, SampleNearWallMatchesFormula) {
    HitScene scene(cornerScene(), {});
    DirtSettings s;
    for (float d : {8.0f, 16.0f, 40.0f}) {
        const float dirt = dirtForSample({d, 256, 1}, {0, 0, 1}, scene, s, 0);
        EXPECT_NEAR(dirt, expectedDirt(d, 128, 1, 1), 1e-4f) << d;
        EXPECT_LT(dirt, 0.95f) << d;
    }
    s.depth = 64;
    s.gain = 2;
    s.scale = 1.5f;
    EXPECT_NEAR(dirtForSample({16, 256, 1}, {0, 0, 1}, scene, s, 0), expectedDirt(16, 64, 2, 1.5f), 1e-4f);
    s.scale = 100;  // saturates: black
    EXPECT_EQ(dirtForSample({16, 256, 1}, {0, 0, 1}, scene, s, 0), 0.0f);
}

TEST(Dirt, SkyDoesNotDarken) {
    LightingShader sky;
    sky.sky = true;
    HitScene skyScene(cornerScene(&sky), {});
    HitScene wallScene(cornerScene(), {});
    EXPECT_EQ(dirtForSample({16, 256, 1}, {0, 0, 1}, skyScene, DirtSettings{}, 0), 1.0f);
    EXPECT_LT(dirtForSample({16, 256, 1}, {0, 0, 1}, wallScene, DirtSettings{}, 0), 0.9f);
    DirtSettings random;
    random.mode = 1;
    EXPECT_EQ(dirtForSample({16, 256, 1}, {0, 0, 1}, skyScene, random, 7), 1.0f);
}

TEST(Dirt, RandomModeIsRepeatableAndDarkensCorners) {
    HitScene scene(cornerScene(), {});
    DirtSettings s;
    s.mode = 1;
    const Vec3 p{16, 256, 1};
    const float a = dirtForSample(p, {0, 0, 1}, scene, s, dirtSeed(p));
    const float b = dirtForSample(p, {0, 0, 1}, scene, s, dirtSeed(p));
    EXPECT_EQ(a, b);
    EXPECT_LT(a, 0.95f);
    EXPECT_GT(a, 0.3f);
    EXPECT_EQ(dirtForSample({256, 256, 1}, {0, 0, 1}, scene, s, dirtSeed({256, 256, 1})), 1.0f);
    EXPECT_NE(dirtSeed({16, 256, 1}), dirtSeed({16, 272, 1}));
}

TEST(Dirt, LightmapSmoothsOverMappedNeighbours) {
    HitScene scene(cornerScene(), {});
    // A 4 x 1 row: near the wall, two open samples, and an unmapped luxel.
    std::vector<std::optional<SamplePoint>> points(4);
    points[0] = SamplePoint{{16, 256, 1}, {0, 0, 1}};
    points[1] = SamplePoint{{256, 256, 1}, {0, 0, 1}};
    points[2] = SamplePoint{{300, 256, 1}, {0, 0, 1}};
    const float a = expectedDirt(16, 128, 1, 1);
    const std::vector<float> dirt = dirtForLightmap(points, 4, 1, scene, DirtSettings{}, false);
    ASSERT_EQ(dirt.size(), 4u);
    EXPECT_NEAR(dirt[0], (a + 1) / 2, 1e-4f);
    EXPECT_NEAR(dirt[1], (a + 1 + 1) / 3, 1e-4f);
    EXPECT_NEAR(dirt[2], 1.0f, 1e-6f);
    EXPECT_EQ(dirt[3], 0.0f);
    const std::vector<float> clean = dirtForLightmap(points, 4, 1, scene, DirtSettings{}, true);
    EXPECT_EQ(clean[0], 1.0f);
    EXPECT_EQ(clean[1], 1.0f);

    LuxelImage image(4, 1, LuxelState::Mapped);
    image.state[3] = LuxelState::Unmapped;
    for (Vec3& c : image.color) c = {100, 50, 10};
    applyDirt(image, dirt, false);
    EXPECT_NEAR(image.color[0].x, 100 * dirt[0], 1e-3f);
    EXPECT_NEAR(image.color[0].z, 10 * dirt[0], 1e-3f);
    EXPECT_EQ(image.color[3], (Vec3{100, 50, 10}));
    applyDirt(image, dirt, true);
    EXPECT_NEAR(image.color[0].y, 255 * dirt[0], 1e-3f);
}

// Black luxels stay black whatever their dirt, so only the luxels next to a lit one are traced; the
// lit ones come out as if every luxel had been.
TEST(Dirt, OnlyLuxelsNextToLightAreTraced) {
    HitScene scene(cornerScene(), {});
    constexpr int kWidth = 6, kHeight = 3;
    std::vector<std::optional<SamplePoint>> points(kWidth * kHeight);
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x)
            points[size_t(y * kWidth + x)] = SamplePoint{{8.0f + 8.0f * float(x), 256.0f + 8.0f * float(y), 1}, {0, 0, 1}};
    LuxelImage image(kWidth, kHeight, LuxelState::Mapped);
    image.color[size_t(1 * kWidth + 1)] = {40, 40, 40};  // the only lit luxel, next to the wall

    const std::vector<uint8_t> wanted = dirtWantedLuxels(image);
    ASSERT_EQ(wanted.size(), points.size());
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) EXPECT_EQ(wanted[size_t(y * kWidth + x)], x <= 2 ? 1 : 0) << x << "," << y;

    const std::vector<float> all = dirtForLightmap(points, kWidth, kHeight, scene, DirtSettings{}, false);
    const std::vector<float> some = dirtForLightmap(points, kWidth, kHeight, scene, DirtSettings{}, false, nullptr,
                                                    wanted);
    EXPECT_LT(all[size_t(1 * kWidth + 1)], 0.9f);
    EXPECT_EQ(some[size_t(1 * kWidth + 1)], all[size_t(1 * kWidth + 1)]);
    EXPECT_EQ(some[size_t(1 * kWidth + 5)], 1.0f);  // untraced: far from the light
    EXPECT_LT(all[size_t(1 * kWidth + 5)], 1.0f);

    LuxelImage dark(kWidth, kHeight, LuxelState::Mapped);
    for (const uint8_t w : dirtWantedLuxels(dark)) EXPECT_EQ(w, 0);
}

// Floor (0..512)^2 with ambient 100; a wall at x = 0 and a sky wall at x = 512.
bsp::Bsp cornerBsp(const std::string& floorShader) {
    bsp::Bsp b = quality::emptyBsp({floorShader, "textures/test/wall", "textures/test/sky"});
    quality::addQuad(b, {0, 0, 0}, {0, 512, 0}, {512, 0, 0}, 0);    // floor, normal +z
    quality::addQuad(b, {0, 0, 0}, {0, 0, 256}, {0, 512, 0}, 1);    // wall, normal +x
    quality::addQuad(b, {512, 0, 0}, {0, 512, 0}, {0, 0, 256}, 2);  // sky, normal -x
    quality::finish(b, {{"_ambient", "100"}});
    return b;
}

const char* kShaders =
    "textures/test/sky\n{\n\tsurfaceparm sky\n\tsurfaceparm noimpact\n}\n"
    "textures/test/clean\n{\n\tq3map_noDirty\n}\n"
    "textures/test/vertex\n{\n\tsurfaceparm nolightmap\n}\n";

TEST(DirtStage, DarkensCornerButNotOpenFloorNorNextToSky) {
    const bsp::Bsp b = cornerBsp("textures/test/floor");
    const auto corner = quality::luxelNear(b, 0, {16, 256, 0});
    const auto open = quality::luxelNear(b, 0, {256, 256, 0});
    const auto nearSky = quality::luxelNear(b, 0, {496, 256, 0});
    const auto path = quality::writeScene(b, "corner", kShaders);
    ASSERT_EQ(quality::runLight(path, {}), 0);
    const bsp::Bsp plain = bsp::readBsp(path);
    const auto plainCorner = quality::texel(plain, 0, corner[0], corner[1]);
    EXPECT_EQ(plainCorner, quality::texel(plain, 0, open[0], open[1]));

    writeFileAtomic(path, bsp::serializeBsp(b));
    ASSERT_EQ(quality::runLight(path, {"-dirty"}), 0);
    const bsp::Bsp dirty = bsp::readBsp(path);
    const auto c = quality::texel(dirty, 0, corner[0], corner[1]);
    const auto o = quality::texel(dirty, 0, open[0], open[1]);
    const auto s = quality::texel(dirty, 0, nearSky[0], nearSky[1]);
    EXPECT_EQ(o, plainCorner) << "open floor keeps the ambient";
    EXPECT_EQ(s, o) << "sky next to the floor does not darken it";
    EXPECT_LT(c[0], o[0] * 0.9) << c[0] << " vs " << o[0];
    // Exactly the ambient times the 3x3 mean of the per-sample dirt of the luxel columns at x = 0,
    // 16 and 32 (luxel origins sit 1 unit above the floor; the one at x = 0 lies in the wall's plane,
    // where the wall is within the inhibit radius of every ray and this BSP has no solid leaf).
    HitScene scene(cornerScene(), {});
    float sum = 0;
    for (float x : {0.0f, 16.0f, 32.0f}) sum += dirtForSample({x, 256, 1}, {0, 0, 1}, scene, DirtSettings{}, 0);
    EXPECT_NEAR(c[0], 100.0f * sum / 3, 1.0f);

    writeFileAtomic(path, bsp::serializeBsp(b));
    ASSERT_EQ(quality::runLight(path, {"-dirty", "-dirtdebug"}), 0);
    const bsp::Bsp debug = bsp::readBsp(path);
    EXPECT_EQ(quality::texel(debug, 0, open[0], open[1])[0], 255);
    EXPECT_LT(quality::texel(debug, 0, corner[0], corner[1])[0], 235);
}

TEST(Dirt, OccludersWithinTheIgnoreRadiusDoNotCount) {
    HitScene scene(cornerScene(), {});
    const float all = dirtForSample({1, 256, 1}, {0, 0, 1}, scene, DirtSettings{}, 0, 0.0f);
    const float far = dirtForSample({1, 256, 1}, {0, 0, 1}, scene, DirtSettings{}, 0, 1.5f);
    EXPECT_LT(all, far);
    EXPECT_LT(far, 1.0f);  // rays that meet the wall further away still darken
    EXPECT_EQ(dirtForSample({16, 256, 1}, {0, 0, 1}, scene, DirtSettings{}, 0, 1.5f),
              dirtForSample({16, 256, 1}, {0, 0, 1}, scene, DirtSettings{}, 0, 0.0f));
    // q3map2's inhibit radius is the default.
    EXPECT_EQ(dirtForSample({1, 256, 1}, {0, 0, 1}, scene, DirtSettings{}, 0), far);
}

// The corner's BSP: one node on the plane x = 0, the open leaf in front (a cluster), structural
// solid behind it (no cluster).
bsp::Bsp wallTreeBsp() {
    bsp::Bsp b;
    b.planes = {{{1, 0, 0}, 0}};
    b.nodes = {{0, {-1, -2}, {-1000, -1000, -1000}, {1000, 1000, 1000}}};
    b.leafs = {{0, 0, {0, -1000, -1000}, {1000, 1000, 1000}, 0, 0, 0, 0},
               {-1, 0, {-1000, -1000, -1000}, {0, 1000, 1000}, 0, 0, 0, 0}};
    return b;
}

TEST(Dirt, RaysIntoStructuralSolidCountHoweverClose) {
    HitScene scene(cornerScene(), {});
    const bsp::Bsp b = wallTreeBsp();
    const BspTree tree(b);
    // Half a unit from the wall: the steep rays meet it within the inhibit radius. Through the
    // surfaces alone they pass; into the solid behind the wall every ray towards it counts.
    const float surfacesOnly = dirtForSample({0.5f, 256, 1}, {0, 0, 1}, scene, DirtSettings{}, 0);
    const float withSolid = dirtForSample({0.5f, 256, 1}, {0, 0, 1}, scene, DirtSettings{}, 0, 1.5f, &tree);
    EXPECT_NEAR(withSolid, expectedDirt(0.5f, 128, 1, 1), 1e-4f);
    EXPECT_LT(withSolid, surfacesOnly - 0.1f);
    // A luxel in the wall's own plane: rays towards the wall enter the solid at once (each adds
    // 1), rays away from it meet nothing; not the black of every ray meeting the wall at t = 0.
    const float onPlane = dirtForSample({0, 256, 1}, {0, 0, 1}, scene, DirtSettings{}, 0, 1.5f, &tree);
    int towardsWall = 0;  // beyond the tree's 0.1-unit on-plane epsilon at the ray's end
    for (const Vec3& d : dirtConeDirections()) towardsWall += d.x * 128 < -0.1f ? 1 : 0;
    EXPECT_EQ(towardsWall, 21);
    EXPECT_NEAR(onPlane, 1.0f - towardsWall / 49.0f, 1e-5f);
    EXPECT_GT(onPlane, 0.45f);
    EXPECT_LT(onPlane, 0.6f);
    // Far from the wall the solid changes nothing.
    EXPECT_EQ(dirtForSample({40, 256, 1}, {0, 0, 1}, scene, DirtSettings{}, 0, 1.5f, &tree),
              dirtForSample({40, 256, 1}, {0, 0, 1}, scene, DirtSettings{}, 0, 1.5f));
}

TEST(Dirt, OpenRaysSkipOnlySurfacesBackedBySolid) {
    // The wall wound as Quake 3 winds a face seen from x > 0, with the solid leaf behind it; the
    // floor has open space below it.
    const std::vector<SceneSurface> surfaces{test::quad({0, 0, 0}, {512, 0, 0}, {0, 512, 0}),
                                             test::quad({0, 0, 0}, {0, 0, 256}, {0, 512, 0})};
    const bsp::Bsp b = wallTreeBsp();
    const BspTree tree(b);
    const SolidBackedTest backed = dirtSolidBacked(tree);
    const std::span<const Vec3, 3> wallTriangle(surfaces[1].xyz.data(), 3);
    EXPECT_TRUE(backed(wallTriangle));
    EXPECT_FALSE(backed(std::span<const Vec3, 3>(surfaces[0].xyz.data(), 3)));
    // Wound the other way the wall's back would be the open room: not backed.
    const std::array<Vec3, 3> reversed{surfaces[1].xyz[0], surfaces[1].xyz[2], surfaces[1].xyz[1]};
    EXPECT_FALSE(backed(reversed));

    const HitScene whole(surfaces, {});
    const HitScene split(surfaces, {}, backed);
    const std::array<Vec3, 2> directions{normalize(Vec3{-1, 0, 0.2f}), normalize(Vec3{0.3f, 0, -1})};
    std::array<RayHit, 2> all, open;
    split.nearestMany({16, 256, 8}, directions, 0, 128, all);
    split.nearestOpenMany({16, 256, 8}, directions, 0, 128, open);
    EXPECT_TRUE(all[0].hit);    // the wall ...
    EXPECT_FALSE(open[0].hit);  // ... which the open part leaves out
    EXPECT_TRUE(all[1].hit && open[1].hit);
    EXPECT_EQ(all[1].distance, open[1].distance);  // the floor stays
    // Without the test the open part is the whole scene.
    whole.nearestOpenMany({16, 256, 8}, directions, 0, 128, open);
    EXPECT_TRUE(open[0].hit && open[1].hit);
    // Every ray that would meet the wall enters the solid behind it: dirt is the same either way.
    for (const Vec3 origin : {Vec3{0.5f, 256, 1}, Vec3{16, 256, 1}, Vec3{40, 100, 1}, Vec3{3, 256, 30}})
        EXPECT_EQ(dirtForSample(origin, {0, 0, 1}, split, DirtSettings{}, 0, 1.5f, &tree),
                  dirtForSample(origin, {0, 0, 1}, whole, DirtSettings{}, 0, 1.5f, &tree));
}

TEST(Dirt, SkyFaceInFrontOfSolidDoesNotDarken) {
    // The wall is a sky face sealing the solid behind it.
    LightingShader sky;
    sky.sky = true;
    HitScene scene(cornerScene(&sky), {});
    const bsp::Bsp b = wallTreeBsp();
    const BspTree tree(b);
    EXPECT_EQ(dirtForSample({16, 256, 1}, {0, 0, 1}, scene, DirtSettings{}, 0, 1.5f, &tree), 1.0f);

    // Luxels from 16 to 400 units away (unmapped luxels between them keep the smoothing out): each
    // luxel's dirt is the one its sample alone gets. The lightmap asks for sky only within reach of
    // its blocks; asking too little would let the solid behind the sky darken the near ones.
    const std::array<float, 5> distances{16, 100, 126, 140, 400};
    std::vector<std::optional<SamplePoint>> points(2 * distances.size());
    for (size_t k = 0; k < distances.size(); ++k)
        points[2 * k] = SamplePoint{{distances[k], 256, 1}, normalize(Vec3{-0.3f, 0.1f, 1})};
    const std::vector<float> dirt =
        dirtForLightmap(points, int(points.size()), 1, scene, DirtSettings{}, false, &tree);
    for (size_t k = 0; k < distances.size(); ++k) {
        const SamplePoint& p = *points[2 * k];
        EXPECT_EQ(dirt[2 * k], dirtForSample(p.origin, p.normal, scene, DirtSettings{}, dirtSeed(p.origin),
                                             kDirtInhibitRadius, &tree))
            << distances[k];
    }
    EXPECT_EQ(dirt[0], 1.0f);  // every ray towards the wall meets sky first
    HitScene plain(cornerScene(), {});
    EXPECT_LT(dirtForLightmap(points, int(points.size()), 1, plain, DirtSettings{}, false, &tree)[0], 0.9f);
}


// The corner (floor, wall at x = 0, sky wall at x = 512) under ambient 100, with a 16 x 16
// vertex-lit tile from `tile` (surface 3).
bsp::Bsp cornerWithVertexTile(Vec3 tile) {
    bsp::Bsp b = quality::emptyBsp({"textures/test/floor", "textures/test/wall", "textures/test/sky", "textures/test/vertex"});
    quality::addQuad(b, {0, 0, 0}, {0, 512, 0}, {512, 0, 0}, 0);
    quality::addQuad(b, {0, 0, 0}, {0, 0, 256}, {0, 512, 0}, 1);
    quality::addQuad(b, {512, 0, 0}, {0, 512, 0}, {0, 0, 256}, 2);
    quality::addQuad(b, tile, {0, 16, 0}, {16, 0, 0}, 3);
    b.surfaces.back().lightmapNum = bsp::kLightmapByVertex;  // as -bsp leaves it
    return b;
}

TEST(DirtStage, VertexLitSurfaceIsDarkenedNearTheWall) {
    // Vertex-lit tiles on the floor: one with vertexes 8 and 24 units from the wall, one in the open.
    // With -dirty the first loses light at every vertex, the second keeps the ambient.
    bsp::Bsp b = cornerWithVertexTile({8, 200, 0.5f});
    quality::addQuad(b, {248, 200, 0.5f}, {0, 16, 0}, {16, 0, 0}, 3);
    b.surfaces.back().lightmapNum = bsp::kLightmapByVertex;
    quality::finish(b, {{"_ambient", "100"}});
    const auto path = quality::writeScene(b, "vertexdirt", kShaders);
    ASSERT_EQ(quality::runLight(path, {}), 0);
    const bsp::Bsp plain = bsp::readBsp(path);
    writeFileAtomic(path, bsp::serializeBsp(b));
    ASSERT_EQ(quality::runLight(path, {"-dirty"}), 0);
    const bsp::Bsp dirty = bsp::readBsp(path);
    for (size_t tile : {3u, 4u}) {
        const bsp::Surface& s = dirty.surfaces[tile];
        ASSERT_LT(s.lightmapNum, 0);  // vertex lit
        for (int v = 0; v < s.numVerts; ++v) {
            const size_t i = static_cast<size_t>(s.firstVert + v);
            EXPECT_EQ(plain.drawVerts[i].color[0], 100);
            if (tile == 3)
                EXPECT_LT(dirty.drawVerts[i].color[0], 90) << "by the wall, vertex " << v;
            else
                EXPECT_EQ(dirty.drawVerts[i].color[0], 100) << "in the open, vertex " << v;
        }
    }
}

TEST(DirtStage, VertexDirtIsTakenAtTheVertexNotWhereTheSearchEnds) {
    // Ambient light only: a darkened vertex is never brighter than the ambient, so the search tries
    // every nudged position and keeps the last; the dirt is still the one at the vertex itself.
    bsp::Bsp b = cornerWithVertexTile({2, 200, 0.5f});
    quality::finish(b, {{"_ambient", "100"}});
    const auto path = quality::writeScene(b, "vertexdirtorigin", kShaders);
    ASSERT_EQ(quality::runLight(path, {"-dirty"}), 0);
    const bsp::Bsp dirty = bsp::readBsp(path);
    HitScene scene(cornerScene(), {});
    const bsp::Surface& s = dirty.surfaces[3];
    for (int v = 0; v < s.numVerts; ++v) {
        const bsp::DrawVert& dv = dirty.drawVerts[static_cast<size_t>(s.firstVert + v)];
        const Vec3 xyz = Vec3::fromArray(dv.xyz);
        const float atVertex = dirtForSample(xyz, {0, 0, 1}, scene, DirtSettings{}, dirtSeed(xyz));
        EXPECT_NEAR(dv.color[0], 100 * atVertex, 1.0f) << "vertex " << v;
        if (xyz.x < 10) {  // by the wall the last nudged position (8 units further on each axis) differs
            const Vec3 last = xyz + Vec3{8, 8, 8};
            EXPECT_GT(dirtForSample(last, {0, 0, 1}, scene, DirtSettings{}, dirtSeed(last)), atVertex + 0.02f);
        }
    }
}

TEST(DirtStage, VertexDirtRaysStopAtStructuralSolid) {
    // The corner with the wall's BSP (structural solid behind x = 0) and a vertex-lit tile whose
    // near vertexes lie half a unit from the wall: their steep rays meet the wall within the
    // inhibit radius, and count because they enter the solid, as they do for luxels.
    bsp::Bsp b = cornerWithVertexTile({0.5f, 200, 0.5f});
    const bsp::Bsp tree = wallTreeBsp();
    b.planes = tree.planes;
    b.nodes = tree.nodes;
    b.leafs = tree.leafs;
    quality::finish(b, {{"_ambient", "100"}});
    const auto path = quality::writeScene(b, "vertexdirtsolid", kShaders);
    ASSERT_EQ(quality::runLight(path, {"-dirty"}), 0);
    const bsp::Bsp dirty = bsp::readBsp(path);
    HitScene scene(cornerScene(), {});
    const bsp::Surface& s = dirty.surfaces[3];
    int near = 0;
    for (int v = 0; v < s.numVerts; ++v) {
        const bsp::DrawVert& dv = dirty.drawVerts[static_cast<size_t>(s.firstVert + v)];
        const Vec3 xyz = Vec3::fromArray(dv.xyz);
        if (xyz.x > 1) continue;
        ++near;
        EXPECT_NEAR(dv.color[0], 100 * expectedDirt(0.5f, 128, 1, 1), 1.0f) << "vertex " << v;
        EXPECT_GT(100 * dirtForSample(xyz, {0, 0, 1}, scene, DirtSettings{}, dirtSeed(xyz)), dv.color[0] + 5.0f)
            << "surfaces alone darken less";
    }
    EXPECT_EQ(near, 2);
}

TEST(DirtStage, NoDirtyShaderKeepsItsLight) {
    const bsp::Bsp b = cornerBsp("textures/test/clean");
    const auto corner = quality::luxelNear(b, 0, {16, 256, 0});
    const auto open = quality::luxelNear(b, 0, {256, 256, 0});
    const auto path = quality::writeScene(b, "clean", kShaders);
    ASSERT_EQ(quality::runLight(path, {"-dirty", "-dirtscale", "4"}), 0);
    const bsp::Bsp lit = bsp::readBsp(path);
    EXPECT_EQ(quality::texel(lit, 0, corner[0], corner[1]), quality::texel(lit, 0, open[0], open[1]));
    EXPECT_GT(quality::texel(lit, 0, open[0], open[1])[0], 90);
}

TEST(DirtStage, SameBytesWhateverTheThreadCount) {
    const bsp::Bsp b = cornerBsp("textures/test/floor");
    const auto path = quality::writeScene(b, "threads", kShaders);
    const std::vector<std::string> args = {"-dirty", "-dirtmode", "1", "-floodlight", "-samples", "2"};
    ASSERT_EQ(quality::runLight(path, args, 1), 0);
    const std::vector<uint8_t> one = readFileBytes(path);
    writeFileAtomic(path, bsp::serializeBsp(b));
    ASSERT_EQ(quality::runLight(path, args, 2), 0);
    EXPECT_EQ(readFileBytes(path), one);
}

}  // namespace
}  // namespace q3::light
