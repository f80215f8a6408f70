// The light cache on hand-built maps: occlusion by the pillar of a box room (and the exact edge of
// its shadow along a path), what blocks light and what does not, suns and sky, PVS culling,
// ranking with its tie-break, the contract for lights already in the SH grid, and the projection
// of the lights beyond the local ones into the probe.
#include <gtest/gtest.h>

#include <cmath>

#include "light_cache.h"
#include "light_cache_test_bsp.h"
#include "sh_test_support.h"

namespace q3::sh {
namespace {

using test::TestMap;

LightCache load(const TestMap& map) {
    const std::vector<uint8_t> bsp = test::buildTestBsp(map);
    LightCache cache;
    const std::string error = cache.loadFromBsp(bsp.data(), bsp.size(), "test.bsp");
    EXPECT_EQ(error, "");
    return cache;
}

LightCacheResult queryAt(const LightCache& cache, float x, float y, float z, int maxLocal = kMaxLocalLights) {
    const float p[3] = {x, y, z};
    return cache.query(p, maxLocal);
}

WorldLight sun(float dx, float dy, float dz) {
    WorldLight l;
    l.type = WorldLightType::Sun;
    l.falloff = WorldLightFalloff::Parallel;
    const float len = std::sqrt(dx * dx + dy * dy + dz * dz);
    l.direction = {dx / len, dy / len, dz / len};
    l.intensity = {0.5f, 0.5f, 0.5f};
    l.cluster = -1;
    return l;
}

TEST(LightCacheTrace, ThePillarHidesTheLightFromBehind) {
    const LightCache cache = load(test::roomWithPillar());
    ASSERT_EQ(cache.lights().size(), 1u);
    const LightCacheResult behind = queryAt(cache, 200, 0, 64);
    EXPECT_EQ(behind.localCount, 0);
    EXPECT_EQ(behind.occludedCount, 1u);
    EXPECT_EQ(behind.cluster, 0);

    const LightCacheResult inView = queryAt(cache, 200, 200, 64);
    ASSERT_EQ(inView.localCount, 1);
    EXPECT_EQ(inView.local[0].index, 0u);
    EXPECT_EQ(inView.occludedCount, 0u);
    EXPECT_EQ(inView.local[0].arriving, worldLightArriving(cache.lights()[0], {200, 200, 64}));
    // 40000 / (400^2 + 200^2 + 64^2)
    EXPECT_NEAR(inView.local[0].arriving[0], 40000.0 / (160000 + 40000 + 4096), 1e-6);
}

// Walking along x = 200 from y = -150 to 150 the light disappears behind the pillar and comes back.
// The segment to the light (-200, 0, 128) is nearest the pillar's far edge at x = -32, where it is
// |y| * 168 / 400 from the axis; it is blocked while that is within the pillar's 32 units (plus
// the 0.125 clip epsilon): |y| <= 76.49.
TEST(LightCacheTrace, TheShadowEdgeAlongAPathIsWhereTheGeometrySaysIt) {
    const LightCache cache = load(test::roomWithPillar());
    int steps = 0;
    bool previous = true;
    for (int y = -150; y <= 150; ++y) {
        const bool lit = queryAt(cache, 200, float(y), 64).localCount == 1;
        EXPECT_EQ(lit, std::abs(y) >= 77) << "y " << y;
        steps += lit != previous;
        previous = lit;
    }
    EXPECT_EQ(steps, 2);
}

TEST(LightCacheTrace, OnlySolidOpaqueBrushesBlock) {
    for (int32_t shader : {test::kShaderWater, test::kShaderGlass, test::kShaderSky}) {
        TestMap map = test::roomWithPillar();
        map.boxes.back().shader = shader;
        const LightCache cache = load(map);
        // Sky brushes are solid for point lights; water and glass let light through.
        EXPECT_EQ(queryAt(cache, 200, 0, 64).localCount, shader == test::kShaderSky ? 0 : 1) << shader;
    }
}

TEST(LightCacheTrace, SunsReachThroughSkyOrOutOfTheWorld) {
    TestMap map = test::roomWithPillar();
    map.lights = {sun(0, 0.6f, 0.8f)};
    const float open[3] = {-200, -200, 64};     // the ray leaves through the ceiling at y = -56
    const float shaded[3] = {0, -100, 64};      // the ray meets the pillar's -y face at z = 154.7
    {
        const LightCache solidCeiling = load(map);
        EXPECT_FALSE(solidCeiling.reaches(solidCeiling.lights()[0], open));
        EXPECT_EQ(solidCeiling.query(open).localCount, 0);
    }
    map.boxes[1].shader = test::kShaderSky;
    {
        const LightCache skyCeiling = load(map);
        EXPECT_TRUE(skyCeiling.reaches(skyCeiling.lights()[0], open));
        const LightCacheResult r = skyCeiling.query(open);
        ASSERT_EQ(r.localCount, 1);
        EXPECT_EQ(r.local[0].arriving, map.lights[0].intensity);
        EXPECT_FALSE(skyCeiling.reaches(skyCeiling.lights()[0], shaded));
    }
    map.boxes.erase(map.boxes.begin() + 1);  // no ceiling: the ray leaves the world
    const LightCache roofless = load(map);
    EXPECT_TRUE(roofless.reaches(roofless.lights()[0], open));
    EXPECT_FALSE(roofless.reaches(roofless.lights()[0], shaded));
}

TEST(LightCacheTrace, APointInsideABrushStillSeesOut) {
    const LightCache cache = load(test::roomWithPillar());
    EXPECT_EQ(queryAt(cache, 200, 200, -4).localCount, 1);  // sunk 4 units into the floor
}

// Two clusters split at x = 0 that cannot see each other.
TestMap twoClusterRoom(bool seeEachOther) {
    TestMap map = test::roomWithPillar();
    map.numClusters = 2;
    map.cluster = [](const float*, const float maxs[3]) { return maxs[0] <= 0 ? 0 : 1; };
    map.visible = [seeEachOther](int32_t from, int32_t to) { return seeEachOther || from == to; };
    return map;
}

TEST(LightCachePvs, LightsInClustersNotSeenAreNeverTraced) {
    TestMap map = twoClusterRoom(false);
    map.lights.push_back(sun(0, 0.6f, 0.8f));
    map.boxes.erase(map.boxes.begin() + 1);  // roofless, so the sun reaches the floor
    const LightCache hidden = load(map);
    const LightCacheResult r = queryAt(hidden, 200, -200, 64);
    EXPECT_EQ(r.cluster, 1);
    ASSERT_EQ(r.localCount, 1);  // the sun: never culled by clusters
    EXPECT_EQ(r.local[0].index, 1u);
    EXPECT_EQ(r.occludedCount, 0u);
    EXPECT_EQ(r.projectedCount, 0u);
    EXPECT_EQ(queryAt(hidden, -200, -200, 64).localCount, 2);  // in the light's own cluster

    const LightCache seen = load(twoClusterRoom(true));
    EXPECT_EQ(queryAt(seen, 200, 200, 64).localCount, 1);
}

TEST(LightCachePvs, UnknownClustersAreNotCulled) {
    TestMap map = twoClusterRoom(false);
    map.lights[0].cluster = -1;  // a light in solid
    EXPECT_EQ(queryAt(load(map), 200, 200, 64).localCount, 1);
}

// Seven lights exactly 100 units from (100, 200, 64) (integer offsets, so equal strengths tie
// bit for bit), all in view of it, of strengths 2, 8, 5, 8, 1, 5, 3 there.
TestMap rankedLights() {
    TestMap map = test::roomWithPillar();
    map.lights.clear();
    const float offsets[7][3] = {{60, -80, 0}, {80, -60, 0}, {100, 0, 0}, {-80, -60, 0},
                                 {0, -100, 0}, {-100, 0, 0}, {0, 0, 100}};
    const float strengths[7] = {2, 8, 5, 8, 1, 5, 3};
    for (int i = 0; i < 7; ++i)
        map.lights.push_back(test::testPointLight(100 + offsets[i][0], 200 + offsets[i][1], 64 + offsets[i][2],
                                                  strengths[i] * 10000));
    return map;
}

TEST(LightCacheRanking, StrongestFourWithTiesInRecordOrder) {
    const TestMap map = rankedLights();
    const LightCache cache = load(map);
    const LightCacheResult r = queryAt(cache, 100, 200, 64);
    ASSERT_EQ(r.localCount, 4);
    const uint32_t expected[4] = {1, 3, 2, 5};  // 8, 8 (tie: index 1 first), 5, 5 (tie: 2 first)
    for (int i = 0; i < 4; ++i) {
        EXPECT_EQ(r.local[i].index, expected[i]) << i;
        EXPECT_NEAR(r.local[i].arriving[0], map.lights[expected[i]].intensity[0] / 10000, 1e-4);
    }
    EXPECT_EQ(r.projectedCount, 3u);

    // Fewer local slots: the same order, cut short; everything else goes to the probe.
    const LightCacheResult two = queryAt(cache, 100, 200, 64, 2);
    ASSERT_EQ(two.localCount, 2);
    EXPECT_EQ(two.local[0].index, 1u);
    EXPECT_EQ(two.local[1].index, 3u);
    EXPECT_EQ(two.projectedCount, 5u);

    // An occluded light gives its slot to the next one: the pillar now hides light 1.
    TestMap blocked = map;
    blocked.lights[1].origin = {-100, -100, 64};        // the segment crosses the pillar at (-20, 20)
    blocked.lights[1].intensity = {1e7f, 1e7f, 1e7f};  // 77 there: the strongest by far, but hidden
    const float from[3] = {100, 200, 64};
    const LightCache withHidden = load(blocked);
    ASSERT_FALSE(withHidden.reaches(withHidden.lights()[1], from));
    const LightCacheResult h = withHidden.query(from);
    ASSERT_EQ(h.localCount, 4);
    EXPECT_EQ(h.occludedCount, 1u);
    const uint32_t next[4] = {3, 2, 5, 6};
    for (int i = 0; i < 4; ++i) EXPECT_EQ(h.local[i].index, next[i]) << i;
    EXPECT_EQ(h.projectedCount, 2u);
}

TEST(LightCacheGridContract, LightsAlreadyInTheGridAreNeitherLocalNorProjected) {
    TestMap map = rankedLights();
    map.lights[1].flags = kWorldLightInShGrid;
    map.lights[4].flags = kWorldLightInShGrid;
    const LightCache cache = load(map);
    const LightCacheResult r = queryAt(cache, 100, 200, 64);
    ASSERT_EQ(r.localCount, 4);
    const uint32_t expected[4] = {3, 2, 5, 6};
    for (int i = 0; i < 4; ++i) EXPECT_EQ(r.local[i].index, expected[i]) << i;
    EXPECT_EQ(r.projectedCount, 1u);  // light 0 only: 4 is in the grid

    // With every light in the grid the probe is the grid sample unchanged.
    for (WorldLight& l : map.lights) l.flags = kWorldLightInShGrid;
    GridSH grid;
    grid.mins[0] = grid.mins[1] = grid.mins[2] = -256;
    grid.size[0] = grid.size[1] = grid.size[2] = 512;
    grid.bounds[0] = grid.bounds[1] = grid.bounds[2] = 2;
    for (int i = 0; i < 8; ++i) grid.points.push_back(toGridPoint(projectAmbient({0.25 * i, 0.5, 1})));
    map.grid = grid;
    const LightCache allInGrid = load(map);
    const float p[3] = {100, 200, 64};
    const LightCacheResult g = allInGrid.query(p);
    EXPECT_EQ(g.localCount, 0);
    EXPECT_EQ(g.projectedCount, 0u);
    const GridPointSH sample = allInGrid.grid().sample(p);
    for (int i = 0; i < kCoeffCount; ++i)
        for (int c = 0; c < 3; ++c) EXPECT_EQ(g.probe.coeffs[i][c], sample.coeffs[i][c]);
}

// The probe gains exactly the SH projection of the projected lights' evaluateWorldLight over all
// normals (numerical projection over 8192 normals; the two differ by the quadrature of the kink
// at each light's terminator only: within 0.2% of the arriving light).
TEST(LightCacheProjection, TheRestIsTheProjectionOfEvaluateWorldLight) {
    TestMap map = rankedLights();
    WorldLight controlled = test::testPointLight(150, 150, 100, 0);
    controlled.falloff = WorldLightFalloff::Controlled;
    controlled.intensity = {0.3f, 0.2f, 0.1f};
    controlled.falloffConstants = {16, 400, 0.5f, 0};
    controlled.incidenceWeight = 0.4f;
    controlled.radius = 400;
    map.lights.push_back(controlled);
    WorldLight spot = test::testPointLight(100, 100, 200, 30000);
    spot.type = WorldLightType::Spot;
    spot.direction = {0, 0.6f, -0.8f};
    spot.cone = {0.6f, 32, 0, 0};
    map.lights.push_back(spot);
    map.lights.push_back(sun(0.3f, 0.4f, 0.866f));
    map.boxes.erase(map.boxes.begin() + 1);  // roofless
    GridSH grid;
    grid.size[0] = grid.size[1] = grid.size[2] = 1024;
    grid.bounds[0] = grid.bounds[1] = grid.bounds[2] = 1;
    grid.points.push_back(toGridPoint(projectDirectionalIrradiance({0, 0, 1}, {0.1, 0.2, 0.3})));
    map.grid = grid;
    const LightCache cache = load(map);
    const std::array<float, 3> p{100, 200, 64};
    const LightCacheResult r = cache.query(p.data(), 1);
    ASSERT_EQ(r.localCount, 1);
    // Every light is traced: those the boxes hide reach neither the local set nor the probe.
    uint32_t reaching = 0;
    for (const WorldLight& light : cache.lights()) reaching += cache.reaches(light, p.data()) ? 1 : 0;
    ASSERT_LT(reaching, map.lights.size());
    ASSERT_GE(reaching, 3u);
    ASSERT_EQ(r.projectedCount, reaching - 1);
    ASSERT_EQ(r.occludedCount, map.lights.size() - reaching);

    const std::vector<Vec3d> normals = test::fibonacciSphere(8192);
    const double weight = 4 * kPi / double(normals.size());
    double projected[kCoeffCount][3] = {};
    double scale[3] = {};
    for (uint32_t li = 0; li < map.lights.size(); ++li) {
        const WorldLight& light = cache.lights()[li];
        if (li == r.local[0].index || !cache.reaches(light, p.data())) continue;
        const auto arriving = worldLightArriving(light, p);
        for (int c = 0; c < 3; ++c) scale[c] += std::fabs(arriving[size_t(c)]);
        for (const Vec3d& n : normals) {
            const auto e = evaluateWorldLight(light, p, {float(n.x), float(n.y), float(n.z)});
            const Basis y = evalBasis(n);
            for (int i = 0; i < kCoeffCount; ++i)
                for (int c = 0; c < 3; ++c) projected[i][c] += e[size_t(c)] * y[size_t(i)] * weight;
        }
    }
    const GridPointSH sample = cache.grid().sample(p.data());
    for (int i = 0; i < kCoeffCount; ++i)
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(r.probe.coeffs[i][c] - sample.coeffs[i][c], projected[i][c], 0.002 * scale[c] + 1e-6)
                << "coefficient " << i << " channel " << c;
    EXPECT_GT(scale[0], 0.1);
}

TEST(LightCacheLoad, AMapWithoutWorldLightsOrGridAnswersWithNothing) {
    TestMap map = test::roomWithPillar();
    map.lights.clear();
    const LightCache cache = load(map);
    EXPECT_TRUE(cache.lights().empty());
    EXPECT_EQ(cache.grid().source(), GridSource::None);
    const LightCacheResult r = queryAt(cache, 0, 100, 64);
    EXPECT_EQ(r.localCount, 0);
    EXPECT_EQ(r.cluster, 0);
    for (int i = 0; i < kCoeffCount; ++i) EXPECT_EQ(r.probe.coeffs[i][0], 0);
}

TEST(LightCacheLoad, NonFinitePositionsGetNoLights) {
    const LightCache cache = load(test::roomWithPillar());
    const LightCacheResult r = queryAt(cache, std::nanf(""), 0, 0);
    EXPECT_EQ(r.localCount, 0);
    EXPECT_EQ(r.leaf, -1);
    EXPECT_EQ(queryAt(cache, INFINITY, 0, 0).localCount, 0);
}

}  // namespace
}  // namespace q3::sh
