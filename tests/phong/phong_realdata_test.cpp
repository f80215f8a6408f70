// Phong shading on real OpenArena maps: the step runs in linear time on maps of ~100k vertices,
// gives the same normals twice, smooths only what the rules allow and leaves the BSP untouched.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>

#include "light_context.h"
#include "phong.h"
#include "phong_reference.h"
#include "test_data.h"

namespace q3::light {
namespace {

std::filesystem::path largestRealBsp() {
    const std::vector<std::filesystem::path> all = test::allRealBsps();
    EXPECT_FALSE(all.empty());
    if (all.empty()) return {};
    return *std::max_element(all.begin(), all.end(), [](const auto& a, const auto& b) {
        return std::filesystem::file_size(a) < std::filesystem::file_size(b);
    });
}

// World positions of every draw vertex (brush model origins applied).
std::vector<Vec3> worldPositions(const LightContext& ctx) {
    std::vector<Vec3> p(ctx.bsp.drawVerts.size());
    for (size_t v = 0; v < p.size(); ++v) p[v] = Vec3::fromArray(ctx.bsp.drawVerts[v].xyz);
    for (size_t s = 0; s < ctx.bsp.surfaces.size(); ++s)
        for (int v = 0; v < ctx.bsp.surfaces[s].numVerts; ++v) {
            const size_t i = static_cast<size_t>(ctx.bsp.surfaces[s].firstVert + v);
            p[i] = Vec3::fromArray(ctx.bsp.drawVerts[i].xyz) + ctx.surfaceOffsets[s];
        }
    return p;
}

// q3map2's grouping loop with candidates found by sweeping x-sorted vertices, every surface at
// the -shadeangle default (the maps' shaders are not loaded here), soups excluded.
std::vector<Vec3> sweepReference(const LightContext& ctx) {
    const std::vector<Vec3> p = worldPositions(ctx);
    std::vector<Vec3> n(p.size());
    std::vector<float> radians(p.size(), 0.0f);
    const float worldAngle = entityShadeAngle(ctx.entities[0]);
    for (size_t v = 0; v < p.size(); ++v) n[v] = Vec3::fromArray(ctx.bsp.drawVerts[v].normal);
    for (size_t s = 0; s < ctx.bsp.surfaces.size(); ++s) {
        const bsp::Surface& surface = ctx.bsp.surfaces[s];
        const float degrees = worldAngle > 0 ? worldAngle : ctx.options.shadeAngle;
        for (int v = 0; v < surface.numVerts; ++v)
            radians[static_cast<size_t>(surface.firstVert + v)] =
                surface.surfaceType == bsp::MST_TRIANGLE_SOUP ? 0.0f : degToRad(degrees);
    }
    std::vector<size_t> order(p.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return p[a].x < p[b].x || (p[a].x == p[b].x && a < b); });
    std::vector<size_t> rank(p.size());
    for (size_t k = 0; k < order.size(); ++k) rank[order[k]] = k;

    std::vector<Vec3> out = n;
    std::vector<bool> done(p.size(), false);
    for (size_t i = 0; i < p.size(); ++i) {
        if (done[i] || radians[i] <= 0) continue;
        std::vector<size_t> near;
        for (size_t k = rank[i]; k-- > 0 && p[i].x - p[order[k]].x < 0.01f;) near.push_back(order[k]);
        for (size_t k = rank[i]; k < order.size() && p[order[k]].x - p[i].x < 0.01f; ++k) near.push_back(order[k]);
        std::sort(near.begin(), near.end());
        referenceSmoothGroup(i, near, p, n, radians, done, out);
    }
    return out;
}

void checkMap(const std::filesystem::path& path) {
    SCOPED_TRACE(path.string());
    LightContext ctx;
    ctx.bsp = bsp::readBsp(path);
    ctx.entities = bsp::parseEntities(ctx.bsp.entities, path.string());
    const std::vector<bsp::DrawVert> stored = ctx.bsp.drawVerts;
    buildSurfaceGeometry(ctx);
    ctx.options.shade = true;
    ctx.options.shadeAngle = 60;
    Log log(false);

    const auto start = std::chrono::steady_clock::now();
    smoothNormals(ctx, log);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ASSERT_EQ(ctx.shadedNormals.size(), ctx.bsp.drawVerts.size());
    EXPECT_LT(seconds, 5.0) << ctx.bsp.drawVerts.size() << " vertexes";

    const std::vector<Vec3> first = ctx.shadedNormals;
    smoothNormals(ctx, log);
    EXPECT_EQ(ctx.shadedNormals, first);

    // The same rules with another spatial index (a sweep over x-sorted vertices) as the oracle.
    const std::vector<Vec3> reference = sweepReference(ctx);
    size_t changed = 0;
    for (size_t s = 0; s < ctx.bsp.surfaces.size(); ++s) {
        const bsp::Surface& surface = ctx.bsp.surfaces[s];
        for (int v = 0; v < surface.numVerts; ++v) {
            const size_t i = static_cast<size_t>(surface.firstVert + v);
            ASSERT_EQ(first[i], reference[i]) << "vertex " << i;
            const Vec3 own = Vec3::fromArray(ctx.bsp.drawVerts[i].normal);
            if (first[i] == own) continue;
            ++changed;
            EXPECT_NE(surface.surfaceType, bsp::MST_TRIANGLE_SOUP) << "vertex " << i;
            EXPECT_NEAR(length(first[i]), 1.0f, 1e-5f) << "vertex " << i;
        }
    }
    EXPECT_GT(changed, 100u);
    for (size_t i = 0; i < stored.size(); ++i)
        ASSERT_EQ(std::memcmp(&stored[i], &ctx.bsp.drawVerts[i], sizeof(bsp::DrawVert)), 0) << "vertex " << i;
}

TEST(PhongRealData, SmallDeathmatchMap) { checkMap(test::realBsp("oacmpdm1")); }

TEST(PhongRealData, LargestShippedMap) { checkMap(largestRealBsp()); }

}  // namespace
}  // namespace q3::light
