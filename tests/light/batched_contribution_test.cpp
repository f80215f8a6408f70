// The batched light paths (lightToSamples and lightToGridPoints, for point, spot and area lights)
// against the one-sample functions they stand in for: the same contributions, rays and ray order,
// bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <random>

#include "bsp_tree.h"
#include "light_contribution.h"
#include "light_test_util.h"
#include "trace_scene.h"

namespace q3::light {
namespace {

bool sameBits(Vec3 a, Vec3 b) { return std::memcmp(&a, &b, sizeof a) == 0; }

bool sameRay(const ShadowRay& a, const ShadowRay& b) {
    return sameBits(a.from, b.from) && sameBits(a.direction, b.direction) &&
           std::memcmp(&a.tnear, &b.tnear, sizeof a.tnear) == 0 && std::memcmp(&a.tfar, &b.tfar, sizeof a.tfar) == 0 &&
           a.toSky == b.toSky && a.skyIndex == b.skyIndex && a.mask == b.mask && a.clearOfSolid == b.clearOfSolid;
}

// Two clusters that do not see each other (z below 40 and above 60), a structural slab between
// them (a leaf outside every cluster) and a caster quad: every early exit of the one-sample path
// has samples that take it.
struct World {
    bsp::Bsp bsp;
    std::unique_ptr<BspTree> tree;
    std::unique_ptr<TraceScene> scene;
    World() {
        bsp.planes = {{{0, 0, 1}, 40}, {{0, 0, 1}, 60}};
        bsp.nodes = {{0, {1, -1}, {-1000, -1000, -1000}, {1000, 1000, 1000}},
                     {1, {-3, -2}, {-1000, -1000, 40}, {1000, 1000, 1000}}};
        bsp.leafs = {{0, 0, {-1000, -1000, -1000}, {1000, 1000, 40}, 0, 0, 0, 0},
                     {-1, 0, {-1000, -1000, 40}, {1000, 1000, 60}, 0, 0, 0, 0},
                     {1, 0, {-1000, -1000, 60}, {1000, 1000, 1000}, 0, 0, 0, 0}};
        bsp.visibility = {2, 0, 0, 0, 1, 0, 0, 0, 0x1, 0x2};
        tree = std::make_unique<BspTree>(bsp);
        std::vector<SceneSurface> casters{test::quad({-30, -30, 20}, {40, 0, 0}, {0, 40, 0})};
        TraceSceneOptions options;
        const BspTree* t = tree.get();
        options.solidBetween = [t](Vec3 from, Vec3 to) { return t->segmentCrossesSolid(from, to); };
        scene = std::make_unique<TraceScene>(casters, options);
    }
};

std::vector<Light> someLights(std::mt19937& rng) {
    std::uniform_real_distribution<float> coord(-120, 120), z(-100, 30), unit(0, 1);
    std::vector<Light> lights;
    for (int k = 0; k < 24; ++k) {
        Light l;
        l.type = k % 4 == 3 ? LightType::Spot : LightType::Point;
        l.origin = {coord(rng), coord(rng), k % 5 == 4 ? 100.0f : z(rng)};
        l.photons = 300 * 7500.0f * (0.2f + unit(rng));
        l.color = {1, unit(rng), k % 7 == 0 ? 0.0f : 0.5f};
        l.normal = normalize(Vec3{unit(rng) - 0.5f, unit(rng) - 0.5f, -1});
        l.radiusByDist = 0.3f + unit(rng);
        l.linear = k % 6 == 1;
        l.angleAttenuation = k % 5 != 2;
        l.angleScale = k % 8 == 5 ? 0.5f : 0;
        l.extraDist = k % 3 == 0 ? 20.0f : 0;
        l.fast = k % 2 == 0;
        l.falloffTolerance = k % 4 == 0 ? 40.0f : 1.0f;
        l.cluster = l.origin.z > 60 ? 1 : l.origin.z < 40 ? 0 : -1;
        l.style = k % 3;
        lights.push_back(l);
    }
    return lights;
}

// Area lights: emitters facing down and up, one-sided and two-sided, -fast or not.
std::vector<Light> someAreaLights() {
    std::vector<Light> lights;
    for (const float facing : {-1.0f, 1.0f})
        for (const float h : {-10.0f, 25.0f}) {
            std::vector<Light> square = test::squareEmitterLights(4000, 30, h, facing);
            for (Light& l : square) {
                l.twoSided = h > 0;
                l.fast = facing > 0;
                l.cluster = 0;
                lights.push_back(l);
            }
        }
    return lights;
}

TEST(BatchedPointLights, SamplesMatchOneAtATime) {
    World world;
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> coord(-100, 100), z(-60, 30);
    std::vector<std::optional<SamplePoint>> points;
    for (int i = 0; i < 400; ++i) {
        SamplePoint s{{coord(rng), coord(rng), z(rng)}, normalize(Vec3{coord(rng), coord(rng), 150}), 0, i % 9 == 0};
        if (i % 11 == 0) s.normal = {0, 0, -1};  // faces away from most lights
        if (i % 13 == 0) s.cluster = -1;
        if (i % 17 == 0) {  // in the other cluster, which sees no light below the slab
            s.origin.z = 80;
            s.cluster = 1;
        }
        points.push_back(i % 10 == 5 ? std::nullopt : std::optional(s));
    }
    std::vector<uint32_t> which;
    for (uint32_t i = 0; i < points.size(); ++i)
        if (points[i]) which.push_back(i);
    std::vector<Light> lights = someLights(rng);
    for (const Light& l : someAreaLights()) lights.push_back(l);
    for (const float ignoreNear : {0.0f, 1.5f, 40.0f}) {
        LightingEnv env;
        env.scene = world.scene.get();
        env.tree = world.tree.get();
        env.settings.ignoreNear = ignoreNear;
        env.settings.faster = ignoreNear == 1.5f;  // area lights as inverse square
        env.settings.lightAngleHL = ignoreNear == 40.0f;
        env.rayMask = 5;
        for (const Light& base : lights) {
            Light light = base;
            // A spot and a point light on a sample point (zero distance).
            if (&base == &lights[3]) light.origin = points[0]->origin;
            if (&base == &lights[2]) light.origin = points[6]->origin;
            const float envelope = &base == &lights[1] ? 90.0f : 1e9f;
            std::vector<ShadowRay> oneRays, batchRays;
            std::vector<size_t> oneTraced, batchTraced;
            std::vector<Vec3> oneOut(points.size()), oneDirs(points.size()), batchOut(points.size()),
                batchDirs(points.size());
            LightingEnv one = env;
            one.deferredRays = &oneRays;
            for (uint32_t i : which) {
                const size_t before = oneRays.size();
                std::optional<LightContribution> c = lightToSample(light, *points[i], one, envelope);
                if (!c) {
                    oneRays.resize(before);
                    continue;
                }
                oneOut[i] = c->color;
                oneDirs[i] = c->direction;
                if (oneRays.size() > before) oneTraced.push_back(i);
            }
            LightingEnv batch = env;
            batch.deferredRays = &batchRays;
            ASSERT_TRUE(samplesBatchable(light, batch));
            lightToSamples(light, batch, envelope, points, which, batchOut, batchDirs.data(), batchTraced);
            ASSERT_EQ(oneTraced, batchTraced);
            ASSERT_EQ(oneRays.size(), batchRays.size());
            for (size_t k = 0; k < oneRays.size(); ++k) EXPECT_TRUE(sameRay(oneRays[k], batchRays[k])) << k;
            for (uint32_t i : which) {
                EXPECT_TRUE(sameBits(oneOut[i], batchOut[i])) << i;
                EXPECT_TRUE(sameBits(oneDirs[i], batchDirs[i])) << i;
            }
        }
    }
    // The exits are all taken: some samples lit with a ray, some without one (too short), some dark.
    LightingEnv env;
    env.scene = world.scene.get();
    env.settings.ignoreNear = 40;
    std::vector<ShadowRay> rays;
    env.deferredRays = &rays;
    std::vector<size_t> traced;
    std::vector<Vec3> out(points.size());
    lightToSamples(lights[0], env, 1e9f, points, which, out, nullptr, traced);
    size_t lit = 0;
    for (uint32_t i : which) lit += out[i] != Vec3{};
    EXPECT_GT(traced.size(), 0u);
    EXPECT_GT(lit, traced.size());
    EXPECT_LT(lit, which.size());
}

TEST(BatchedPointLights, GridPointsMatchOneAtATime) {
    World world;
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> coord(-100, 100), z(-60, 120);
    std::vector<Vec3> origins;
    std::vector<int> clusters;
    for (int i = 0; i < 300; ++i) {
        origins.push_back({coord(rng), coord(rng), z(rng)});
        clusters.push_back(origins.back().z > 60 ? 1 : origins.back().z < 40 ? (i % 7 == 0 ? -1 : 0) : -1);
    }
    std::vector<Light> lights = someLights(rng);
    for (const Light& l : someAreaLights()) lights.push_back(l);
    for (const int setting : {0, 1, 2}) {
        LightingEnv env;
        env.scene = world.scene.get();
        env.tree = world.tree.get();
        env.settings.ignoreNear = setting > 0 ? 32.0f : 0.0f;
        env.settings.forceFast = setting == 1;
        env.settings.faster = setting == 2;  // area lights as inverse square
        for (const Light& base : lights) {
            Light light = base;
            if (&base == &lights[2]) light.origin = origins[5];
            const float envelope = &base == &lights[1] ? 90.0f : 1e9f;
            std::vector<ShadowRay> oneRays, batchRays;
            std::vector<std::optional<LightContribution>> one(origins.size()), batch(origins.size());
            std::vector<int32_t> oneRayOf(origins.size(), -1), batchRayOf(origins.size(), -1);
            LightingEnv oneEnv = env;
            oneEnv.deferredRays = &oneRays;
            for (size_t p = 0; p < origins.size(); ++p) {
                const size_t before = oneRays.size();
                one[p] = lightToGridPoint(light, origins[p], clusters[p], oneEnv, envelope);
                if (!one[p]) oneRays.resize(before);
                else if (oneRays.size() > before) oneRayOf[p] = int32_t(before);
            }
            LightingEnv batchEnv = env;
            batchEnv.deferredRays = &batchRays;
            ASSERT_TRUE(gridPointsBatchable(light, batchEnv));
            std::vector<uint32_t> all(origins.size());
            for (uint32_t p = 0; p < all.size(); ++p) all[p] = p;
            lightToGridPoints(light, batchEnv, envelope, origins, clusters, all, batch, batchRayOf);
            ASSERT_EQ(oneRayOf, batchRayOf);
            ASSERT_EQ(oneRays.size(), batchRays.size());
            for (size_t k = 0; k < oneRays.size(); ++k) EXPECT_TRUE(sameRay(oneRays[k], batchRays[k])) << k;
            for (size_t p = 0; p < origins.size(); ++p) {
                ASSERT_EQ(one[p].has_value(), batch[p].has_value()) << p;
                if (!one[p]) continue;
                EXPECT_TRUE(sameBits(one[p]->color, batch[p]->color)) << p;
                EXPECT_TRUE(sameBits(one[p]->direction, batch[p]->direction)) << p;
                EXPECT_EQ(one[p]->style, batch[p]->style);
            }
        }
    }
}

// Points on the edges the four-lane path must decide as the one-point functions do: a luxel the
// light grazes (incidence 0.0005, which half-Lambert leaves dark) and points exactly at the
// envelope's distance (dark for luxels, lit for grid points), each in a group of four.
TEST(BatchedPointLights, LanesKeepTheEdgesOfTheOnePointFunctions) {
    World world;
    Light light;
    light.origin = {0, 0, 10};
    light.photons = 300 * 7500.0f;
    light.cluster = 0;
    const std::vector<Vec3> spots = {{1000, 0, 9.5f}, {30, 40, 10}, {0, 10, 10}, {-8, -6, 0}};
    std::vector<std::optional<SamplePoint>> points;
    for (const Vec3 p : spots) points.push_back(SamplePoint{p, {0, 0, 1}, 0, false});
    points[1]->normal = {-0.6f, -0.8f, 0};
    points.push_back(SamplePoint{{5, 5, 0}, {0, 0, 1}, 0, false});
    std::vector<uint32_t> which{0, 1, 2, 3, 4};
    for (const bool halfLambert : {false, true})
        for (const float envelope : {50.0f, 1e9f}) {
            LightingEnv env;
            env.scene = world.scene.get();
            env.tree = world.tree.get();
            env.settings.lightAngleHL = halfLambert;
            std::vector<ShadowRay> rays;
            env.deferredRays = &rays;
            std::vector<Vec3> out(points.size()), expected(points.size());
            std::vector<size_t> traced;
            lightToSamples(light, env, envelope, points, which, out, nullptr, traced);
            for (uint32_t i : which) {
                if (std::optional<LightContribution> c = lightToSample(light, *points[i], env, envelope))
                    expected[i] = c->color;
            }
            for (uint32_t i : which) EXPECT_TRUE(sameBits(expected[i], out[i])) << i << " hl " << halfLambert;
            // Grazed, 1000 units away: lit by Lambert within reach, never by half-Lambert.
            EXPECT_EQ(out[0] == Vec3{}, halfLambert || envelope == 50.0f);
            EXPECT_EQ(out[1] == Vec3{}, envelope == 50.0f);  // at the envelope

            std::vector<Vec3> origins(spots);
            origins.push_back({5, 5, 0});
            std::vector<int> clusters(origins.size(), 0);
            std::vector<std::optional<LightContribution>> grid(origins.size());
            std::vector<int32_t> rayOf(origins.size(), -1);
            lightToGridPoints(light, env, envelope, origins, clusters, which, grid, rayOf);
            for (uint32_t p : which) {
                const std::optional<LightContribution> one = lightToGridPoint(light, origins[p], 0, env, envelope);
                ASSERT_EQ(one.has_value(), grid[p].has_value()) << p;
                if (one) {
                    EXPECT_TRUE(sameBits(one->color, grid[p]->color)) << p;
                }
            }
            EXPECT_TRUE(grid[1].has_value());  // the grid keeps a point at the envelope
        }
}

// The four-lane path of area lights decides the -fast bound as the one-sample path does: with the
// tolerance at the median of the exact contributions, about half of the samples fall below it,
// many of them where the bound alone cannot tell.
TEST(BatchedPointLights, AreaLanesKeepTheFastBound) {
    World world;
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> coord(-300, 300), z(-200, 0), unit(-1, 1);
    std::vector<std::optional<SamplePoint>> points;
    for (int i = 0; i < 800; ++i)
        points.push_back(SamplePoint{{coord(rng), coord(rng), z(rng)},
                                     normalize(Vec3{unit(rng), unit(rng), 1.5f}), 0, i % 5 == 0});
    std::vector<uint32_t> which(points.size());
    for (uint32_t i = 0; i < which.size(); ++i) which[i] = i;
    LightingEnv env;
    env.scene = world.scene.get();
    env.tree = world.tree.get();
    for (Light light : test::squareEmitterLights(4000, 30, 25, -1)) {
        light.cluster = 0;
        light.fast = true;
        light.falloffTolerance = 0;
        std::vector<float> adds;  // before occlusion
        std::vector<ShadowRay> unused;
        LightingEnv unoccluded = env;
        unoccluded.deferredRays = &unused;
        for (const std::optional<SamplePoint>& p : points)
            if (std::optional<LightContribution> c = lightToSample(light, *p, unoccluded, 1e9f))
                adds.push_back(maxComponent(c->color));
        ASSERT_GT(adds.size(), 100u);
        std::nth_element(adds.begin(), adds.begin() + ptrdiff_t(adds.size() / 2), adds.end());
        light.falloffTolerance = adds[adds.size() / 2] / maxComponent(light.color);
        std::vector<ShadowRay> oneRays, batchRays;
        LightingEnv one = env, batch = env;
        one.deferredRays = &oneRays;
        batch.deferredRays = &batchRays;
        std::vector<Vec3> expected(points.size()), out(points.size());
        size_t lit = 0;
        for (uint32_t i : which)
            if (std::optional<LightContribution> c = lightToSample(light, *points[i], one, 1e9f)) {
                expected[i] = c->color;
                ++lit;
            }
        std::vector<size_t> traced;
        lightToSamples(light, batch, 1e9f, points, which, out, nullptr, traced);
        for (uint32_t i : which) ASSERT_TRUE(sameBits(expected[i], out[i])) << i;
        ASSERT_EQ(oneRays.size(), batchRays.size());
        EXPECT_GT(lit, adds.size() / 4);
        EXPECT_LT(lit, adds.size() * 3 / 4);
        // Grid points at the same places (their normal is their direction to the light).
        std::vector<Vec3> origins;
        for (const std::optional<SamplePoint>& p : points) origins.push_back(p->origin);
        std::vector<int> clusters(origins.size(), 0);
        std::vector<std::optional<LightContribution>> grid(origins.size());
        std::vector<int32_t> rayOf(origins.size(), -1);
        lightToGridPoints(light, batch, 1e9f, origins, clusters, which, grid, rayOf);
        size_t gridLit = 0;
        for (uint32_t i : which) {
            const std::optional<LightContribution> c = lightToGridPoint(light, origins[i], 0, one, 1e9f);
            ASSERT_EQ(c.has_value(), grid[i].has_value()) << i;
            if (c) {
                ASSERT_TRUE(sameBits(c->color, grid[i]->color)) << i;
            }
            gridLit += c.has_value();
        }
        EXPECT_GT(gridLit, 0u);
    }
}

TEST(BatchedPointLights, WhichLightsAndEnvironmentsTakeTheBatch) {
    World world;
    std::vector<ShadowRay> rays;
    LightingEnv env;
    env.scene = world.scene.get();
    env.deferredRays = &rays;
    Light l;
    EXPECT_TRUE(samplesBatchable(l, env));
    EXPECT_TRUE(gridPointsBatchable(l, env));
    l.affectsSurfaces = false;
    EXPECT_FALSE(samplesBatchable(l, env));
    EXPECT_TRUE(gridPointsBatchable(l, env));
    l.affectsGrid = false;
    EXPECT_FALSE(gridPointsBatchable(l, env));
    Light sun, area;
    sun.type = LightType::Sun;
    area.type = LightType::Area;
    EXPECT_FALSE(samplesBatchable(sun, env));
    EXPECT_FALSE(gridPointsBatchable(sun, env));
    EXPECT_TRUE(samplesBatchable(area, env));
    EXPECT_TRUE(gridPointsBatchable(area, env));
    Light controlled;
    controlled.controlled = ControlledParams{};
    EXPECT_FALSE(samplesBatchable(controlled, env));
    LightingEnv sunOnly = env;
    sunOnly.settings.sunOnly = true;
    EXPECT_FALSE(samplesBatchable(Light{}, sunOnly));
    LightingEnv immediate = env;
    immediate.deferredRays = nullptr;
    EXPECT_FALSE(samplesBatchable(Light{}, immediate));
    EXPECT_FALSE(gridPointsBatchable(Light{}, immediate));
}

}  // namespace
}  // namespace q3::light
