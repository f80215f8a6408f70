// The legacy light grid (q3map2 SetupGrid / TraceGrid): layout from model 0 and worldspawn
// "gridsize", one work item per point in parallel, in-solid points moved by a fixed search (not
// random), every occluder counted, and the lump-15 encoding of grid_encode.
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include <algorithm>

#include "grid_encode.h"
#include "light_context.h"
#include "light_text.h"
#include "progress.h"

namespace q3::light {
namespace {

constexpr float kGridEpsilon = 0.0f;       // GRID_EPSILON: first point-in-solid test
constexpr float kNudgedEpsilon = -0.125f;  // VERTEX_EPSILON: test of nudged points

GridOptions gridOptionsFromContext(const LightContext& ctx) {
    GridOptions g;
    g.scale = ctx.options.gridScale;
    g.ambientScale = ctx.options.gridAmbientScale;
    g.directionality = ctx.options.gridDirectionality;
    g.ambientDirectionality = ctx.options.gridAmbientDirectionality;
    g.minLight = ctx.world.minGridLight;
    return g;
}

// For every cluster, the indices (in light order) of the lights that may reach a grid point in it:
// the PVS (and, for suns, sky visibility) test done once per cluster and light instead of once per
// point and light.
std::vector<std::vector<uint32_t>> gridLightsByCluster(const LightContext& ctx) {
    const int numClusters = ctx.tree ? ctx.tree->numClusters() : 0;
    std::vector<std::vector<uint32_t>> byCluster(static_cast<size_t>(std::max(0, numClusters)));
    for (int c = 0; c < numClusters; ++c)
        for (size_t i = 0; i < ctx.lights.size(); ++i) {
            const Light& light = ctx.lights[i];
            if (!light.affectsGrid) continue;
            const bool reachable = light.type == LightType::Sun
                                       ? ctx.skyVisibility.maySeeSky(c, light.skyIndex)
                                       : light.cluster < 0 || ctx.tree->clusterVisible(c, light.cluster);
            if (reachable)
                byCluster[static_cast<size_t>(c)].push_back(static_cast<uint32_t>(i));
        }
    return byCluster;
}

}  // namespace

void lightGrid(LightContext& ctx, Log& log) {
    bsp::Entity* worldspawn = ctx.entities.empty() ? nullptr : &ctx.entities[0];
    const std::string gridSizeValue = worldspawn ? worldspawn->value("gridsize") : std::string();
    const Vec3 requested = parseGridSize(gridSizeValue, ctx.bspPath.string() + ": worldspawn \"gridsize\"");
    const GridLayout layout = computeGridLayout(requested, ctx.bsp);
    if (layout.growSteps > 0)
        log.info(strCat("grid size grown to ", layout.sizeKeyValue(), " to stay within ", kMaxGridPoints, " points"));

    const int numPoints = layout.numPoints();
    const GridOptions gridOptions = gridOptionsFromContext(ctx);
    const LightingEnv env = gridLightingEnv(ctx);
    const float nudgeRadius = 0.5f * maxComponent(layout.size);
    const float nudgeStep = std::max(1.0f, nudgeRadius / 4.0f);
    const bool useTree = ctx.tree && !ctx.bsp.nodes.empty();
    const std::vector<Vec3> nudges = nudgeOffsets(nudgeRadius, nudgeStep);
    const std::vector<std::vector<uint32_t>> lightsByCluster = gridLightsByCluster(ctx);
    std::vector<uint32_t> allLights(ctx.lights.size());
    for (size_t i = 0; i < allLights.size(); ++i) allLights[i] = static_cast<uint32_t>(i);

    std::vector<bsp::GridPoint> points(static_cast<size_t>(std::max(0, numPoints)));
    std::vector<uint8_t> inSolid(points.size(), 0);
    log.info(strCat("light grid: ", layout.bounds[0], " x ", layout.bounds[1], " x ", layout.bounds[2], " = ",
                    numPoints, " points"));
    Progress progress = Progress::forConsole(log, points.size());
    auto body = [&](const tbb::blocked_range<int>& range) {
        progress.advance(range.size());
        std::vector<LightContribution> contributions;
        for (int i = range.begin(); i != range.end(); ++i) {
            Vec3 origin = layout.pointOrigin(i);
            int cluster = -1;
            if (useTree) {
                cluster = ctx.tree->clusterForPointExt(origin, kGridEpsilon);
                if (cluster < 0) {
                    std::optional<Vec3> free = ctx.tree->nudgeOutOfSolid(origin, nudges, kNudgedEpsilon);
                    if (!free) {
                        points[static_cast<size_t>(i)] = bsp::GridPoint{};  // the engine skips all-zero points
                        inSolid[static_cast<size_t>(i)] = 1;
                        continue;
                    }
                    origin = *free;
                    cluster = ctx.tree->clusterForPoint(origin);
                }
            }
            contributions.clear();
            Vec3 total = ctx.world.ambient;
            const std::vector<uint32_t>& candidates =
                cluster >= 0 && static_cast<size_t>(cluster) < lightsByCluster.size()
                    ? lightsByCluster[static_cast<size_t>(cluster)]
                    : allLights;
            for (uint32_t lightIndex : candidates) {
                const Light& light = ctx.lights[lightIndex];
                std::optional<LightContribution> c = lightToGridPoint(light, origin, cluster, env);
                if (!c) continue;
                contributions.push_back(*c);
                total += c->color;
                if (ctx.options.cheapGrid && total.x >= 255 && total.y >= 255 && total.z >= 255) break;
            }
            const GridSample sample = accumulateGridSample(contributions, ctx.world.ambient, gridOptions);
            points[static_cast<size_t>(i)] = encodeGridPoint(sample, gridOptions, ctx.color);
        }
    };
    tbb::task_arena arena(ctx.threads > 0 ? ctx.threads : tbb::task_arena::automatic);
    arena.execute([&] { tbb::parallel_for(tbb::blocked_range<int>(0, std::max(0, numPoints), 64), body); });
    progress.finish();

    ctx.bsp.lightGrid = std::move(points);
    ctx.stats.gridPoints = static_cast<uint64_t>(std::max(0, numPoints));
    for (uint8_t s : inSolid) ctx.stats.gridPointsInSolid += s;
    if (layout.sizeChanged() && worldspawn) worldspawn->set("gridsize", layout.sizeKeyValue());
    log.info(strCat(ctx.stats.gridPointsInSolid, " grid points in solid"));
}

}  // namespace q3::light
