// The sub-sampling walk (-samples N) on a real map: the first quads lit as one batch before the
// walk give the luxels what the walk's own sub-samples, traced one at a time, give them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <limits>

#include "light_context.h"
#include "light_stage.h"
#include "luxel_subsampling.h"
#include "test_data.h"

namespace q3::light {
namespace {

// A square of sample points facing up, `size` x `size` at `step` units, centred below the light;
// points in solid have none.
std::vector<std::optional<SamplePoint>> pointsBelow(const BspTree& tree, const Light& light, int size, float step,
                                                    float depth) {
    std::vector<std::optional<SamplePoint>> points(size_t(size) * size_t(size));
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const Vec3 p = light.origin + Vec3{(float(x) - 0.5f * float(size)) * step,
                                               (float(y) - 0.5f * float(size)) * step, -depth};
            const int cluster = tree.clusterForPoint(p);
            if (cluster >= 0) points[size_t(y) * size_t(size) + size_t(x)] = SamplePoint{p, {0, 0, 1}, cluster, false};
        }
    return points;
}

TEST(LuxelSubsampling, BatchedFirstQuadsGiveWhatOneByOneGives) {
    const std::filesystem::path maps = test::tempDir() / "maps";
    std::filesystem::create_directories(maps);
    std::filesystem::copy_file(test::realBsp("oacmpdm1"), maps / "oacmpdm1.bsp");
    for (const auto& source : test::oacmpMapSources())  // its lights
        if (source.stem() == "oacmpdm1") std::filesystem::copy_file(source, maps / "oacmpdm1.map");
    CommonOptions common;
    common.mapPath = maps / "oacmpdm1.bsp";
    common.basePaths = {test::openArenaBase().string()};
    common.fsGame = "baseoa";
    common.threads = 2;
    Log log(false);
    LightContext ctx;
    ctx.options.fast = true;
    loadLightInputs(ctx, common, log);
    buildSurfaceGeometry(ctx);
    buildScene(ctx);
    createLights(ctx, log);
    const LightingEnv env = surfaceLightingEnv(ctx);
    const RawLightmap raw;

    constexpr int kSize = 40;
    size_t refined = 0, compared = 0;
    int lightsTried = 0;
    for (const Light& light : ctx.lights) {
        if (light.type != LightType::Point || lightsTried >= 24) continue;
        ++lightsTried;
        const std::vector<std::optional<SamplePoint>> points = pointsBelow(*ctx.tree, light, kSize, 8.0f, 24.0f);
        std::vector<int> clusters;
        for (const auto& p : points)
            if (p) clusters.push_back(p->cluster);
        std::sort(clusters.begin(), clusters.end());
        clusters.erase(std::unique(clusters.begin(), clusters.end()), clusters.end());
        const LuxelSampler sampler{ctx, env, raw, Vec3{}, false, clusters};
        std::vector<Vec3> centre(points.size());
        LuxelRect lit;
        for (size_t i = 0; i < points.size(); ++i) {
            if (!points[i]) continue;
            centre[i] = sampler.lightAt(light, *points[i]);
            if (!(centre[i] == Vec3{})) lit.add(int(i % kSize), int(i / kSize));
        }
        const std::vector<uint8_t> darkFlags = darkFlagsOf(points);
        for (const int maxSamples : {2, 3}) {
            std::vector<Vec3> batched = centre, single = centre;
            std::vector<int> samplesA(points.size(), 1), samplesB(points.size(), 1);
            LuxelRect litA = lit, litB = lit;
            LuxelSampler::Scratch scratch;
            refineEdges(sampler, light, points, kSize, kSize, maxSamples, batched, samplesA, litA, darkFlags, scratch, 1);
            refineEdges(sampler, light, points, kSize, kSize, maxSamples, single, samplesB, litB, darkFlags, scratch,
                        std::numeric_limits<size_t>::max());
            for (size_t i = 0; i < points.size(); ++i) {
                refined += !(batched[i] == centre[i]);
                ++compared;
                EXPECT_EQ(std::memcmp(&batched[i], &single[i], sizeof(Vec3)), 0)
                    << "light at " << light.origin.x << " " << light.origin.y << " " << light.origin.z << ", luxel " << i
                    << ", -samples " << maxSamples;
            }
            EXPECT_EQ(samplesA, samplesB);
        }
    }
    EXPECT_EQ(lightsTried, 24);
    // Enough shadow edges to mean something: the walk changed this many luxels.
    EXPECT_GT(refined, 500u) << "of " << compared;
}

}  // namespace
}  // namespace q3::light
