// The legacy light grid (q3map2 SetupGrid / TraceGrid): layout from model 0 and worldspawn
// "gridsize", lit in parallel by blocks of points (lights culled once per block), in-solid points
// moved by q3map2's random nudges (drawn in its single-thread order), every occluder counted, and
// the lump-15 encoding of grid_encode.
#include <algorithm>

#include "grid_blocks.h"
#include "grid_encode.h"
#include "light_context.h"
#include "light_text.h"
#include "progress.h"

namespace q3::light {
namespace {

constexpr int kBlockEdge = 4;              // grid points per block edge (lights culled per block)

GridOptions gridOptionsFromContext(const LightContext& ctx) {
    GridOptions g;
    g.scale = ctx.options.gridScale;
    g.ambientScale = ctx.options.gridAmbientScale;
    g.directionality = ctx.options.gridDirectionality;
    g.ambientDirectionality = ctx.options.gridAmbientDirectionality;
    g.minLight = ctx.world.minGridLight;
    return g;
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
    const LightingEnv env = gridLightingEnv(ctx, layout.size);
    // Points are placed first, one after another in index order, as q3map2's TraceGrid places them
    // on one thread: a point in solid takes the first free one of its random nudges, whose values
    // continue the sequence light creation drew from (placeGridAsTraceGrid). The nudges reach
    // half a cell along each axis at most.
    const float nudgeRadius = length(layout.size * 0.5f);
    const std::vector<std::optional<PlacedGridPoint>> placements = placeGridAsTraceGrid(
        ctx.tree.get(), ctx.bsp, GridLattice{layout.bounds, layout.mins, layout.size}, ctx.random, ctx.threads);
    const std::vector<float> envelopes = lightEnvelopes(ctx.lights, env.settings.forceFast);
    std::vector<bsp::GridPoint> points(static_cast<size_t>(std::max(0, numPoints)));
    std::vector<uint8_t> inSolid(points.size(), 0);
    log.info(strCat("light grid: ", layout.bounds[0], " x ", layout.bounds[1], " x ", layout.bounds[2], " = ",
                    numPoints, " points"));
    Progress progress = Progress::forConsole(log, points.size());
    // One grid point: nudged out of solid (or left all-zero, which the engine skips), then lit by
    // the lights that reach its block, in light order.
    LightingEnv clearEnv = env;
    clearEnv.clearOfSolid = true;
    auto lightPoint = [&](size_t i, Vec3, const BlockLights& reaching) {
        const std::optional<PlacedGridPoint>& placed = placements[i];
        if (!placed) {
            points[i] = bsp::GridPoint{};
            inSolid[i] = 1;
            return;
        }
        const Vec3 origin = placed->origin;
        const int cluster = placed->cluster;
        thread_local std::vector<LightContribution> contributions;
        contributions.clear();
        Vec3 total = ctx.world.ambient;
        for (size_t k = 0; k < reaching.candidates.size(); ++k) {
            const uint32_t lightIndex = reaching.candidates[k];
            const bool clear = !reaching.clearOfSolid.empty() && reaching.clearOfSolid[k];
            std::optional<LightContribution> c =
                lightToGridPoint(ctx.lights[lightIndex], origin, cluster, clear ? clearEnv : env, envelopes[lightIndex]);
            if (!c) continue;
            contributions.push_back(*c);
            total += c->color;
            if (ctx.options.cheapGrid && total.x >= 255 && total.y >= 255 && total.z >= 255) break;
        }
        const GridSample sample = accumulateGridSample(contributions, ctx.world.ambient, gridOptions);
        points[i] = encodeGridPoint(sample, gridOptions, ctx.color);
    };
    // Nudged points move at most nudgeRadius from their lattice position.
    lightGridByBlocks(GridLattice{layout.bounds, layout.mins, layout.size}, ctx.lights, nudgeRadius + 1.0f,
                      env.settings, kBlockEdge, ctx.threads, progress, lightPoint, ctx.tree.get());
    progress.finish();

    ctx.bsp.lightGrid = std::move(points);
    ctx.stats.gridPoints = static_cast<uint64_t>(std::max(0, numPoints));
    for (uint8_t s : inSolid) ctx.stats.gridPointsInSolid += s;
    if (layout.sizeChanged() && worldspawn) worldspawn->set("gridsize", layout.sizeKeyValue());
    log.info(strCat(ctx.stats.gridPointsInSolid, " grid points in solid"));
}

}  // namespace q3::light
