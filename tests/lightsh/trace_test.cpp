// TraceGridSH on scenes built in the test: analytic point-light values, two-sided colour that the
// legacy grid cannot hold, area lights against a brute-force sum, suns through sky, ambient and the
// minlight floor, points in solid, thread-count independence, and the BSP attachment.
#include <gtest/gtest.h>

#include <oneapi/tbb/global_control.h>

#include <cmath>
#include <cstring>
#include <random>
#include <type_traits>

#include "../light/light_test_util.h"
#include "grid_encode.h"
#include "grid_sh.h"
#include "grid_sh_corners.h"
#include "progress.h"
#include "light_context.h"
#include "sh_grid_runtime.h"

namespace q3::light {
namespace {

using sh::Vec3d;

std::unique_ptr<LightContext> makeContext(Vec3 mins, Vec3 maxs, float cell) {
    auto ctx = std::make_unique<LightContext>();
    bsp::Model world{};
    mins.toArray(world.mins);
    maxs.toArray(world.maxs);
    ctx->bsp.models.push_back(world);
    ctx->entities.push_back(test::entity({{"classname", "worldspawn"}}));
    ctx->bspPath = "maps/trace.bsp";
    ctx->options.gridSizeSH[0] = ctx->options.gridSizeSH[1] = ctx->options.gridSizeSH[2] = cell;
    ctx->threads = 1;
    return ctx;
}

Light pointLight(Vec3 origin, float intensity, Vec3 color = {1, 1, 1}) {
    Light l;
    l.type = LightType::Point;
    l.origin = origin;
    l.photons = intensity * 7500.0f;
    l.color = color;
    return l;
}

sh::SH9Color pointSH(const sh::GridSH& grid, size_t i) { return sh::fromGridPoint(grid.points[i]); }

std::vector<Vec3d> randomNormals(int count, uint32_t seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> n(0, 1);
    std::vector<Vec3d> out;
    while (int(out.size()) < count) {
        Vec3d v{n(rng), n(rng), n(rng)};
        const double len = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
        if (len < 1e-6) continue;
        out.push_back({v.x / len, v.y / len, v.z / len});
    }
    return out;
}

double dotd(Vec3d a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

TEST(ShTrace, PointLightMatchesLegacyContribution) {
    auto ctx = makeContext({-64, -64, -64}, {64, 64, 64}, 32);
    ctx->lights.push_back(pointLight({10, 20, 5}, 300, {1, 0.5f, 0.25f}));
    test::CapturingLog log;
    const ShGridLayout layout = setupGridSH(*ctx, log.log);
    ShTraceStats stats;
    const sh::GridSH grid = traceGridSH(*ctx, layout, log.log, &stats).decode();
    ASSERT_EQ(grid.points.size(), 125u);
    EXPECT_EQ(stats.blackAfterFill, 0u);
    const LightingEnv env = gridLightingEnv(*ctx, layout.size);
    const std::vector<Vec3d> normals = randomNormals(200, 7);
    for (int i = 0; i < 125; ++i) {
        const Vec3 origin = layout.pointOrigin(i % 5, (i / 5) % 5, i / 25);
        const std::optional<LightContribution> c = lightToGridPoint(ctx->lights[0], origin, -1, env);
        ASSERT_TRUE(c);
        const sh::SH9Color value = pointSH(grid, size_t(i));
        // Towards the light: the L2 clamped cosine at n = l is 0.09375 + 0.5 + 0.46875 = 1.0625.
        const sh::Rgb atLight = sh::evalIrradiance(value, {c->direction.x, c->direction.y, c->direction.z});
        EXPECT_NEAR(atLight.r, 1.0625 * c->color.x / 255.0, 1e-4 * (1 + c->color.x / 255.0));
        EXPECT_NEAR(atLight.g, 1.0625 * c->color.y / 255.0, 1e-4 * (1 + c->color.y / 255.0));
        // Any normal: within the L2 truncation bound of the true max(0, n.l) C.
        for (const Vec3d& n : normals) {
            const double truth = std::max(0.0, dotd(n, c->direction)) * c->color.x / 255.0;
            EXPECT_NEAR(sh::evalIrradiance(value, n).r, truth, 0.0938 * c->color.x / 255.0 + 1e-5);
        }
    }
}

TEST(ShTrace, RedAndBlueOnOppositeSidesLegacyCannot) {
    auto ctx = makeContext({0, 0, 0}, {0, 0, 0}, 8);  // one point at the origin
    ctx->lights.push_back(pointLight({0, -100, 0}, 400, {1, 0, 0}));
    ctx->lights.push_back(pointLight({0, 100, 0}, 250, {0, 0, 1}));
    test::CapturingLog log;
    const sh::GridSH grid = traceGridSH(*ctx, setupGridSH(*ctx, log.log), log.log).decode();
    ASSERT_EQ(grid.points.size(), 1u);
    const sh::SH9Color value = pointSH(grid, 0);
    const sh::Rgb minusY = sh::evalIrradianceClamped(value, {0, -1, 0});
    const sh::Rgb plusY = sh::evalIrradianceClamped(value, {0, 1, 0});
    const double red = 400 * 7500.0 / (100 * 100) / 255.0, blue = 250 * 7500.0 / (100 * 100) / 255.0;
    EXPECT_GT(minusY.r, 5 * minusY.b);
    EXPECT_GT(plusY.b, 5 * plusY.r);
    EXPECT_NEAR(minusY.r, red, 0.0938 * (red + blue));
    EXPECT_NEAR(plusY.b, blue, 0.0938 * (red + blue));

    // The legacy grid keeps one direction: the weaker light, opposite to it, only reaches the
    // ambient part at a quarter of its strength.
    const LightingEnv env = gridLightingEnv(*ctx, kDefaultGridSize);
    std::vector<LightContribution> contributions;
    gatherGridLight(ctx->lights, {0, 0, 0}, -1, env, contributions);
    const GridSample legacy = accumulateGridSample(contributions, {}, GridOptions{});
    auto legacyAt = [&](Vec3 n) {
        return (legacy.ambient + legacy.directed * std::max(0.0f, dot(n, legacy.direction))) / 255.0f;
    };
    EXPECT_LT(legacyAt({0, 1, 0}).z, 0.3 * blue);
    EXPECT_GT(plusY.b, 0.9 * blue);
}

// Brute-force SH of a square emitter cut into many small pieces (no occlusion).
sh::SH9Color bruteForceArea(const Light& light, Vec3 corner, Vec3 edgeU, Vec3 edgeV, Vec3 point, int steps) {
    sh::SH9Color acc;
    const double radiance = light.add / sh::kPi / 255.0;
    const float cellArea = length(cross(edgeU, edgeV)) / float(steps * steps);
    for (int i = 0; i < steps; ++i)
        for (int j = 0; j < steps; ++j) {
            const Vec3 p = corner + edgeU * ((i + 0.5f) / steps) + edgeV * ((j + 0.5f) / steps);
            const Vec3 toPiece = p - point;
            const float r = length(toPiece);
            const Vec3 dir = toPiece / r;
            const double omega = cellArea * std::abs(dot(dir, light.normal)) / (r * r);
            sh::addDirectionalIrradiance(acc, {dir.x, dir.y, dir.z},
                                         {light.color.x * radiance * omega, light.color.y * radiance * omega,
                                          light.color.z * radiance * omega});
        }
    return acc;
}

// A 96 x 96 emitter (corner {-48, -48, 0}, edges kEmitterU / kEmitterV) in the plane z = 0 facing
// up, its origin nudged off the plane as surface lights are.
const Vec3 kEmitterCorner{-48, -48, 0}, kEmitterU{96, 0, 0}, kEmitterV{0, 96, 0};
Light squareEmitter() {
    const Vec3 corner = kEmitterCorner, edgeU = kEmitterU, edgeV = kEmitterV;
    Light area;
    area.type = LightType::Area;
    area.normal = {0, 0, 1};
    area.winding = {corner, corner + edgeV, corner + edgeU + edgeV, corner + edgeU};
    area.origin = Vec3{0, 0, 0} + area.normal;
    area.planeDist = dot(area.origin, area.normal);
    area.add = 3000;
    area.photons = 1;
    return area;
}

TEST(ShTrace, AreaLightSampledOverItsSurface) {
    // The square emitter seen from close by and off to the side.
    const Vec3 corner = kEmitterCorner, edgeU = kEmitterU, edgeV = kEmitterV;
    Light area = squareEmitter();
    area.color = {1, 0.9f, 0.8f};
    const LightingEnv env;
    const std::vector<Vec3d> normals = randomNormals(300, 11);
    for (const Vec3 point : {Vec3{30, 10, 40}, Vec3{0, 0, 24}, Vec3{-70, 20, 30}}) {
        const sh::SH9Color truth = bruteForceArea(area, corner, edgeU, edgeV, point, 400);
        sh::SH9Color sampled, single;
        ASSERT_TRUE(addLightToGridPointSH(sampled, area, point, -1, env));
        ASSERT_TRUE(addLightToGridPointSH(single, area, point, -1, env, true));
        double peak = 0, errSampled = 0, errSingle = 0;
        for (const Vec3d& n : normals) {
            const double t = sh::evalIrradiance(truth, n).r;
            peak = std::max(peak, t);
            errSampled = std::max(errSampled, std::abs(sh::evalIrradiance(sampled, n).r - t));
            errSingle = std::max(errSingle, std::abs(sh::evalIrradiance(single, n).r - t));
        }
        ASSERT_GT(peak, 0.1);
        // Integrated exactly over the emitter: only the fine sum's own error remains.
        EXPECT_LT(errSampled, 0.002 * peak) << "point " << point.x << " " << point.y << " " << point.z;
        EXPECT_LT(errSampled, 0.1 * errSingle) << "the whole emitter must beat one sample";
        // The uniform band is the emitter's whole solid angle.
        EXPECT_NEAR(sampled.c[0][0], truth.c[0][0], 0.001 * truth.c[0][0]);
    }
}

// The pieces of a close emitter are shadowed together by the legacy grid's one ray: the SH grid sees
// the light exactly when the legacy grid does, and a blocker cannot hide only some pieces.
TEST(ShTrace, AreaLightPiecesShareTheLegacyShadowRay) {
    const Light area = squareEmitter();
    const Vec3 point{0, 0, 40};
    sh::SH9Color open;
    ASSERT_TRUE(addLightToGridPointSH(open, area, point, -1, LightingEnv{}));

    // A small plate on the centre ray hides the emitter from both grids.
    std::vector<SceneSurface> plate{test::quad({-4, -4, 20}, {8, 0, 0}, {0, 8, 0})};
    TraceScene blocked(plate, {});
    LightingEnv env;
    env.scene = &blocked;
    sh::SH9Color hidden;
    EXPECT_FALSE(addLightToGridPointSH(hidden, area, point, -1, env));
    EXPECT_FALSE(lightToGridPoint(area, point, -1, env));
    EXPECT_EQ(hidden.c[0][0], 0.0);

    // A plate over one corner of the emitter leaves the centre ray free: the whole emitter counts.
    std::vector<SceneSurface> side{test::quad({20, 20, 20}, {30, 0, 0}, {0, 30, 0})};
    TraceScene partial(side, {});
    env.scene = &partial;
    sh::SH9Color seen;
    ASSERT_TRUE(addLightToGridPointSH(seen, area, point, -1, env));
    for (int k = 0; k < 9; ++k) EXPECT_DOUBLE_EQ(seen.c[k][0], open.c[k][0]);
}

// One probe's lights with their rays traced as one batch give what they give one by one: the
// blocked light drops out, styled light stays out, the others add in light order.
// Two point lights, a yellow emitter and a styled light over a small plate at z = 20.
struct PlateAndLights {
    TraceScene blocked{{test::quad({-4, -4, 20}, {8, 0, 0}, {0, 8, 0})}, {}};
    std::vector<Light> lights{pointLight({0, 0, 0}, 300, {1, 0, 0}), pointLight({90, 10, 60}, 200, {0, 1, 0}),
                              squareEmitter(), pointLight({-50, 30, 80}, 250, {0, 0, 1})};
    PlateAndLights() {
        lights[2].color = {1, 1, 0};
        lights[3].style = 1;
    }
};

TEST(ShTrace, BatchedLightsEqualOneByOne) {
    PlateAndLights setup;
    LightingEnv env;
    env.scene = &setup.blocked;
    const std::vector<Light>& lights = setup.lights;
    const Vec3 point{0, 0, 40};  // the plate hides the first light and the emitter's centre
    sh::SH9Color oneByOne, batched;
    int reached = 0;
    for (const Light& l : lights)
        if (l.style == 0 && addLightToGridPointSH(oneByOne, l, point, -1, env)) ++reached;
    EXPECT_EQ(reached, 1);
    const std::vector<uint32_t> all{0, 1, 2, 3};
    addLightsToGridPointSH(batched, lights, all, point, -1, env);
    for (int k = 0; k < sh::kCoeffCount; ++k)
        for (int ch = 0; ch < 3; ++ch) EXPECT_EQ(batched.c[k][ch], oneByOne.c[k][ch]) << k << " " << ch;
    EXPECT_GT(batched.c[0][1], 0.0);
    EXPECT_EQ(batched.c[0][0], 0.0);
    EXPECT_EQ(batched.c[0][2], 0.0);
}

// A block of probes traced together, with envelopes given and one light marked clear of solid,
// gives every probe what it gets alone.
TEST(ShTrace, BlockOfProbesEqualsEachProbeAlone) {
    PlateAndLights setup;
    LightingEnv env;
    env.scene = &setup.blocked;
    const std::vector<Light>& lights = setup.lights;
    const std::vector<uint32_t> all{0, 1, 2, 3};
    const std::vector<uint8_t> clear{0, 1, 0, 0};
    const std::vector<float> envelopes = lightEnvelopes(lights, env.settings.forceFast);
    const std::vector<Vec3> origins{{0, 0, 40}, {30, -20, 35}, {-10, 5, 60}, {2, 2, 25}};
    const std::vector<int> clusters(origins.size(), -1);
    std::vector<sh::SH9Color> block(origins.size());
    addLightsToGridPointsSH(block, lights, all, clear, envelopes, origins, clusters, env);
    int lit = 0;
    for (size_t p = 0; p < origins.size(); ++p) {
        sh::SH9Color alone;
        addLightsToGridPointSH(alone, lights, all, origins[p], -1, env);
        for (int k = 0; k < sh::kCoeffCount; ++k)
            for (int ch = 0; ch < 3; ++ch) EXPECT_EQ(block[p].c[k][ch], alone.c[k][ch]) << p << " " << k << " " << ch;
        lit += alone.c[0][0] + alone.c[0][1] + alone.c[0][2] > 0 ? 1 : 0;
    }
    EXPECT_GE(lit, 2);
    EXPECT_NE(block[0].c[0][0], block[1].c[0][0]);  // the probes do not all see the same lights
}

// A 9 x 9 x 5 lattice 32 32 64 apart (corners every 4, 4 and 2 points: eight blocks) lit with
// shared corners; `worst` gets each region's largest difference from every point lit alone,
// relative to the point's own coefficient 0 (x < 128: the blocks next to the origin along x).
struct SharedLatticeRun {
    uint64_t pairs = 0;
    double worstNear = 0, worstFar = 0;  // points with x < 128, x >= 128
    std::vector<sh::SH9Color> light;
    std::vector<Vec3> origins;
};

SharedLatticeRun traceSharedLattice(const std::vector<Light>& lights, const TraceScene& scene, int threads = 1) {
    const GridLattice grid{{9, 9, 5}, {0, 0, 0}, {32, 32, 64}};
    const size_t count = 9 * 9 * 5;
    LightingEnv env;
    env.scene = &scene;
    const std::vector<float> envelopes = lightEnvelopes(lights, false);
    const std::vector<uint8_t> leftOut(lights.size(), 0);
    SharedLatticeRun run;
    run.light.assign(count, sh::SH9Color{});
    run.origins.assign(count, Vec3{});
    std::vector<int> placed(count, 0), stored(count, 0);
    const ShPointSink sink{[&](size_t i, Vec3 at) {
                               ++placed[i];
                               run.origins[i] = at;
                               return std::optional<PlacedGridPoint>(PlacedGridPoint{at, -1, false});
                           },
                           [&](size_t i, sh::SH9Color& acc) {
                               ++stored[i];
                               run.light[i] = acc;
                           }};
    Progress progress(count, ProgressMode::Silent, [](std::string_view) {});
    run.pairs = traceGridSHSharedCorners(grid, lights, leftOut, envelopes, env, 1.0f, nullptr, threads, progress, sink);
    std::vector<uint32_t> all;
    for (uint32_t i = 0; i < lights.size(); ++i) all.push_back(i);
    for (size_t i = 0; i < count; ++i) {
        EXPECT_EQ(placed[i], 1) << i;
        EXPECT_EQ(stored[i], 1) << i;
        sh::SH9Color alone;
        addLightsToGridPointSH(alone, lights, all, run.origins[i], -1, env);
        double& worst = run.origins[i].x < 128 ? run.worstNear : run.worstFar;
        for (int k = 0; k < sh::kCoeffCount; ++k)
            for (int ch = 0; ch < 3; ++ch)
                worst = std::max(worst, std::fabs(run.light[i].c[k][ch] - alone.c[k][ch]) /
                                            std::max(1e-9, std::fabs(alone.c[0][ch])));
    }
    return run;
}

// Far lights are lit at the shared corners and interpolated between them; near lights, and far
// ones whose corners disagree, are lit at every point as without sharing.
TEST(ShTrace, SharedCornersFollowEveryPointAlone) {
    constexpr uint64_t kBetweenCorners = 9 * 9 * 5 - 3 * 3 * 3;
    const TraceScene empty{{}, {}};
    // 2000 units away: shared everywhere, within 1 % of every point's own light.
    const SharedLatticeRun far = traceSharedLattice({pointLight({2000, 300, 500}, 4.0e7f, {1, 0.5f, 0.25f})}, empty);
    EXPECT_EQ(far.pairs, kBetweenCorners);
    EXPECT_LE(std::max(far.worstNear, far.worstFar), 0.01);
    // Inside the lattice: near every block, lit at every point, exactly.
    const SharedLatticeRun inside = traceSharedLattice({pointLight({100, 120, 100}, 3000, {1, 1, 1})}, empty);
    EXPECT_EQ(inside.pairs, 0u);
    EXPECT_EQ(std::max(inside.worstNear, inside.worstFar), 0.0);
    // A wall at x = 48 hides the light from the corners at x = 0: the blocks next to them light
    // every point themselves (exactly, black behind the wall); the others share.
    const TraceScene wall{{test::quad({48, -1000, -1000}, {0, 2000, 0}, {0, 0, 2000})}, {}};
    const SharedLatticeRun split = traceSharedLattice({pointLight({2000, 50, 100}, 4.0e7f, {1, 1, 1})}, wall);
    EXPECT_GT(split.pairs, 0u);
    EXPECT_LT(split.pairs, kBetweenCorners);
    EXPECT_EQ(split.worstNear, 0.0);
    EXPECT_LE(split.worstFar, 0.01);
    for (size_t i = 0; i < split.light.size(); ++i) {
        if (split.origins[i].x < 48) {
            EXPECT_EQ(split.light[i].c[0][0], 0.0) << i;
        }
    }
    // The wall between the light and every point: blocked at every corner, shared, black.
    const TraceScene farWall{{test::quad({500, -1000, -1000}, {0, 2000, 0}, {0, 0, 2000})}, {}};
    const SharedLatticeRun dark = traceSharedLattice({pointLight({2000, 50, 100}, 4.0e7f, {1, 1, 1})}, farWall);
    EXPECT_EQ(dark.pairs, kBetweenCorners);
    EXPECT_EQ(std::max(dark.worstNear, dark.worstFar), 0.0);
    // The thread count changes nothing.
    const SharedLatticeRun twoThreads = traceSharedLattice({pointLight({2000, 50, 100}, 4.0e7f, {1, 1, 1})}, wall, 2);
    for (size_t i = 0; i < split.light.size(); ++i)
        for (int k = 0; k < sh::kCoeffCount; ++k)
            for (int ch = 0; ch < 3; ++ch) EXPECT_EQ(twoThreads.light[i].c[k][ch], split.light[i].c[k][ch]);
}

struct SkyScene {
    LightingShader skyShader;
    std::vector<SceneSurface> surfaces;
    SkyScene() {
        skyShader.sky = true;
        surfaces.push_back(test::quad({-4096, -4096, 1000}, {8192, 0, 0}, {0, 8192, 0}, &skyShader, 0));
        surfaces.push_back(test::quad({-200, 0, 500}, {400, 0, 0}, {0, 400, 0}));  // roof over y > 0
    }
};

TEST(ShTrace, SunThroughSkyAndJitteredSamples) {
    SkyScene sky;
    auto ctx = makeContext({-64, -128, 0}, {64, 128, 0}, 64);  // points at y = -128 .. 128
    ctx->scene = std::make_unique<TraceScene>(sky.surfaces, TraceSceneOptions{});
    // Two samples of one sun (what _deviance/_samples produce): each is its own light.
    for (Vec3 dir : {normalize(Vec3{0.05f, 0, 1}), normalize(Vec3{-0.05f, 0, 1})}) {
        Light sun;
        sun.type = LightType::Sun;
        sun.normal = dir;
        sun.photons = 100;
        sun.skyIndex = 0;
        ctx->lights.push_back(sun);
    }
    test::CapturingLog log;
    const ShGridLayout layout = setupGridSH(*ctx, log.log);
    ASSERT_EQ(layout.bounds, (std::array<int, 3>{3, 5, 1}));
    const sh::GridSH grid = traceGridSH(*ctx, layout, log.log).decode();
    for (int y = 0; y < 5; ++y) {
        const sh::SH9Color v = pointSH(grid, size_t(1 + 3 * y));
        const double up = sh::evalIrradiance(v, {0, 0, 1}).r;
        if (layout.pointOrigin(1, y, 0).y < 0) {
            sh::SH9Color expected;
            for (const Light& sun : ctx->lights)
                sh::addDirectionalIrradiance(expected, {sun.normal.x, sun.normal.y, sun.normal.z},
                                             {100 / 255.0, 100 / 255.0, 100 / 255.0});
            for (int k = 0; k < 9; ++k) EXPECT_NEAR(v.c[k][0], expected.c[k][0], 1e-5) << "coefficient " << k;
            EXPECT_NEAR(up, 2 * 1.0625 * 100 / 255.0, 0.01);
        } else {
            EXPECT_EQ(up, 0.0) << "under the roof, y = " << layout.pointOrigin(1, y, 0).y;
        }
    }
}

TEST(ShTrace, AmbientIsExactAndMinlightIsAFloor) {
    auto ctx = makeContext({0, 0, 0}, {64, 0, 0}, 32);
    ctx->world.ambient = {30, 60, 90};
    test::CapturingLog log;
    const ShGridLayout layout = setupGridSH(*ctx, log.log);
    const sh::GridSH grid = traceGridSH(*ctx, layout, log.log).decode();
    for (size_t i = 0; i < grid.points.size(); ++i)
        for (const Vec3d& n : randomNormals(50, 3)) {
            const sh::Rgb v = sh::evalIrradiance(pointSH(grid, i), n);
            EXPECT_NEAR(v.r, 30 / 255.0, 1e-6);
            EXPECT_NEAR(v.g, 60 / 255.0, 1e-6);
            EXPECT_NEAR(v.b, 90 / 255.0, 1e-6);
        }
    // Floor 50: red and green rise to it, blue (90) stays; the lit directional part is untouched.
    ctx->world.minGridLight = {50, 50, 50};
    ctx->lights.push_back(pointLight({200, 0, 0}, 100));
    const sh::GridSH floored = traceGridSH(*ctx, layout, log.log).decode();
    const sh::SH9Color v = pointSH(floored, 0);
    const double y0 = sh::evalBasis({0, 0, 1})[0];
    // The light adds C * pi * Y0 to coefficient 0, i.e. C / 4 to the uniform part (C = 18.75 at 200 units).
    const double lightUniform = 0.25 * 100 * 7500.0 / (200.0 * 200.0);
    EXPECT_NEAR(v.c[0][0] * y0, 50 / 255.0, 1e-6);                          // 30 + 4.7 < 50: raised
    EXPECT_NEAR(v.c[0][1] * y0, (60 + lightUniform) / 255.0, 1e-6);         // above the floor: as is
    EXPECT_NEAR(v.c[0][2] * y0, (90 + lightUniform) / 255.0, 1e-6);
    ctx->world.minGridLight = {};
    const sh::SH9Color unfloored = pointSH(traceGridSH(*ctx, layout, log.log).decode(), 0);
    for (int k = 1; k < 9; ++k) EXPECT_EQ(v.c[k][0], unfloored.c[k][0]) << "the floor only touches coefficient 0";
    ctx->world.minGridLight = {50, 50, 50};
    sh::SH9Color manual;
    applyAmbientAndFloor(manual, {30, 60, 90}, {50, 50, 50});
    EXPECT_NEAR(manual.c[0][0] * y0, 50 / 255.0, 1e-9);
    EXPECT_NEAR(manual.c[0][1] * y0, 60 / 255.0, 1e-9);
    EXPECT_NEAR(manual.c[0][2] * y0, 90 / 255.0, 1e-9);
    // -gridscale scales the whole point.
    ctx->options.gridScale = 2;
    const sh::GridSH doubled = traceGridSH(*ctx, layout, log.log).decode();
    EXPECT_NEAR(doubled.points[1].coeffs[3][0], 2 * floored.points[1].coeffs[3][0], 1e-6);
}

// World split by the plane x = 64: x < 64 is outside the world (solid), x > 64 one open cluster.
void addHalfSolidTree(bsp::Bsp& b) {
    b.planes.push_back(bsp::Plane{{1, 0, 0}, 64});
    bsp::Node node{};
    node.planeNum = 0;
    node.children[0] = -1;  // leaf 0
    node.children[1] = -2;  // leaf 1
    b.nodes.push_back(node);
    bsp::Leaf open{}, solid{};
    open.cluster = 0;
    solid.cluster = -1;
    b.leafs.push_back(open);
    b.leafs.push_back(solid);
}

std::unique_ptr<LightContext> halfSolidContext() {
    auto ctx = makeContext({0, 0, 0}, {256, 64, 64}, 16);
    addHalfSolidTree(ctx->bsp);
    ctx->tree = std::make_unique<BspTree>(ctx->bsp);
    ctx->lights.push_back(pointLight({200, 30, 40}, 200, {1, 0.7f, 0.4f}));
    ctx->lights.push_back(pointLight({120, 10, 10}, 80, {0.2f, 0.4f, 1}));
    ctx->world.ambient = {3, 3, 3};
    return ctx;
}

TEST(ShTrace, PointsInSolidAreNudgedOrFilled) {
    auto ctx = halfSolidContext();
    test::CapturingLog log;
    const ShGridLayout layout = setupGridSH(*ctx, log.log);
    ShTraceStats stats;
    const sh::GridSH grid = traceGridSH(*ctx, layout, log.log, &stats).decode();
    // x = 0..48 are deeper than half a cell (8) into the solid side; x = 64 lies on the plane.
    const uint64_t perColumn = uint64_t(layout.bounds[1]) * layout.bounds[2];
    EXPECT_EQ(stats.inSolid, 4 * perColumn);
    EXPECT_EQ(stats.filled, stats.inSolid);
    EXPECT_EQ(stats.blackBeforeFill, stats.inSolid);
    EXPECT_EQ(stats.blackAfterFill, 0u);
    // A filled point next to the open side takes the average of its set neighbours (only x + 1 is
    // set among them), so it equals that neighbour.
    const int bx = layout.bounds[0], by = layout.bounds[1];
    for (int z = 0; z < layout.bounds[2]; ++z)
        for (int y = 0; y < by; ++y) {
            const size_t filled = size_t(3 + y * bx + z * bx * by), free = filled + 1;
            EXPECT_EQ(std::memcmp(&grid.points[filled], &grid.points[free], sizeof(sh::GridPointSH)), 0);
        }
}

sh::GridLumpImage zeroImage(int32_t bx, int32_t by, int32_t bz) {
    const float mins[3] = {0, 0, 0}, size[3] = {8, 8, 8};
    const int32_t bounds[3] = {bx, by, bz};
    return sh::GridLumpImage(mins, size, bounds);
}

void setCoeff(sh::GridLumpImage& image, size_t i, int k, int ch, float v) {
    sh::GridPointSH p = image.point(i);
    p.coeffs[k][ch] = v;
    image.setPoint(i, p);
}

TEST(ShTrace, NeighbourFillAveragesAndSpreads) {
    sh::GridLumpImage points = zeroImage(6, 1, 1);
    std::vector<uint8_t> unset = {0, 1, 1, 1, 1, 0};
    setCoeff(points, 0, 0, 0, 1);
    setCoeff(points, 5, 0, 0, 3);
    EXPECT_EQ(fillFromNeighbours(points, unset), 4u);
    const float expected[6] = {1, 1, 1, 3, 3, 3};
    for (int i = 0; i < 6; ++i) EXPECT_EQ(points.point(size_t(i)).coeffs[0][0], expected[i]) << i;
    // 2 x 2: the corner opposite the only set point gets the average of the two filled first.
    sh::GridLumpImage square = zeroImage(2, 2, 1);
    std::vector<uint8_t> unsetSquare = {0, 1, 1, 1};
    setCoeff(square, 0, 4, 2, 2);
    EXPECT_EQ(fillFromNeighbours(square, unsetSquare), 3u);
    EXPECT_EQ(square.point(3).coeffs[4][2], 2.0f);
    // Nothing set anywhere: everything stays zero.
    sh::GridLumpImage none = zeroImage(2, 2, 2);
    std::vector<uint8_t> all(8, 1);
    EXPECT_EQ(fillFromNeighbours(none, all), 0u);
    EXPECT_EQ(none.bytes(), zeroImage(2, 2, 2).bytes());
}

TEST(ShTrace, SameBytesWithOneAndTwoThreads) {
    auto ctx = halfSolidContext();
    for (int i = 0; i < 6; ++i)
        ctx->lights.push_back(pointLight({80.0f + 25 * i, 5.0f * i, 60.0f - 7 * i}, 50.0f + 10 * i));
    test::CapturingLog log;
    const ShGridLayout layout = setupGridSH(*ctx, log.log);
    std::vector<uint8_t> first, second;
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
        ctx->threads = 1;
        first = traceGridSH(*ctx, layout, log.log).release();
    }
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
        ctx->threads = 2;
        second = traceGridSH(*ctx, layout, log.log).release();
    }
    EXPECT_EQ(first, second);
}

TEST(ShTrace, ManyLightsStayWithinTheTruncationBounds) {
    // 64 coloured lights spread over a sphere (Fibonacci lattice) around one grid point.
    auto ctx = makeContext({0, 0, 0}, {0, 0, 0}, 8);
    const double golden = sh::kPi * (3.0 - std::sqrt(5.0));
    for (int i = 0; i < 64; ++i) {
        const double z = 1.0 - (i + 0.5) * 2.0 / 64.0, r = std::sqrt(1 - z * z), a = golden * i;
        const Vec3 dir{float(r * std::cos(a)), float(r * std::sin(a)), float(z)};
        const Vec3 color{0.5f + 0.5f * dir.x * dir.x, 0.6f, 0.4f + 0.6f * float(i % 3) / 2};
        ctx->lights.push_back(pointLight(dir * (150.0f + float(i % 5) * 20), 40, color));
    }
    test::CapturingLog log;
    const ShGridLayout layout = setupGridSH(*ctx, log.log);
    const sh::GridSH grid = traceGridSH(*ctx, layout, log.log).decode();
    const sh::SH9Color value = pointSH(grid, 0);
    const LightingEnv env = gridLightingEnv(*ctx, layout.size);
    std::vector<LightContribution> contributions;
    gatherGridLight(ctx->lights, {0, 0, 0}, -1, env, contributions);
    ASSERT_EQ(contributions.size(), 64u);
    double sumAbs = 0;
    for (const LightContribution& c : contributions) sumAbs += c.color.x / 255.0;
    double errSum = 0, truthSum = 0, maxErr = 0;
    for (const Vec3d& n : randomNormals(2000, 5)) {
        double truth = 0;
        for (const LightContribution& c : contributions) truth += std::max(0.0, dotd(n, c.direction)) * c.color.x / 255.0;
        const double err = std::abs(sh::evalIrradiance(value, n).r - truth);
        maxErr = std::max(maxErr, err);
        errSum += err;
        truthSum += truth;
    }
    EXPECT_LE(maxErr, 0.0938 * sumAbs + 1e-6);
    EXPECT_LE(errSum / 2000, 0.0230 * sumAbs + 1e-6);
    EXPECT_LT(errSum / truthSum, 0.03) << "mean relative error of a smooth environment";
}

TEST(ShTrace, ControlledLightsUseTheirIncidenceProjection) {
    Light l = pointLight({0, 0, 100}, 1, {1, 0.5f, 0.5f});
    ControlledParams p;
    p.dotProductWeight = 0.3f;
    p.falloffEnd = 400;
    l.controlled = p;
    const LightingEnv env;
    const Vec3 point{30, -20, 0};
    const std::optional<LightContribution> c = lightToGridPoint(l, point, -1, env);
    ASSERT_TRUE(c);
    sh::SH9Color value;
    ASSERT_TRUE(addLightToGridPointSH(value, l, point, -1, env));
    const sh::Rgb k{c->color.x / 255.0, c->color.y / 255.0, c->color.z / 255.0};
    const Vec3d dir{c->direction.x, c->direction.y, c->direction.z};
    const sh::SH9Color expected = sh::projectControlledIncidence(dir, k, 0.3);
    for (int i = 0; i < 9; ++i)
        for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(value.c[i][ch], expected.c[i][ch], 1e-6) << i;
    // Not the clamped cosine: with w < 1 the side facing the light is flatter.
    const sh::SH9Color cosine = sh::projectDirectionalIrradiance(dir, k);
    EXPECT_GT(std::abs(value.c[0][0] - cosine.c[0][0]), 0.1 * cosine.c[0][0]);
    // Suns of the controlled model force w = 1: the plain directional projection.
    Light sun;
    sun.type = LightType::Sun;
    sun.normal = normalize(Vec3{1, 1, 2});
    ControlledParams sunParams;
    sunParams.dotProductWeight = 0.2f;
    sun.controlled = sunParams;
    sh::SH9Color sunValue;
    ASSERT_TRUE(addLightToGridPointSH(sunValue, sun, point, -1, env));
    const sh::SH9Color sunExpected = sh::projectDirectionalIrradiance({sun.normal.x, sun.normal.y, sun.normal.z},
                                                                      {1, 1, 1});
    for (int i = 0; i < 9; ++i) EXPECT_NEAR(sunValue.c[i][0], sunExpected.c[i][0], 1e-6) << i;
}

TEST(ShTrace, StyledAndGridlessLightsStayOut) {
    auto ctx = makeContext({0, 0, 0}, {64, 0, 0}, 32);
    ctx->world.ambient = {10, 10, 10};
    Light styled = pointLight({32, 0, 50}, 300);
    styled.style = 1;  // switchable light: not in the IBSP grids
    Light gridless = pointLight({32, 0, -50}, 300);
    gridless.affectsGrid = false;  // spawnflags 16
    ctx->lights = {styled, gridless};
    test::CapturingLog log;
    const sh::GridSH grid = traceGridSH(*ctx, setupGridSH(*ctx, log.log), log.log).decode();
    sh::SH9Color ambientOnly;
    applyAmbientAndFloor(ambientOnly, {10, 10, 10}, {});
    const sh::GridPointSH expected = sh::toGridPoint(ambientOnly);
    for (const sh::GridPointSH& p : grid.points) EXPECT_EQ(std::memcmp(&p, &expected, sizeof(p)), 0);
    ctx->lights[0].style = 0;
    const sh::GridSH lit = traceGridSH(*ctx, setupGridSH(*ctx, log.log), log.log).decode();
    EXPECT_GT(lit.points[1].coeffs[2][0], 0.1f);  // from above once it is style 0
}

TEST(ShTrace, AttachAsLump18OrBspx) {
    sh::GridSH grid;
    grid.size[0] = grid.size[1] = grid.size[2] = 32;
    grid.bounds[0] = 2;
    grid.bounds[1] = grid.bounds[2] = 1;
    grid.points.assign(2, sh::GridPointSH{});
    grid.points[1].coeffs[0][1] = 0.5f;
    bsp::Bsp b;
    b.models.push_back(bsp::Model{});
    b.entities = std::string("{\n\"classname\" \"worldspawn\"\n}\n") + '\0';
    attachGridSH(b, sh::GridLumpImage::encode(grid), false);
    EXPECT_EQ(b.version, 47);
    EXPECT_EQ(b.headerLumps, 19);
    EXPECT_EQ(b.shGrid, sh::encodeGridLump(grid));
    EXPECT_TRUE(b.lump17.empty());
    const std::vector<uint8_t> v47 = bsp::serializeBsp(b);
    int32_t lump17[2];
    std::memcpy(lump17, v47.data() + 8 + 17 * 8, 8);
    EXPECT_EQ(lump17[0], 0);
    EXPECT_EQ(lump17[1], 0);

    attachGridSH(b, sh::GridLumpImage::encode(grid), true);
    EXPECT_EQ(b.version, 46);
    EXPECT_EQ(b.headerLumps, 17);
    EXPECT_TRUE(b.shGrid.empty());
    ASSERT_NE(b.findBspx(sh::kBspxLumpName), nullptr);
    const std::vector<uint8_t> v46 = bsp::serializeBsp(b);
    sh::GridRuntime runtime;
    ASSERT_EQ(runtime.loadFromBsp(v46.data(), v46.size(), "x"), "");
    EXPECT_EQ(runtime.source(), sh::GridSource::Bspx);
    EXPECT_EQ(runtime.grid().points[1].coeffs[0][1], 0.5f);
}

// The grid is held once: the lump image the tracer fills is the buffer the BSP writes. It cannot
// be copied, attachGridSH takes it only as an rvalue, and the bytes it hands over are the very
// buffer that was filled (moved, not copied) for lump 18 and for the BSPX lump alike.
TEST(ShTrace, AttachMovesTheLumpImageIntoTheBsp) {
    static_assert(!std::is_copy_constructible_v<sh::GridLumpImage>);
    static_assert(!std::is_copy_assignable_v<sh::GridLumpImage>);
    static_assert(std::is_same_v<decltype(&attachGridSH), void (*)(bsp::Bsp&, sh::GridLumpImage&&, bool)>);
    static_assert(std::is_same_v<decltype(&traceGridSH),
                                 sh::GridLumpImage (*)(const LightContext&, const ShGridLayout&, Log&, ShTraceStats*)>);
    for (const bool bspx : {false, true}) {
        sh::GridLumpImage image = zeroImage(3, 2, 2);
        setCoeff(image, 7, 2, 1, 0.25f);
        const std::vector<uint8_t> expected = image.bytes();
        const uint8_t* buffer = image.bytes().data();
        bsp::Bsp b;
        attachGridSH(b, std::move(image), bspx);
        const std::vector<uint8_t>& stored = bspx ? b.findBspx(sh::kBspxLumpName)->data : b.shGrid;
        EXPECT_EQ(stored.data(), buffer) << "bspx " << bspx;
        EXPECT_EQ(stored, expected);
        EXPECT_EQ(image.numPoints(), 0u);
        EXPECT_TRUE(image.bytes().empty());
    }
}

}  // namespace
}  // namespace q3::light
